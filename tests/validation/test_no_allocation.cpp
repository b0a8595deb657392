// The step loop must not allocate once its buffers have grown: this test binary counts calls to
// the global operator new and checks that 200 steps of a frictional, rolling, periodic scene with
// persistent contacts allocate nothing after a warm-up.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <vector>

#include "physics_test_helpers.hpp"

namespace {
std::atomic<std::size_t> g_allocations{0};
}  // namespace

void* operator new(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
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
#pragma GCC diagnostic pop

namespace drumlab {
namespace {

TEST(StepLoop, DoesNotAllocateAfterWarmUp) {
  SceneConfig s = test::make_scene(0.01);
  s.gravity = Vec3(0, -9.81, 0);
  s.material.friction = 0.5;
  s.material.rolling_friction = 0.02;
  s.wall = s.material;
  s.drum = DrumConfig{0.2, 0.1, 1.0, 0.2, DrumEnds::periodic};
  Particles p;
  for (int ix = 0; ix < 7; ++ix) {
    for (int iz = 0; iz < 4; ++iz) {
      p.add(Vec3(-0.06 + 0.02 * ix, -0.07 + 0.002 * (ix % 2), 0.0125 + 0.025 * iz), 0.0099, 2500.0);
    }
  }
  Simulation sim(s, std::move(p));
  sim.advance(3000);  // settle into persistent contacts, buffers grow
  const std::size_t before = g_allocations.load();
  for (int k = 0; k < 200; ++k) sim.step();
  const std::size_t during = g_allocations.load() - before;
  {
    std::vector<double> probe(10);  // the counter itself works
    probe[0] = 1.0;
  }
  EXPECT_GT(g_allocations.load(), before + during);
  EXPECT_GT(sim.diagnostics().contacts, 0u);
  EXPECT_EQ(during, 0u) << "allocations in 200 steps";
}

}  // namespace
}  // namespace drumlab
