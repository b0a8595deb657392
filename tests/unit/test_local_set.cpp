// The next local set of a migration (engine/parallel/local_set.hpp), on hand-made sets: particles
// taken from packed records or from the current arrays (with a ghost's new motion), and the
// contact list merged from the current list and the migrants' records under the stated rules,
// checked entry by entry against what those rules give.
#include <gtest/gtest.h>

#include <tuple>
#include <vector>

#include "engine/parallel/local_set.hpp"

namespace drumlab {
namespace {

Particles four_particles() {
  Particles p;
  for (int k = 0; k < 4; ++k) {
    p.add(Vec3(k, 0.0, 0.0), 0.01 + 0.001 * k, 2500.0, 0);
    p.velocity.back() = Vec3(0.0, k, 0.0);
    p.omega.back() = Vec3(0.0, 0.0, k);
  }
  p.add_array("film", 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) p.extra[0].values[i] = 10.0 + double(i);
  return p;
}

WallHistory wall_of(std::size_t n) {
  WallHistory w(n);
  for (std::size_t i = 0; i < n; ++i) w[i][0] = Vec3(double(i), -1.0, 0.5);
  return w;
}

TEST(LocalSet, ParticlesComeFromRecordsOrFromTheCurrentArraysWithANewMotion) {
  const Particles p = four_particles();
  const WallHistory wall = wall_of(p.size());
  const std::size_t size = packed_size(p);
  // A migrant: particle 3 of another set, its position and film changed.
  Particles other = four_particles();
  other.position[3] = Vec3(7.0, 8.0, 9.0);
  other.extra[0].values[3] = 42.0;
  WallHistory other_wall = wall_of(4);
  other_wall[3][2] = Vec3(3.0, 3.0, 3.0);
  std::vector<std::byte> bytes;
  pack_particle(other, 3, 17, other_wall[3], bytes);
  // A ghost's new motion: position, velocity, angular velocity.
  std::vector<std::byte> motion;
  put_bytes(motion, Vec3(-1.0, -2.0, -3.0));
  put_bytes(motion, Vec3(-4.0, -5.0, -6.0));
  put_bytes(motion, Vec3(-7.0, -8.0, -9.0));
  const PackedPiece stays{5, nullptr, -1, 2};
  const PackedPiece migrant{17, bytes.data(), -1};
  const PackedPiece kept_ghost{20, nullptr, 1, 0, motion.data()};
  const std::vector<const PackedPiece*> seq{&stays, &migrant, &kept_ghost};
  Particles out = empty_like(p);
  WallHistory out_wall;
  fill_particles(seq, p, wall, size, out, out_wall);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out.position[0], p.position[2]);
  EXPECT_EQ(out.velocity[0], p.velocity[2]);
  EXPECT_EQ(out.radius[0], p.radius[2]);
  EXPECT_EQ(out.extra[0].values[0], 12.0);
  EXPECT_EQ(out_wall[0], wall[2]);
  // The migrant: every array from its record.
  EXPECT_EQ(out.position[1], Vec3(7.0, 8.0, 9.0));
  EXPECT_EQ(out.velocity[1], other.velocity[3]);
  EXPECT_EQ(out.mass[1], other.mass[3]);
  EXPECT_EQ(out.id[1], other.id[3]);
  EXPECT_EQ(out.extra[0].values[1], 42.0);
  EXPECT_EQ(out_wall[1], other_wall[3]);
  // The kept ghost: its motion from the message, the rest from the current arrays.
  EXPECT_EQ(out.position[2], Vec3(-1.0, -2.0, -3.0));
  EXPECT_EQ(out.velocity[2], Vec3(-4.0, -5.0, -6.0));
  EXPECT_EQ(out.omega[2], Vec3(-7.0, -8.0, -9.0));
  EXPECT_EQ(out.force[2], p.force[0]);
  EXPECT_EQ(out.radius[2], p.radius[0]);
  EXPECT_EQ(out.id[2], p.id[0]);
  EXPECT_EQ(out.extra[0].values[2], 10.0);
  EXPECT_EQ(out_wall[2], wall[0]);
}

/// A list over `n` particles from (i, j, history x-component, state) entries, i < j, sorted.
ContactList list_of(std::size_t n, std::size_t state_size,
                    const std::vector<std::tuple<Index, Index, double, double>>& entries) {
  std::vector<std::size_t> row(n + 1, 0);
  std::vector<Index> col;
  std::vector<Vec3> history;
  std::vector<double> state;
  for (const auto& [i, j, h, st] : entries) {
    ++row[i + 1];
    col.push_back(j);
    history.push_back(Vec3(h, 0.0, 0.0));
    for (std::size_t c = 0; c < state_size; ++c) state.push_back(st);
  }
  for (std::size_t i = 0; i < n; ++i) row[i + 1] += row[i];
  ContactList c;
  c.set_state_size(state_size);
  c.assign(row, col, history, state);
  return c;
}

TEST(LocalSet, ContactsKeepWhatStaysAndMergeTheMigrantsRecords) {
  // Current set: slots 10, 11, 12, 13, 14; 13 and 14 ghosts. Next set: slots 10, 12, 13, 15, 16
  // (11 left, 14 dropped, 15 arrived, 16 a new ghost); 13 stays a ghost, 16 is one.
  const std::vector<std::uint8_t> old_ghost{0, 0, 0, 1, 1};
  const std::vector<std::uint8_t> ghost{0, 0, 1, 0, 1};
  const std::vector<std::uint64_t> slot{10, 12, 13, 15, 16};
  const std::vector<Index> new_of_old{0, 5, 1, 2, 5};  // 5: not in the next set
  const ContactList old = list_of(5, 1,
                                  {{0, 1, 1.0, 0.1},    // 10-11: 11 left
                                   {0, 2, 2.0, 0.2},    // 10-12: kept
                                   {0, 3, 0.0, 0.0},    // 10-13: all zero bits, not carried
                                   {1, 2, 3.0, 0.3},    // 11-12: 11 left
                                   {2, 3, 4.0, 0.4},    // 12-13: kept
                                   {2, 4, 5.0, 0.5},    // 12-14: 14 dropped
                                   {3, 4, 6.0, 0.6}});  // 13-14: ghosts
  ContactRecords records;
  records.state_size = 1;
  const double st[] = {0.0};
  records.add(10, 15, Vec3(7.0, 0, 0), std::span(st));   // new pair with the migrant
  records.add(10, 12, Vec3(99.0, 0, 0), std::span(st));  // also listed here: the list's wins
  records.add(12, 15, Vec3(8.0, 0, 0), std::span(st));   // kept
  records.add(12, 15, Vec3(98.0, 0, 0), std::span(st));  // the same pair again: the first wins
  records.add(13, 16, Vec3(97.0, 0, 0), std::span(st));  // two ghosts: left out
  records.add(11, 15, Vec3(96.0, 0, 0), std::span(st));  // 11 not here: left out
  records.add(15, 16, Vec3(9.0, 0, 0), std::span(st));   // owned-ghost: kept
  SimulationState s;
  merge_contacts(old, old_ghost, new_of_old, ghost, slot, records, s);
  const std::vector<std::size_t> want_row{0, 2, 4, 4, 5, 5};
  const std::vector<Index> want_col{1, 3, 2, 3, 4};
  const std::vector<double> want_h{2.0, 7.0, 4.0, 8.0, 9.0};
  EXPECT_EQ(s.contact_row_start, want_row);
  EXPECT_EQ(s.contact_col, want_col);
  ASSERT_EQ(s.contact_history.size(), want_h.size());
  for (std::size_t k = 0; k < want_h.size(); ++k) EXPECT_EQ(s.contact_history[k].x(), want_h[k]);
  const std::vector<double> want_state{0.2, 0.0, 0.4, 0.0, 0.0};
  EXPECT_EQ(s.contact_state, want_state);
  EXPECT_EQ(s.contact_state_size, 1u);
}

}  // namespace
}  // namespace drumlab
