// drumlab-mpi on wet and cohesive scenes against drumlab run: a small drum with liquid migration,
// wall bridges, a viscous term and half its liquid seeded in bridges at the start, on 1, 2 and 3
// ranks (and 2 ranks x 2 threads), and one with sjkr adhesion on 2 and 3 ranks, give the serial
// run's state bit for bit (positions, velocities, forces, films, wall bridges, every touching or
// bridged pair with its history and its state), with the scene's liquid conserved to round-off; a
// wet checkpoint written on 3 ranks (periodic ends, grid search m5, no viscous term) continues on 2
// as the uninterrupted run; the HDF5 series of the wet drum on 2 ranks is the serial run's (bond
// graph and agglomerate labels included). The bridge events cross ranks every step
// (engine/parallel/bridge_events.hpp), so the films agree only if every rank replays them in the
// serial order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "engine/io/h5_series.hpp"
#include "engine/periodic.hpp"
#include "tests/mpi/mpi_runner.hpp"
#include "tests/mpi/wet_drum_text.hpp"
#include "tests/same_bits.hpp"
#include "tests/small_drum_text.hpp"

namespace drumlab::test {
namespace {

/// A pair that matters: touching, or with any law state (a bridge, an adhesive contact). A Verlet
/// list also lists pairs apart within its skin with zero state, depending on when it was rebuilt.
struct Pair {
  Index a, b;
  Vec3 history;
  std::vector<double> state;
};
std::vector<Pair> live_pairs(const SimulationState& s) {
  std::vector<Pair> out;
  const Particles& p = s.particles;
  const std::size_t ss = s.contact_state_size;
  for (std::size_t i = 0; i + 1 < s.contact_row_start.size(); ++i) {
    for (std::size_t k = s.contact_row_start[i]; k < s.contact_row_start[i + 1]; ++k) {
      const Index j = s.contact_col[k];
      const std::vector<double> st(
          s.contact_state.begin() + static_cast<std::ptrdiff_t>(k * ss),
          s.contact_state.begin() + static_cast<std::ptrdiff_t>((k + 1) * ss));
      const double r = p.radius[i] + p.radius[j];
      const bool touching = (p.position[i] - p.position[j]).squaredNorm() < r * r;
      bool state = false;
      for (const double v : st) state = state || v != 0.0;
      if (touching || state) out.push_back({p.id[i], p.id[j], s.contact_history[k], st});
    }
  }
  return out;
}

/// The scene's liquid held in films, pair bridges (state [0] of a liquid-only law) and wall
/// bridges (m^3), and the number of live pair bridges.
struct Liquid {
  double total = 0.0;
  std::size_t bridges = 0;
};
Liquid liquid_held(const SimulationState& s) {
  Liquid l;
  for (const ParticleArray& a : s.particles.extra) {
    if (a.name != "liquid_film" && a.name.rfind("wall_bridge_volume", 0) != 0) continue;
    for (const double v : a.values) l.total += v;
  }
  for (std::size_t k = 0; k < s.contact_col.size(); ++k) {
    const double v = s.contact_state[k * s.contact_state_size];
    l.total += v;
    l.bridges += v > 0.0;
  }
  return l;
}

/// Equal bit for bit: every particle array (films and wall bridges included), the live pairs with
/// their history and state, the wall history, the clock.
void expect_same_state(const SimulationState& a, const SimulationState& b,
                       const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(a.particles.size(), b.particles.size());
  EXPECT_EQ(a.particles.id, b.particles.id);
  EXPECT_TRUE(same_bits(a.particles.position, b.particles.position));
  EXPECT_TRUE(same_bits(a.particles.velocity, b.particles.velocity));
  EXPECT_TRUE(same_bits(a.particles.omega, b.particles.omega));
  EXPECT_TRUE(same_bits(a.particles.force, b.particles.force));
  EXPECT_TRUE(same_bits(a.particles.torque, b.particles.torque));
  ASSERT_EQ(a.particles.extra.size(), b.particles.extra.size());
  for (std::size_t k = 0; k < a.particles.extra.size(); ++k) {
    EXPECT_EQ(a.particles.extra[k].name, b.particles.extra[k].name);
    EXPECT_TRUE(same_bits(a.particles.extra[k].values, b.particles.extra[k].values))
        << a.particles.extra[k].name;
  }
  const auto pa = live_pairs(a), pb = live_pairs(b);
  EXPECT_GT(pa.size(), 200u);  // a bed in contact
  ASSERT_EQ(pa.size(), pb.size());
  for (std::size_t k = 0; k < pa.size(); ++k) {
    EXPECT_TRUE(pa[k].a == pb[k].a && pa[k].b == pb[k].b) << "pair " << k;
    EXPECT_TRUE(same_bits(std::vector{pa[k].history}, std::vector{pb[k].history})) << k;
    EXPECT_TRUE(same_bits(pa[k].state, pb[k].state)) << "pair " << k;
  }
  EXPECT_TRUE(same_bits(a.wall_history, b.wall_history));
  EXPECT_TRUE(same_bits(a.time, b.time));
  EXPECT_EQ(a.steps, b.steps);
}

/// The liquid the scene gave its particles: liquid_content x each one's solid volume.
double scene_liquid(const SimulationState& s) {
  double v = 0.0;
  for (const double r : s.particles.radius)
    v += kLiquidContent * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  return v;
}

class MpiWet : public MpiCase {};

TEST_F(MpiWet, LiquidMigrationIsBitIdenticalOnOneToThreeRanks) {
  const std::string scene = dir.write("wet.toml", scene_text(wet_law()));
  const std::string args = "--steps 120 --rebalance-every 50 --balance-threshold 0";
  const SimulationState want = serial(scene, "--steps 120", "serial.h5");
  ASSERT_EQ(want.contact_state_size, 2u);  // [liquid] alone: bridge volume, age
  const Liquid held = liquid_held(want);
  EXPECT_GT(held.bridges, 100u);
  EXPECT_NEAR(held.total, scene_liquid(want), 1e-12 * scene_liquid(want));
  double wall = 0.0;  // the wall bridges take part
  for (const ParticleArray& a : want.particles.extra) {
    if (a.name.rfind("wall_bridge_volume", 0) == 0) {
      for (const double v : a.values) wall += v;
    }
  }
  EXPECT_GT(wall, 0.0);
  for (const int r : {1, 2, 3}) {
    const SimulationState got = parallel(r, scene, args, "mpi.h5");
    expect_same_state(want, got, std::to_string(r) + " ranks");
    EXPECT_NEAR(liquid_held(got).total, scene_liquid(got), 1e-12 * scene_liquid(got));
    if (r > 1) {  // events were replayed across ranks
      EXPECT_EQ(last_output.find("bridge events     0 "), std::string::npos) << last_output;
      EXPECT_NE(last_output.find("bridge events"), std::string::npos) << last_output;
    }
  }
}

TEST_F(MpiWet, LiquidMigrationOnTwoRanksTimesTwoThreadsIsBitIdentical) {
  const std::string scene = dir.write("wet.toml", scene_text(wet_law()));
  const SimulationState want = serial(scene, "--steps 60", "serial.h5");
  expect_same_state(want, parallel(2, scene, "--steps 60", "mpi.h5", 2), "2 ranks x 2 threads");
}

TEST_F(MpiWet, AdhesionIsBitIdenticalOnTwoAndThreeRanks) {
  const std::string scene =
      dir.write("sjkr.toml", scene_text("[cohesion]\nmodel = \"sjkr\"\nenergy_density = 2e5\n"));
  const SimulationState want = serial(scene, "--steps 120", "serial.h5");
  for (const int r : {2, 3}) {
    expect_same_state(
        want,
        parallel(r, scene, "--steps 120 --rebalance-every 50 --balance-threshold 0", "mpi.h5"),
        std::to_string(r) + " ranks");
  }
}

// Periodic ends (wall bridges with the mantle only), a grid search (the contact list is rebuilt
// every step, so ruptures of dropped pairs happen every step) and no viscous term.
TEST_F(MpiWet, WetCheckpointRestartsFromThreeOnTwoRanks) {
  const std::string scene = dir.write("wet.toml", scene_text(wet_law(false), "periodic"));
  const SimulationState whole = serial(scene, "--method m5 --steps 120", "whole.h5");
  parallel(3, scene, "--method m5 --steps 60", "half3.h5");
  expect_same_state(
      whole, parallel(2, scene, "--method m5 --steps 60 --restart " + dir.file("half3.h5"), "a.h5"),
      "3 -> 2 ranks");
  EXPECT_NEAR(liquid_held(whole).total, scene_liquid(whole), 1e-12 * scene_liquid(whole));
}

/// The frame's bonds as the file lists them, by their particles' stable ids.
struct IdBond {
  std::uint32_t a, b;
  double volume, force, age;
};
std::vector<IdBond> id_bonds(const SeriesFrame& f) {
  std::vector<IdBond> out;
  for (const Bond& b : f.bonds) out.push_back({f.id[b.i], f.id[b.j], b.volume, b.force, b.age});
  return out;
}

/// Frames a and b of two series hold the same particles, films, wall liquid, agglomerate labels
/// and bond graph (pairs, volumes, forces, ages, in the same order), bit for bit.
void expect_same_frame(const SeriesFrame& a, const SeriesFrame& b) {
  EXPECT_EQ(a.step, b.step);
  ASSERT_EQ(a.id, b.id);
  EXPECT_TRUE(same_bits(a.position, b.position));
  EXPECT_TRUE(same_bits(a.film, b.film));
  EXPECT_TRUE(same_bits(std::vector{a.wall_liquid}, std::vector{b.wall_liquid}));
  EXPECT_EQ(a.agglomerate_id, b.agglomerate_id);
  const auto ba = id_bonds(a), bb = id_bonds(b);
  ASSERT_EQ(ba.size(), bb.size());
  for (std::size_t n = 0; n < ba.size(); ++n) {
    EXPECT_TRUE(ba[n].a == bb[n].a && ba[n].b == bb[n].b) << "bond " << n;
    EXPECT_TRUE(same_bits(std::vector{ba[n].volume, ba[n].force, ba[n].age},
                          std::vector{bb[n].volume, bb[n].force, bb[n].age}))
        << "bond " << n;
  }
}

// The series of a wet scene written by 2 and 3 ranks (each its rows, the agglomerates found
// without gathering) is the serial run's series: every frame's particles, films, bond graph
// (pairs, volumes, forces, ages, in the file's order) and agglomerate labels bit for bit, under
// the granule criterion and as plain components (which join the bed across the ranks' parts),
// with caps and with periodic ends; and `drumlab analyze` reads the same agglomerates from them.
TEST_F(MpiWet, SeriesOfAWetSceneIsTheSerialRunsSeries) {
  struct Case {
    std::string ends, age;
  };
  for (const auto& [ends, age] : {Case{"", "0.0005"}, Case{"", "0"}, Case{"periodic", "0"}}) {
    SCOPED_TRACE("ends '" + ends + "', granule age " + age);
    const std::string scene = dir.write("wet.toml", scene_text(wet_law(), ends));
    const std::string h5 = " --steps 60 --every 30 --granule-age " + age + " --h5 ";
    serial(scene, h5 + dir.file("serial_series.h5"), "s.h5");
    const SeriesInfo want = read_series_info(dir.file("serial_series.h5"));
    ASSERT_EQ(want.frames, 3u);
    EXPECT_TRUE(want.has_bonds);
    for (const int ranks : {2, 3}) {
      SCOPED_TRACE(std::to_string(ranks) + " ranks");
      const std::string mpi = "mpi" + std::to_string(ranks);
      parallel(ranks, scene, h5 + dir.file(mpi + "_series.h5"), "m.h5");
      const SeriesInfo got = read_series_info(dir.file(mpi + "_series.h5"));
      ASSERT_EQ(got.frames, want.frames);
      EXPECT_TRUE(got.has_bonds && got.complete);
      for (std::size_t k = 0; k < want.frames; ++k) {
        SCOPED_TRACE("frame " + std::to_string(k));
        const SeriesFrame a = read_series_frame(dir.file("serial_series.h5"), k);
        expect_same_frame(a, read_series_frame(dir.file(mpi + "_series.h5"), k));
        EXPECT_GT(a.bonds.size(), k == 0 ? 0u : 50u);  // bridges form as the bed packs
        const std::set<std::uint32_t> labels(a.agglomerate_id.begin(), a.agglomerate_id.end());
        if (k > 0) {  // some agglomerates hold several primaries
          EXPECT_LT(labels.size() + 20, a.id.size());
        }
      }
    }
    for (const std::string name : {"serial", "mpi3"}) {
      const Ran r = shell(std::string(DRUMLAB_CLI) + " analyze " + dir.file(name + "_series.h5") +
                          " --granule-age " + age + " --agglomerates " + dir.file(name + ".csv"));
      ASSERT_EQ(r.exit_code, 0) << r.output;
    }
    EXPECT_EQ(read_text(dir.file("serial.csv")), read_text(dir.file("mpi3.csv")));
  }
}

// A frame of a wet scene before any bond forms (the loose fill) has an empty bond list, which
// every rank writes as a dataset of no rows: the series equals the serial run's.
TEST_F(MpiWet, SeriesFramesWithoutBondsAreTheSerialRunsFrames) {
  const std::string scene = dir.write("wet.toml", scene_text(wet_law()));
  const std::string h5 = " --settle-time 0 --steps 60 --every 30 --h5 ";
  serial(scene, h5 + dir.file("serial_series.h5"), "s.h5");
  parallel(2, scene, h5 + dir.file("mpi_series.h5"), "m.h5");
  const SeriesInfo got = read_series_info(dir.file("mpi_series.h5"));
  ASSERT_EQ(got.frames, 3u);
  EXPECT_TRUE(got.has_bonds && got.complete);
  for (std::size_t k = 0; k < got.frames; ++k) {
    SCOPED_TRACE("frame " + std::to_string(k));
    const SeriesFrame a = read_series_frame(dir.file("serial_series.h5"), k);
    if (k == 0) {
      EXPECT_TRUE(a.bonds.empty());
    }
    expect_same_frame(a, read_series_frame(dir.file("mpi_series.h5"), k));
  }
}

}  // namespace
}  // namespace drumlab::test
