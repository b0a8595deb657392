#pragma once
// A particle as bytes, for migration between ranks and for gathering a decomposed state: every
// array of Particles::for_each_array (fixed and registered extras, in that order), then its slot
// in the serial run's order and its wall history. Contacts travel as records keyed by the two
// particles' serial slots, so a rank can rebuild its contact list for any set of particles.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "engine/simulation_state.hpp"

namespace drumlab {

/// Appends v's bytes to out.
template <class T>
void put_bytes(std::vector<std::byte>& out, const T& v) {
  const auto* b = reinterpret_cast<const std::byte*>(&v);
  out.insert(out.end(), b, b + sizeof(T));
}
/// Reads a T at in[pos] and advances pos.
template <class T>
T get_bytes(std::span<const std::byte> in, std::size_t& pos) {
  T v;
  std::memcpy(static_cast<void*>(&v), in.data() + pos, sizeof(T));
  pos += sizeof(T);
  return v;
}

/// Appends particle i of p (its arrays, `slot`, its wall history) to out.
void pack_particle(const Particles& p, std::size_t i, std::uint64_t slot,
                   const std::array<Vec3, kWallParts>& wall, std::vector<std::byte>& out);

/// Appends the particle packed at in[pos] to p (which has the same extra arrays registered) and
/// wall; returns its serial slot and advances pos.
std::uint64_t unpack_particle(std::span<const std::byte> in, std::size_t& pos, Particles& p,
                              WallHistory& wall);

/// The first bytes of a packed particle: its position, velocity and angular velocity (the first
/// three arrays of for_each_array), what the ghost refresh sends every step.
inline constexpr std::size_t kPackedMotionBytes = 3 * sizeof(Vec3);

/// Bytes of one particle of p packed (every particle of p packs to this size).
std::size_t packed_size(const Particles& p);
/// The serial slot of the particle packed at `record` (packed_size bytes).
std::uint64_t packed_slot(std::span<const std::byte> record);
/// The position of the particle packed at `record` (its first array).
Vec3 packed_position(std::span<const std::byte> record);
/// The radius of the particle packed at `record` (its sixth array).
double packed_radius(std::span<const std::byte> record);

/// An empty Particles with the same extra arrays registered as p.
Particles empty_like(const Particles& p);

/// Contact records: pair (a, b) of serial slots, a < b, its tangential history (a's displacement
/// relative to b) and its state_size scalars.
struct ContactRecords {
  std::size_t state_size = 0;
  std::vector<std::uint64_t> a, b;
  std::vector<Vec3> history;
  std::vector<double> state;
  std::size_t size() const { return a.size(); }
  void add(std::uint64_t sa, std::uint64_t sb, const Vec3& h, std::span<const double> st);
  void pack(std::size_t k, std::vector<std::byte>& out) const;
  void unpack(std::span<const std::byte> in, std::size_t& pos);
};

/// The records of the contacts (i, j) of s whose rows or partners satisfy keep(i, j); `slot`
/// gives each particle's serial slot (increasing with the storage slot).
template <class Keep>
void collect_records(const SimulationState& s, std::span<const std::uint64_t> slot, Keep&& keep,
                     ContactRecords& out) {
  out.state_size = s.contact_state_size;
  const std::size_t rows = s.contact_row_start.empty() ? 0 : s.contact_row_start.size() - 1;
  for (std::size_t i = 0; i < rows; ++i) {
    for (std::size_t k = s.contact_row_start[i]; k < s.contact_row_start[i + 1]; ++k) {
      const Index j = s.contact_col[k];
      if (!keep(i, static_cast<std::size_t>(j))) continue;
      out.add(slot[i], slot[j], s.contact_history[k],
              std::span(s.contact_state).subspan(k * out.state_size, out.state_size));
    }
  }
}

/// Sets s's contact list (CSR) for the particles with serial slots `slot` (increasing) from the
/// records whose both particles are present and keep(i, j) holds (local slots); duplicates once.
template <class Keep>
void assign_records(ContactRecords r, std::span<const std::uint64_t> slot, Keep&& keep,
                    SimulationState& s);

}  // namespace drumlab

#include "engine/parallel/particle_pack_impl.hpp"
