// The serial pieces of the MPI decomposition (engine/parallel/particle_pack.hpp, ContactList's row
// keys): a particle survives packing with every array, contact records rebuild a subset's contact
// list, and keyed rows form the serial run's blocks cut to the subset.
#include <gtest/gtest.h>

#include <cstring>

#include "engine/contact/contact_history.hpp"
#include "engine/parallel/particle_pack.hpp"
#include "tests/same_bits.hpp"

namespace drumlab {
namespace {

TEST(ParticlePack, RoundTripKeepsEveryArrayAndTheWallHistory) {
  Particles p;
  p.add_array("film", 0.5);
  p.add(Vec3(0.1, 0.2, 0.3), 0.01, 2500.0, 1);
  p.add(Vec3(-0.1, 0.0, 0.05), 0.02, 2500.0, 0);
  p.velocity[1] = Vec3(1.0, -2.0, 3.0);
  p.extra[0].values[1] = 0.25;
  const std::array<Vec3, kWallParts> wall = {Vec3(1, 2, 3), Vec3(4, 5, 6), Vec3(7, 8, 9)};
  std::vector<std::byte> bytes;
  pack_particle(p, 1, 42, wall, bytes);
  Particles q = empty_like(p);
  WallHistory w;
  std::size_t pos = 0;
  EXPECT_EQ(unpack_particle(bytes, pos, q, w), 42u);
  EXPECT_EQ(pos, bytes.size());
  ASSERT_EQ(q.size(), 1u);
  EXPECT_TRUE(q.position[0] == p.position[1]);
  EXPECT_TRUE(q.velocity[0] == p.velocity[1]);
  EXPECT_EQ(q.radius[0], p.radius[1]);
  EXPECT_EQ(q.id[0], 1u);
  EXPECT_EQ(q.size_class[0], 0);
  EXPECT_EQ(q.extra[0].values[0], 0.25);
  EXPECT_TRUE(w[0][2] == wall[2]);
  // A fixed-size record: its slot and position read in place, its motion first.
  EXPECT_EQ(bytes.size(), packed_size(p));
  EXPECT_EQ(packed_slot(bytes), 42u);
  EXPECT_TRUE(packed_position(bytes) == p.position[1]);
  EXPECT_EQ(packed_radius(bytes), p.radius[1]);
  double motion[9];
  ASSERT_EQ(sizeof(motion), kPackedMotionBytes);
  std::memcpy(motion, bytes.data(), kPackedMotionBytes);
  EXPECT_EQ(motion[3], 1.0);  // velocity after position
  EXPECT_EQ(motion[5], 3.0);
}

TEST(ParticlePack, RecordsRebuildTheContactListOfASubset) {
  ContactRecords r;
  r.add(3, 9, Vec3(1, 0, 0), {});
  r.add(1, 3, Vec3(2, 0, 0), {});
  r.add(1, 3, Vec3(2, 0, 0), {});  // a second copy (two ranks sent it): kept once
  r.add(5, 7, Vec3(3, 0, 0), {});  // 7 absent
  r.add(1, 5, Vec3(4, 0, 0), {});
  r.add(0, 3, Vec3(5, 0, 0), {});   // 0 below the slots' range: absent
  r.add(9, 12, Vec3(6, 0, 0), {});  // 12 above it: absent
  const std::vector<std::uint64_t> slot = {1, 3, 5, 9};
  SimulationState s;
  assign_records(
      r, slot, [](std::size_t i, std::size_t) { return i != 2; }, s);
  EXPECT_EQ(s.contact_row_start, (std::vector<std::size_t>{0, 2, 3, 3, 3}));
  EXPECT_EQ(s.contact_col, (std::vector<Index>{1, 2, 3}));
  EXPECT_EQ(s.contact_history[0].x(), 2.0);
  EXPECT_EQ(s.contact_history[1].x(), 4.0);
  EXPECT_EQ(s.contact_history[2].x(), 1.0);
}

TEST(ContactListRowKeys, KeyedRowsFormTheSerialBlocksCutToTheSubset) {
  ContactList c;
  const std::vector<IndexPair> pairs = {{0, 1}, {1, 2}, {2, 3}};
  c.update(pairs, 4);
  // Serial slots 10, 511 | 512, 2000: the serial blocks [0, 512), [512, 1024), [1536, 2048).
  const std::vector<std::uint64_t> keys = {10, 511, 512, 2000};
  c.set_row_keys(keys);
  c.index_cross_block(512);
  EXPECT_EQ(std::vector<std::size_t>(c.block_start().begin(), c.block_start().end()),
            (std::vector<std::size_t>{0, 2, 3, 4}));
  // Pairs (1, 2) and (2, 3) cross blocks: partners 2 and 3 receive cross-block shares.
  EXPECT_EQ(std::vector<Index>(c.cross_receivers().begin(), c.cross_receivers().end()),
            (std::vector<Index>{2, 3}));
  c.set_row_keys({});  // serial: rows 0..3 are one block
  c.index_cross_block(512);
  EXPECT_EQ(c.block_start().size(), 2u);
  EXPECT_TRUE(c.cross_receivers().empty());
}

}  // namespace
}  // namespace drumlab
