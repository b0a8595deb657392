// [[spray]] in a scene: the keys and their one-line errors (a nozzle outside the drum, a negative
// rate, a stop before its start, a droplet larger than the smallest particle...), and a dry
// powder sprayed in a turning drum: the liquid accounted for at every step (films + bridges +
// wall bridges + airborne + lost + wall film = sprayed), the same films for any thread count and
// search method, with a wall that loses droplets and one that they wet, and checkpoints that
// carry the droplets and the wall's film bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "engine/analysis/agglomerate_table.hpp"
#include "engine/fill/random_fill.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/scene/scene_config.hpp"
#include "engine/simulation.hpp"
#include "engine/spray/droplet_cloud.hpp"
#include "engine/threads.hpp"
#include "tests/small_drum_text.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab::test {
namespace {

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

const char* const kDryPowder =
    "[liquid]\nsurface_tension = 0.072\nliquid_content = 0.0\nmax_bridge_volume = 2e-9\n";

std::string nozzle(const std::string& extra = "") {
  return "[[spray]]\nname = \"top\"\nposition = [0.0, 0.0, 0.025]\ndirection = [0.0, -1.0, "
         "0.0]\nangle_deg = 40.0\nrate = 2e-7\nstart = 0.0\ndroplet_radius = 3e-4\n"
         "droplet_speed = 5.0\n" +
         extra;
}

std::string scene_text(const std::string& spray, const std::string& liquid = kDryPowder,
                       const std::string& search = "m5") {
  SmallDrumText t;
  t.search = search;
  t.fill = "count = 200\nsettle_time = 0.01\nseed = 3";
  return t.text() + liquid + spray;
}

/// The nozzle table with `key = value` replacing the key's line (or added).
std::string with(const std::string& key, const std::string& value) {
  std::string n = nozzle();
  const std::size_t at = n.find("\n" + key + " = ");
  if (at == std::string::npos) return n + key + " = " + value + "\n";
  const std::size_t end = n.find('\n', at + 1);
  return n.substr(0, at + 1) + key + " = " + value + n.substr(end);
}

TEST(SprayScene, KeysAreReadAndBadOnesAreOneLineNamingTheKey) {
  const SceneConfig s = parse_scene(scene_text(nozzle()), "spray.toml");
  ASSERT_EQ(s.sprays.size(), 1u);
  EXPECT_EQ(s.sprays[0].name, "top");
  EXPECT_EQ(s.sprays[0].shape, SprayShape::cone);
  EXPECT_EQ(s.sprays[0].rate, 2e-7);
  EXPECT_TRUE(std::isinf(s.sprays[0].stop));
  const struct {
    std::string spray, liquid, expected;
  } bad[] = {
      {with("position", "[0.0, 0.12, 0.025]"), kDryPowder, "spray[0].position: the nozzle"},
      {with("position", "[0.0, 0.0, 0.06]"), kDryPowder, "spray[0].position: the nozzle"},
      {with("rate", "-1e-7"), kDryPowder, "spray[0].rate: must be >= 0"},
      {with("start", "0.5") + "stop = 0.25\n", kDryPowder, "spray[0].stop: must be after start"},
      {with("droplet_radius", "0.005"), kDryPowder, "spray[0].droplet_radius: 0.005 m is larger"},
      {with("droplet_radius", "0.0"), kDryPowder, "spray[0].droplet_radius: must be > 0"},
      {with("angle_deg", "180.0"), kDryPowder, "spray[0].angle_deg: must be in [0, 180)"},
      {with("direction", "[0.0, 0.0, 0.0]"), kDryPowder, "spray[0].direction: must be"},
      {with("shape", "\"jet\""), kDryPowder, "spray[0].shape: unknown value 'jet'"},
      {with("fan_axis", "[0.0, 0.0, 1.0]"), kDryPowder, "spray[0].fan_axis: only with shape"},
      {with("shape", "\"flat_fan\"") + "fan_axis = [0.0, 2.0, 0.0]\n", kDryPowder,
       "spray[0].fan_axis: must be a finite vector not parallel"},
      {with("nozzle_size", "1.0"), kDryPowder, "spray[0].nozzle_size: unknown key"},
      {with("at_wall", "\"splash\""), kDryPowder, "spray[0].at_wall: unknown value 'splash'"},
      {nozzle(), "[liquid]\nsurface_tension = 0.072\nbridge_volume = 1e-9\n",
       "spray[0]: needs [liquid] with liquid_content"},
      {nozzle(), "", "spray[0]: needs [liquid] with liquid_content"},
  };
  for (const auto& b : bad) {
    SCOPED_TRACE(b.expected);
    try {
      parse_scene(scene_text(b.spray, b.liquid), "bad.toml");
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("bad.toml: " + b.expected), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

struct SprayRun {
  std::vector<double> film;
  std::vector<Vec3> position;
  SprayTotals totals;
};

/// The by-id films and positions and the totals of a run.
SprayRun result_of(const Simulation& sim) {
  SprayRun r;
  const Particles& p = sim.particles();
  r.film.assign(p.size(), 0.0);
  r.position.assign(p.size(), Vec3::Zero());
  const std::vector<double>& film = *p.find_array(kLiquidFilmArray);
  for (std::size_t i = 0; i < p.size(); ++i) {  // by stable id: storage order may differ
    r.film[p.id[i]] = film[i];
    r.position[p.id[i]] = p.position[i];
  }
  r.totals = sim.spray()->totals();
  return r;
}

/// The nozzle whose droplets wet the wall.
std::string wetting_nozzle() {
  return nozzle("at_wall = \"wet\"\n");
}

/// `steps` steps of the sprayed powder, the accounting checked at every step.
SprayRun run(const std::string& search, int threads, const std::string& spray = nozzle(),
             int steps = 600) {
  const int saved = max_threads();
  set_thread_count(threads);
  const SceneConfig scene = parse_scene(scene_text(spray, kDryPowder, search), "spray.toml");
  Simulation sim(scene, random_fill(scene));
  for (int n = 0; n < steps; ++n) {
    sim.step();
    const SprayTotals t = sim.spray()->totals();
    const LiquidTotals bed = sim.liquid();
    // The powder starts dry: every drop of the bed's liquid came from the nozzle, directly or
    // from the wall's film.
    const double scale = 1e-12 * std::max(t.sprayed, 1e-300);
    EXPECT_NEAR(bed.total(), t.absorbed + t.taken_from_wall, scale) << n;
    EXPECT_NEAR(t.sprayed, t.airborne + t.absorbed + t.lost + t.walled, scale) << n;
    EXPECT_NEAR(bed.total() + t.airborne + t.lost + t.on_wall, t.sprayed, scale) << n;
  }
  set_thread_count(saved);
  return result_of(sim);
}

TEST(SprayScene, LiquidIsAccountedEveryStepAndTheRunIsTheSameForThreadsAndMethods) {
  const SprayRun one = run("m5", 1);
  EXPECT_GT(one.totals.absorbed_count, 20u);  // droplets reached the bed
  EXPECT_GT(one.totals.emitted_count, one.totals.absorbed_count);
  for (const auto& [search, threads] :
       {std::pair<std::string, int>{"m5", 2}, {"brute", 1}, {"verlet:m2", 2}}) {
    SCOPED_TRACE(search + ", " + std::to_string(threads) + " threads");
    const SprayRun other = run(search, threads);
    EXPECT_EQ(other.film, one.film);
    EXPECT_EQ(other.position, one.position);
    EXPECT_EQ(other.totals.absorbed_count, one.totals.absorbed_count);
  }
}

TEST(SprayScene, AWetWallTakesWhatWouldBeLostAndGivesItToTheBedTheSameForThreadsAndMethods) {
  const SprayRun lost = run("m5", 1);
  const SprayRun one = run("m5", 1, wetting_nozzle());
  EXPECT_GT(lost.totals.lost_count, 0u);
  EXPECT_EQ(one.totals.lost_count, 0u);
  EXPECT_GT(one.totals.walled_count, 0u);
  EXPECT_GT(one.totals.taken_from_wall, 0.0);  // the bed touched the wet wall
  for (const auto& [search, threads] :
       {std::pair<std::string, int>{"m5", 2}, {"brute", 1}, {"verlet:m2", 2}}) {
    SCOPED_TRACE(search + ", " + std::to_string(threads) + " threads");
    const SprayRun other = run(search, threads, wetting_nozzle());
    EXPECT_EQ(other.film, one.film);
    EXPECT_EQ(other.position, one.position);
    EXPECT_EQ(other.totals.on_wall, one.totals.on_wall);
  }
}

// A checkpoint in the middle of the spray (droplets in flight, liquid on the wall) continues bit
// for bit, through the HDF5 file, as the uninterrupted run.
TEST(SprayScene, ACheckpointCarriesTheDropletsAndTheWallFilmBitForBit) {
  TempDir dir("spray-checkpoint");
  for (const std::string& spray : {nozzle(), wetting_nozzle()}) {
    SCOPED_TRACE(spray);
    const SceneConfig scene = parse_scene(scene_text(spray), "spray.toml");
    Simulation whole(scene, random_fill(scene));
    whole.advance(300);
    ASSERT_GT(whole.spray()->droplets().size(), 0u);
    const auto file = dir.path() / "c.h5";
    write_checkpoint(file, whole.state(), "spray");
    Simulation restarted(scene, read_checkpoint(file).state);
    EXPECT_EQ(restarted.spray()->droplets().size(), whole.spray()->droplets().size());
    whole.advance(300);
    restarted.advance(300);
    const SprayRun a = result_of(whole), b = result_of(restarted);
    EXPECT_EQ(a.film, b.film);
    EXPECT_EQ(a.position, b.position);
    EXPECT_EQ(a.totals.emitted_count, b.totals.emitted_count);
    EXPECT_EQ(a.totals.absorbed_count, b.totals.absorbed_count);
    EXPECT_EQ(a.totals.on_wall, b.totals.on_wall);
  }
  // A scene without the spray does not take a spraying checkpoint, nor the reverse.
  const SceneConfig dry = parse_scene(scene_text(""), "dry.toml");
  EXPECT_THROW(Simulation(dry, read_checkpoint(dir.path() / "c.h5").state), InputError);
  const SceneConfig wet = parse_scene(scene_text(nozzle()), "spray.toml");
  Simulation plain(dry, random_fill(dry));
  EXPECT_THROW(Simulation(wet, plain.state()), InputError);
}

TEST(SprayScene, TheCommandLineCheckpointsAndRestartsASprayingRun) {
  TempDir dir("spray-scene");
  const std::string scene = dir.write("spray.toml", scene_text(wetting_nozzle())).string();
  const std::string c = dir.path().string() + "/c.h5";
  const auto r = run_cli("run " + scene + " --steps 200 --checkpoint " + c);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("spray             sprayed "), std::string::npos) << r.output;
  EXPECT_TRUE(std::filesystem::exists(c));
  const auto again = run_cli("run " + scene + " --steps 100 --restart " + c);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("spray             sprayed "), std::string::npos) << again.output;
}

// The terms reach every output: the agglomerate table (run's and analyze's of the series, equal)
// and the observables, every frame closing the balance.
TEST(SprayScene, TablesAndSeriesCarryTheSpraysTerms) {
  TempDir dir("spray-outputs");
  const std::string scene = dir.write("spray.toml", scene_text(nozzle())).string();
  const std::string d = dir.path().string() + "/";
  auto r = run_cli("run " + scene + " --steps 400 --every 50 --h5 " + d + "s.h5 --agglomerates " +
                   d + "run.csv --observables " + d + "obs.csv --vtu " + d + "vtu");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // The VTU series: the droplets and the nozzle, a file each a frame, and their collections.
  for (const char* f :
       {"droplets.pvd", "nozzles.pvd", "droplets_000008.vtu", "nozzles_000008.vtp"}) {
    EXPECT_TRUE(std::filesystem::exists(d + "vtu/" + f)) << f;
  }
  const std::string nozzle_file = read_text(d + "vtu/nozzles_000008.vtp");
  EXPECT_NE(nozzle_file.find("NumberOfPoints=\"18\""), std::string::npos);  // apex, axis, 16 rays
  EXPECT_NE(read_text(d + "vtu/droplets_000008.vtu").find("Name=\"velocity\""), std::string::npos);
  const std::vector<AgglomerateStats> rows = read_agglomerate_table(d + "run.csv");
  ASSERT_EQ(rows.size(), 9u);
  for (const AgglomerateStats& row : rows) {
    const SprayLiquid& s = row.spray;
    const double balance = row.free_liquid + row.bridge_liquid + row.wall_liquid + s.airborne +
                           s.lost + s.on_wall - s.sprayed;
    EXPECT_NEAR(balance, 0.0, 1e-11 * std::max(s.sprayed, 1e-300)) << row.time;
  }
  EXPECT_GT(rows.back().spray.sprayed, 0.0);
  EXPECT_GT(rows.back().free_liquid + rows.back().bridge_liquid, 0.0);
  r = run_cli("analyze " + d + "s.h5 --agglomerates " + d + "analyze.csv");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_text(d + "analyze.csv"), read_text(d + "run.csv"));
  // The growth chart from the series and from the table, with the phases printed (a build
  // without VTK prints the phases and refuses the chart).
  r = run_cli("analyze " + d + "s.h5 --granule-criterion components --growth " + d + "g.png");
  EXPECT_NE(r.output.find("growth            nucleation"), std::string::npos) << r.output;
#if DRUMLAB_TESTS_RENDER
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_GT(std::filesystem::file_size(d + "g.png"), 1000u);
  r = run_cli("analyze " + d + "run.csv --growth " + d + "g2.png");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(d + "g2.png"));
#else
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("g.png: this build has no VTK to draw the chart"), std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(d + "g.png"));
#endif
  r = run_cli("analyze " + d + "s.h5");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const std::string obs = read_text(d + "obs.csv");
  EXPECT_NE(obs.find(",sprayed_liquid,airborne_liquid,lost_liquid,wall_film_liquid,"),
            std::string::npos);
}

}  // namespace
}  // namespace drumlab::test
