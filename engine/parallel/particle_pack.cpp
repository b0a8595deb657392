#include "engine/parallel/particle_pack.hpp"

#include <type_traits>

namespace drumlab {

void pack_particle(const Particles& p, std::size_t i, std::uint64_t slot,
                   const std::array<Vec3, kWallParts>& wall, std::vector<std::byte>& out) {
  p.for_each_array([&](std::string_view, const auto& values) { put_bytes(out, values[i]); });
  put_bytes(out, slot);
  for (const Vec3& h : wall) put_bytes(out, h);
}

std::uint64_t unpack_particle(std::span<const std::byte> in, std::size_t& pos, Particles& p,
                              WallHistory& wall) {
  p.for_each_array([&](std::string_view, auto& values) {
    using T = typename std::decay_t<decltype(values)>::value_type;
    values.push_back(get_bytes<T>(in, pos));
  });
  const auto slot = get_bytes<std::uint64_t>(in, pos);
  std::array<Vec3, kWallParts> w;
  for (Vec3& h : w) h = get_bytes<Vec3>(in, pos);
  wall.push_back(w);
  return slot;
}

std::size_t packed_size(const Particles& p) {
  std::size_t n = sizeof(std::uint64_t) + kWallParts * sizeof(Vec3);
  p.for_each_array([&](std::string_view, const auto& values) {
    n += sizeof(typename std::decay_t<decltype(values)>::value_type);
  });
  return n;
}

std::uint64_t packed_slot(std::span<const std::byte> record) {
  std::size_t pos = record.size() - sizeof(std::uint64_t) - kWallParts * sizeof(Vec3);
  return get_bytes<std::uint64_t>(record, pos);
}

Vec3 packed_position(std::span<const std::byte> record) {
  std::size_t pos = 0;  // for_each_array visits `position` first
  return get_bytes<Vec3>(record, pos);
}

double packed_radius(std::span<const std::byte> record) {
  // for_each_array visits position, velocity, omega, force, torque, then `radius`
  std::size_t pos = 5 * sizeof(Vec3);
  return get_bytes<double>(record, pos);
}

Particles empty_like(const Particles& p) {
  Particles q;
  for (const ParticleArray& a : p.extra) q.extra.push_back({a.name, {}, a.initial});
  return q;
}

void ContactRecords::add(std::uint64_t sa, std::uint64_t sb, const Vec3& h,
                         std::span<const double> st) {
  a.push_back(sa);
  b.push_back(sb);
  history.push_back(h);
  state.insert(state.end(), st.begin(), st.end());
}

void ContactRecords::pack(std::size_t k, std::vector<std::byte>& out) const {
  put_bytes(out, a[k]);
  put_bytes(out, b[k]);
  put_bytes(out, history[k]);
  for (std::size_t c = 0; c < state_size; ++c) put_bytes(out, state[k * state_size + c]);
}

void ContactRecords::unpack(std::span<const std::byte> in, std::size_t& pos) {
  a.push_back(get_bytes<std::uint64_t>(in, pos));
  b.push_back(get_bytes<std::uint64_t>(in, pos));
  history.push_back(get_bytes<Vec3>(in, pos));
  for (std::size_t c = 0; c < state_size; ++c) state.push_back(get_bytes<double>(in, pos));
}

}  // namespace drumlab
