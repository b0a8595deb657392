#include "engine/parallel/start_message.hpp"

#include <cstring>
#include <string>

namespace drumlab {
namespace {

/// Appends v's bytes (as put_bytes does; resize and copy, which GCC 12's -Wstringop-overflow and
/// -Warray-bounds do not misread here as vector::insert on a new vector).
template <class T>
void append(std::vector<std::byte>& out, const T& v) {
  const std::size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &v, sizeof(T));
}

/// Appends n bytes.
void append_bytes(std::vector<std::byte>& out, const void* bytes, std::size_t n) {
  const std::size_t at = out.size();
  out.resize(at + n);
  if (n > 0) std::memcpy(out.data() + at, bytes, n);
}

void put_string(std::vector<std::byte>& out, const std::string& s) {
  append(out, static_cast<std::uint64_t>(s.size()));
  append_bytes(out, s.data(), s.size());
}

std::string get_string(std::span<const std::byte> in, std::size_t& pos) {
  const auto n = static_cast<std::size_t>(get_bytes<std::uint64_t>(in, pos));
  std::string s(reinterpret_cast<const char*>(in.data() + pos), n);
  pos += n;
  return s;
}

void put_box(std::vector<std::byte>& out, const Box& b) {
  append(out, b.lo);
  append(out, b.hi);
}

Box get_box(std::span<const std::byte> in, std::size_t& pos) {
  Box b;
  b.lo = get_bytes<Vec3>(in, pos);
  b.hi = get_bytes<Vec3>(in, pos);
  return b;
}

}  // namespace

std::vector<std::byte> pack_start_header(const SimulationState& full, const Decomposition& d) {
  std::vector<std::byte> out;
  for (const double v : {full.time, full.dt, full.drum_omega, full.drum_angle, full.carrier_angle,
                         full.carrier_omega}) {
    append(out, v);
  }
  append(out, full.steps);
  put_string(out, full.search_method);
  append(out, static_cast<std::uint64_t>(full.contact_state_size));
  append(out, static_cast<std::uint64_t>(full.particles.extra.size()));
  for (const ParticleArray& a : full.particles.extra) {
    put_string(out, a.name);
    append(out, a.initial);
  }
  append(out, static_cast<std::uint64_t>(full.particles.size()));
  append(out, full.particles.max_radius());
  append(out, static_cast<std::uint64_t>(d.nodes.size()));
  for (const RcbNode& n : d.nodes) {
    put_box(out, n.box);
    for (const int v : {n.rank_begin, n.rank_end, n.axis, n.left, n.right}) append(out, v);
    append(out, n.cut);
    append(out, static_cast<std::uint64_t>(n.count));
    append(out, n.weight);
  }
  append(out, static_cast<std::uint64_t>(d.boxes.size()));
  for (std::size_t r = 0; r < d.boxes.size(); ++r) {
    put_box(out, d.boxes[r]);
    append(out, static_cast<std::uint64_t>(d.owned[r]));
    append(out, d.owned_weight[r]);
  }
  return out;
}

StartHeader unpack_start_header(std::span<const std::byte> in) {
  StartHeader h;
  std::size_t pos = 0;
  SimulationState& s = h.state;
  for (double* v :
       {&s.time, &s.dt, &s.drum_omega, &s.drum_angle, &s.carrier_angle, &s.carrier_omega}) {
    *v = get_bytes<double>(in, pos);
  }
  s.steps = get_bytes<std::uint64_t>(in, pos);
  s.search_method = get_string(in, pos);
  s.contact_state_size = static_cast<std::size_t>(get_bytes<std::uint64_t>(in, pos));
  const auto extras = get_bytes<std::uint64_t>(in, pos);
  for (std::uint64_t k = 0; k < extras; ++k) {
    ParticleArray a;
    a.name = get_string(in, pos);
    a.initial = get_bytes<double>(in, pos);
    s.particles.extra.push_back(std::move(a));
  }
  h.particles = get_bytes<std::uint64_t>(in, pos);
  h.max_radius = get_bytes<double>(in, pos);
  Decomposition& d = h.decomposition;
  d.nodes.resize(static_cast<std::size_t>(get_bytes<std::uint64_t>(in, pos)));
  for (RcbNode& n : d.nodes) {
    n.box = get_box(in, pos);
    for (int* v : {&n.rank_begin, &n.rank_end, &n.axis, &n.left, &n.right}) {
      *v = get_bytes<int>(in, pos);
    }
    n.cut = get_bytes<double>(in, pos);
    n.count = static_cast<std::size_t>(get_bytes<std::uint64_t>(in, pos));
    n.weight = get_bytes<double>(in, pos);
  }
  const auto ranks = static_cast<std::size_t>(get_bytes<std::uint64_t>(in, pos));
  for (std::size_t r = 0; r < ranks; ++r) {
    d.boxes.push_back(get_box(in, pos));
    d.owned.push_back(static_cast<std::size_t>(get_bytes<std::uint64_t>(in, pos)));
    d.owned_weight.push_back(get_bytes<double>(in, pos));
  }
  return h;
}

StartPart start_part(const SimulationState& full, const Decomposition& d, const GhostLayer& g,
                     int q, std::vector<std::uint8_t>& held) {
  const Particles& p = full.particles;
  const auto uq = static_cast<std::size_t>(q);
  StartPart part;
  part.ghosts.assign(d.boxes.size(), {});
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (d.owner[i] != q) continue;
    pack_particle(p, i, i, full.wall_history[i], part.owned);
    ++part.owned_count;
    held[i] = 1;
  }
  for (const Index i : g.ghosts[uq]) {
    pack_particle(p, i, i, full.wall_history[i], part.ghosts[static_cast<std::size_t>(d.owner[i])]);
    held[i] = 1;
  }
  std::vector<std::uint64_t> slot(p.size());
  for (std::size_t i = 0; i < slot.size(); ++i) slot[i] = i;
  collect_records(
      full, slot, [&](std::size_t i, std::size_t j) { return held[i] != 0 && held[j] != 0; },
      part.records);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (d.owner[i] == q) held[i] = 0;
  }
  for (const Index i : g.ghosts[uq]) held[i] = 0;
  return part;
}

std::vector<std::byte> pack_records(const ContactRecords& records) {
  std::vector<std::byte> out;
  append(out, static_cast<std::uint64_t>(records.state_size));
  append(out, static_cast<std::uint64_t>(records.size()));
  for (std::size_t k = 0; k < records.size(); ++k) records.pack(k, out);
  return out;
}

ContactRecords unpack_records(std::span<const std::byte> in) {
  ContactRecords records;
  std::size_t pos = 0;
  records.state_size = static_cast<std::size_t>(get_bytes<std::uint64_t>(in, pos));
  const auto n = get_bytes<std::uint64_t>(in, pos);
  for (std::uint64_t k = 0; k < n; ++k) records.unpack(in, pos);
  return records;
}

}  // namespace drumlab
