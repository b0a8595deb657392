// The memory estimate (engine/memory_estimate.hpp) against the heap a small settled run really
// holds (glibc mallinfo2 before the Simulation is built and after it has run), for each kind of
// search, on one thread and on two (the parallel pair loop's buffers): within 20 %.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <tuple>

#include "engine/fill/random_fill.hpp"
#include "engine/memory_estimate.hpp"
#include "engine/memory_probe.hpp"
#include "engine/search/verlet_list.hpp"
#include "engine/simulation.hpp"
#include "engine/threads.hpp"

namespace drumlab {
namespace {

class MemoryEstimateTest : public ::testing::TestWithParam<std::tuple<const char*, int>> {};

TEST_P(MemoryEstimateTest, WithinTwentyPercentOfTheMeasuredHeap) {
#if defined(__SANITIZE_THREAD__)
#define DRUMLAB_TSAN_TEST 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define DRUMLAB_TSAN_TEST 1
#endif
#endif
#ifdef DRUMLAB_TSAN_TEST
  // Under TSan (clang 14) the heap measures m5 at 1139 B/particle against 894 estimated, with or
  // without the OpenMP tool; GCC's ASan and the plain build agree within 20 %: its allocator's
  // count is not comparable (not traced further).
  GTEST_SKIP() << "ThreadSanitizer's allocator counts the heap differently";
#endif
  SceneConfig scene = load_scene(std::string(DRUMLAB_SCENES_DIR) + "/mono_periodic.toml");
  scene.fill.count = 800;
  const auto [method, threads] = GetParam();
  set_thread_count(threads);
  scene.search_method = method;
  const std::size_t heap0 = heap_bytes_in_use();
  double measured = 0.0;
  MemoryShape shape;
  {
    Simulation sim(scene, random_fill(scene));
    sim.advance(800);  // 0.1 s: the fill has fallen into a bed with contacts
    measured = static_cast<double>(heap_bytes_in_use() - heap0);
    const SimulationState st = sim.state();
    shape.particles = sim.particles().size();
    shape.threads = threads;
    shape.listed_pairs_per_particle =
        static_cast<double>(st.contact_col.size()) / static_cast<double>(shape.particles);
    const auto* verlet = dynamic_cast<const VerletListSearch*>(&sim.search());
    const ContactSearch& grid = verlet != nullptr ? verlet->builder() : sim.search();
    shape.grid_cells = static_cast<double>(grid.counters().cells_total);
  }
  set_thread_count(1);
  const MemoryEstimate e = estimate_memory(method, shape);
  const double n = static_cast<double>(shape.particles);
  std::printf(
      "%s, %d threads: %.2f pairs/particle, %.0f cells; measured %.0f B/particle, estimated %.0f\n",
      method, threads, shape.listed_pairs_per_particle, shape.grid_cells, measured / n,
      e.total() / n);
  EXPECT_GT(shape.listed_pairs_per_particle, 1.0) << "a settled bed";
  EXPECT_NEAR(e.total() / measured, 1.0, 0.2);
}

INSTANTIATE_TEST_SUITE_P(Methods, MemoryEstimateTest,
                         ::testing::Combine(::testing::Values("m5", "m2", "m1", "mlgrid", "verlet",
                                                              "verlet:m2"),
                                            ::testing::Values(1, 2)),
                         [](const auto& info) {
                           std::string name = std::get<0>(info.param);
                           std::replace(name.begin(), name.end(), ':', '_');
                           return name + "_" + std::to_string(std::get<1>(info.param)) + "threads";
                         });

}  // namespace
}  // namespace drumlab
