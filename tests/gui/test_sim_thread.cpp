// The workbench's SimThread read from the UI thread while the simulation thread switches the
// search and restarts the session: scene() always answers a whole scene with one of the methods
// asked for (it reads a copy published under the lock, never the session the simulation thread
// is replacing). A build with -fsanitize=thread reports the race this guards against.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "app/gui/sim_thread.hpp"
#include "engine/session/run_session.hpp"
#include "tests/gui/gui_test_helpers.hpp"

namespace drumlab::test {
namespace {

/// The small drum (m5) without settling: its scene, and the session options naming it.
std::pair<SceneConfig, SessionOptions> small_drum(const std::string& name) {
  const auto file = write_small_drum(fresh_dir(name), "m5").string();
  SessionOptions o;
  o.scene_file = file;
  o.settle_time = 0.0;
  return {load_dynamic_scene(file), o};
}

TEST(SimThread, SceneIsWholeWhileTheThreadSwitchesMethodsAndRestarts) {
  const auto [scene, o] = small_drum("sim-thread");
  gui::SimThread sim(scene, o, {}, 1);
  sim.set_chunk(2);
  sim.set_running(true);
  const std::vector<std::string> methods = {"m5", "m1", "verlet:m2", "brute", "m3"};
  std::size_t reads = 0;
  std::vector<std::string> seen;
  for (int round = 0; round < 40; ++round) {
    sim.switch_method(methods[static_cast<std::size_t>(round) % methods.size()]);
    if (round % 10 == 9) {
      sim.restart(scene);  // paused afterwards: run on
      sim.set_running(true);
    }
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(10);
    while (std::chrono::steady_clock::now() < until) {
      const SceneConfig s = sim.scene();
      ++reads;
      ASSERT_NE(std::find(methods.begin(), methods.end(), s.search_method), methods.end())
          << "scene() answered search method '" << s.search_method << "'";
      ASSERT_EQ(s.name, scene.name);
      ASSERT_EQ(s.classes.size(), scene.classes.size());
      if (std::find(seen.begin(), seen.end(), s.search_method) == seen.end()) {
        seen.push_back(s.search_method);
      }
    }
  }
  EXPECT_TRUE(sim.state_text() == "running" || sim.state_text() == "paused") << sim.state_text();
  EXPECT_GT(reads, 100u);
  EXPECT_GE(seen.size(), 3u) << "scene() followed the switches";
}

TEST(SimThread, SceneFollowsASwitchOnceItIsApplied) {
  const auto [scene, o] = small_drum("sim-thread-switch");
  gui::SimThread sim(scene, o, {}, 1);
  EXPECT_EQ(sim.scene().search_method, "m5");
  sim.switch_method("verlet:m2");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (sim.scene().search_method != "verlet:m2" && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_EQ(sim.scene().search_method, "verlet:m2");
  sim.switch_method("no-such-method");
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (sim.state_text() == "paused" && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_NE(sim.state_text().find("no-such-method"), std::string::npos) << sim.state_text();
  EXPECT_EQ(sim.scene().search_method, "verlet:m2") << "a refused method leaves the scene";
}

}  // namespace
}  // namespace drumlab::test
