// The step loop must not allocate once its buffers have grown. This test binary replaces the
// global operator new (plain and aligned; new[] and the nothrow forms call these) with one that
// counts while armed, and checks that the steps after a warm-up allocate nothing (but the pair
// buffers' geometric growth where a step needs more pairs than any warm-up step), for
//   * three scenes: a dry periodic drum (friction, rolling resistance, persistent contacts), a wet
//     turning drum with liquid migration (films, bridges seeded at the start, wall bridges, the
//     viscous term: bridges form and rupture in the window), and the same drum with sjkr adhesion;
//   * every search method (the table of engine/search/search_methods.hpp and a Verlet list built
//     by each grid that can build one), re-orderings and Verlet rebuilds inside the window;
//   * one and two OpenMP threads (the warm-up also creates the thread team; libgomp's own
//     allocations are malloc, not operator new, and not counted).
// Not covered: the MPI exchanges, which allocate (tests/README.md says where and why). Under a
// sanitizer (DRUMLAB_SANITIZED) the sanitizer owns operator new: nothing is replaced and the
// tests skip.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdlib>
#include <new>
#include <string>
#include <tuple>
#include <vector>

#include "engine/search/search_methods.hpp"
#include "engine/threads.hpp"
#include "physics_test_helpers.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace {
std::atomic<std::size_t> g_allocations{0};
std::atomic<bool> g_armed{false};
// DRUMLAB_TRAP_ALLOCATION=1: an allocation in a window stops the program (SIGTRAP), so that `gdb
// --args drumlab_validation_tests --gtest_filter=...` shows where it came from (`bt`).
const bool g_trap = std::getenv("DRUMLAB_TRAP_ALLOCATION") != nullptr;

void count_allocation() {
  if (g_armed.load(std::memory_order_relaxed)) {
    if (g_trap) __builtin_trap();
    g_allocations.fetch_add(1, std::memory_order_relaxed);
  }
}
}  // namespace

#ifndef DRUMLAB_SANITIZED
void* operator new(std::size_t n) {
  count_allocation();
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t n, std::align_val_t a) {
  count_allocation();
  const auto align = static_cast<std::size_t>(a);
  // aligned_alloc wants a size that is a multiple of the alignment.
  if (void* p = std::aligned_alloc(align, (n + align - 1) / align * align + (n == 0 ? align : 0)))
    return p;
  throw std::bad_alloc();
}
// GCC flags free() of memory from a (replaced) operator new; here both sides are ours.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}
#pragma GCC diagnostic pop
#define SKIP_UNDER_SANITIZERS() (void)0
#else
#define SKIP_UNDER_SANITIZERS() GTEST_SKIP() << "a sanitizer build: the sanitizer owns operator new"
#endif

namespace drumlab {
namespace {

/// Counts operator new calls (any thread) from construction to count().
class AllocationWindow {
 public:
  AllocationWindow() : before_(g_allocations.load()) { g_armed = true; }
  ~AllocationWindow() { g_armed = false; }
  std::size_t count() const { return g_allocations.load() - before_; }

 private:
  std::size_t before_;
};

TEST(StepLoop, AllocationCounterCounts) {
  SKIP_UNDER_SANITIZERS();
  const AllocationWindow w;
  {
    std::vector<double> plain(10);
    plain[0] = 1.0;
    struct alignas(64) Line {
      double x[8];
    };
    std::vector<Line> aligned(3);
    aligned[0].x[0] = 1.0;
  }
  EXPECT_EQ(w.count(), 2u);
}

SceneConfig dry_periodic_scene() {
  SceneConfig s = test::make_scene(0.01);
  s.gravity = Vec3(0, -9.81, 0);
  s.material.friction = 0.5;
  s.material.rolling_friction = 0.02;
  s.wall = s.material;
  s.drum = DrumConfig{0.2, 0.1, 1.0, 0.2, DrumEnds::periodic, {}};
  return s;
}

Particles dry_periodic_particles() {
  Particles p;
  for (int ix = 0; ix < 7; ++ix) {
    for (int iz = 0; iz < 4; ++iz) {
      p.add(Vec3(-0.06 + 0.02 * ix, -0.07 + 0.002 * (ix % 2), 0.0125 + 0.025 * iz), 0.0099, 2500.0);
    }
  }
  return p;
}

// The small turning drum of the output tests (250 particles of radii 4 and 8 mm, caps, friction
// and rolling resistance on particles and walls), re-ordered every 50 steps, with `tables`.
SceneConfig turning_drum(const std::string& tables) {
  return parse_scene(test::output_scene_text() + tables + "[performance]\nsort_every = 50\n",
                     "no-allocation");
}

// Migration: 1 % liquid, bridges up to 1e-9 m^3 (rupture gap 1 mm), half the liquid seeded in
// bridges at the start, the viscous term on.
const char* const kWet =
    "[liquid]\nsurface_tension = 0.072\ncontact_angle_deg = 10\nliquid_content = 0.01\n"
    "max_bridge_volume = 1e-9\nfilm_share = 0.5\nviscosity = 0.001\nmin_gap = 1e-5\n";
const char* const kSjkr = "[cohesion]\nmodel = \"sjkr\"\nenergy_density = 5e4\n";

struct Start {
  SceneConfig scene;
  Particles particles;
};

Start make_start(const std::string& scene) {
  if (scene == "dry_periodic") return {dry_periodic_scene(), dry_periodic_particles()};
  // Lifters: the triangle walls' pass (with adhesion onto them) keeps its buffers too.
  const std::string lifters = "[[wall.lifters]]\ncount = 4\nheight = 0.02\n";
  SceneConfig s = turning_drum(scene == "wet_migration" ? std::string(kWet)
                               : scene == "lifters"     ? kSjkr + lifters
                                                        : std::string(kSjkr));
  Particles p = random_fill(s);
  return {std::move(s), std::move(p)};
}

/// Every method: the table's rows and a Verlet list on each grid that builds one.
std::vector<std::string> every_method() {
  std::vector<std::string> names;
  for (const SearchMethodInfo& m : search_methods()) names.emplace_back(m.name);
  for (const std::string& b : verlet_builder_names()) names.push_back(verlet_method_name(b));
  return names;
}

using Case = std::tuple<std::string, std::string, int>;  // scene, method, threads

class StepLoopAllocations : public ::testing::TestWithParam<Case> {};

// Warm-up steps grow every buffer (contacts settle, bridges form, the thread team starts): 1,500
// for the wet drum, 3,000 for the others (the sjkr bed compacts for longer, and so its search's
// pair lists grow for longer; the dry periodic one is cheap). Then 200 steps (4 re-orderings;
// Verlet rebuilds; bridges forming and rupturing) allocate nothing.
TEST_P(StepLoopAllocations, NoneAfterWarmUp) {
  SKIP_UNDER_SANITIZERS();
  const auto& [scene, method, threads] = GetParam();
  const int saved = max_threads();
  set_thread_count(threads);
  Start start = make_start(scene);
  start.scene.search_method = method;
  Simulation sim(start.scene, std::move(start.particles));
  std::size_t warm_pairs = 0, window_pairs = 0;  // the most listed pairs of a step
  for (int k = 0; k < (scene == "wet_migration" ? 1500 : 3000); ++k) {
    sim.step();
    warm_pairs = std::max(warm_pairs, sim.contacts().size());
  }
  const std::uint64_t reorders = sim.work().reorders;
  std::size_t during = 0;
  {
    const AllocationWindow w;
    for (int k = 0; k < 200; ++k) {
      sim.step();
      window_pairs = std::max(window_pairs, sim.contacts().size());
    }
    during = w.count();
  }
  set_thread_count(saved);

  EXPECT_EQ(sim.work().reorders - reorders, scene == "dry_periodic" ? 2u : 4u);
  const Diagnostics d = sim.diagnostics();
  EXPECT_GT(d.contacts, 0u);
  if (scene == "wet_migration") {
    EXPECT_GT(d.bridges, 0u);
  }
  if (window_pairs > warm_pairs) {
    // A step of the window needs more pairs than any warm-up step (the dry periodic drum on the
    // grids: 42 against 40): the search's pair buffers grow, geometrically, once for each
    // thread's slice and once for the joined list. Nothing else may allocate.
    EXPECT_LE(during, static_cast<std::size_t>(threads) + 1u)
        << window_pairs << " pairs against " << warm_pairs << " in the warm-up";
  } else {
    EXPECT_EQ(during, 0u) << "allocations in 200 steps";
  }
}

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  std::string name = std::get<0>(info.param) + "_" + std::get<1>(info.param) + "_" +
                     std::to_string(std::get<2>(info.param)) + "threads";
  for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(
    EveryMethod, StepLoopAllocations,
    ::testing::Combine(::testing::Values("dry_periodic", "wet_migration", "wet_sjkr"),
                       ::testing::ValuesIn(every_method()), ::testing::Values(1, 2)),
    case_name);

INSTANTIATE_TEST_SUITE_P(TriangleWalls, StepLoopAllocations,
                         ::testing::Combine(::testing::Values("lifters"),
                                            ::testing::Values("m5", "verlet:m2"),
                                            ::testing::Values(1, 2)),
                         case_name);

}  // namespace
}  // namespace drumlab
