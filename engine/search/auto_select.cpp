#include "engine/search/auto_select.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "engine/search/search_methods.hpp"

namespace drumlab {

namespace {

// Cost model (ns on one core of the development machine, measured with `drumlab contacts` on
// the paper packing and the demo fill): opening a cell, testing a pair, and the per-particle
// overhead of binning and sorting.
constexpr double kNsPerCell = 1.5;
constexpr double kNsPerTest = 2.5;
constexpr double kNsPerParticle = 25.0;
// A Verlet list pays off when it is rebuilt at most every this many steps.
constexpr double kMinStepsBetweenRebuilds = 3.0;

MethodEstimate estimate(const std::string& name, const SearchInput& in) {
  auto search = make_search(name);
  std::vector<IndexPair> pairs;
  search->find_pairs(in, pairs);
  const double n = std::max<double>(1.0, static_cast<double>(in.position.size()));
  MethodEstimate e;
  e.method = name;
  e.cells_per_particle = static_cast<double>(search->counters().cells_visited) / n;
  e.tests_per_particle = static_cast<double>(search->counters().pairs_tested) / n;
  e.model_ns_per_particle =
      kNsPerParticle + kNsPerCell * e.cells_per_particle + kNsPerTest * e.tests_per_particle;
  return e;
}

double time_ns_per_particle(const std::string& name, const SearchInput& in) {
  auto search = make_search(name);
  std::vector<IndexPair> pairs;
  search->find_pairs(in, pairs);  // warm-up
  const int repeats = 3;
  const auto t0 = std::chrono::steady_clock::now();
  for (int r = 0; r < repeats; ++r) search->find_pairs(in, pairs);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return 1e9 * s / repeats / std::max<double>(1.0, static_cast<double>(in.position.size()));
}

}  // namespace

SearchChoice choose_search_method(const SceneConfig& scene, double dt,
                                  std::span<const Vec3> position, std::span<const double> radius,
                                  int timed_candidates) {
  SearchChoice choice;
  const double depth_ratio = scene.drum.depth / scene.drum.diameter;
  const bool shallow = depth_ratio < 0.5 && scene.drum.tilt == 0.0;
  choice.paper_rule = shallow ? "m2" : "m5";
  // Verlet list: particles move at most ~2 omega R per second in a turning drum (the wall speed
  // and the avalanche on top of the bed), so a rebuild is needed every skin / 2 / (v dt) steps.
  const double rmin = *std::min_element(radius.begin(), radius.end());
  const double speed = std::max(2.0 * std::abs(scene.drum.omega) * 0.5 * scene.drum.diameter,
                                std::sqrt(9.81 * rmin));
  const double skin_factor = scene.performance.verlet_skin;  // what the Verlet list will use
  const double steps_between = dt > 0.0 ? 0.5 * skin_factor * rmin / (speed * dt) : 0.0;
  const bool verlet = steps_between >= kMinStepsBetweenRebuilds;
  // With a Verlet list the grid's work is building the list: pairs within the skin.
  SearchInput in{position, radius, verlet ? skin_factor * rmin : 0.0, std::nullopt, std::nullopt};
  if (scene.drum.ends == DrumEnds::periodic) in.period_z = scene.drum.depth;

  for (const std::string& name : verlet_builder_names()) {  // the grids: m1..m5, mlgrid
    choice.candidates.push_back(estimate(name, in));
  }
  std::sort(choice.candidates.begin(), choice.candidates.end(),
            [](const MethodEstimate& a, const MethodEstimate& b) {
              return a.model_ns_per_particle < b.model_ns_per_particle;
            });
  const int timed = std::min<int>(timed_candidates, static_cast<int>(choice.candidates.size()));
  for (int c = 0; c < timed; ++c) {
    choice.candidates[c].measured_ns_per_particle =
        time_ns_per_particle(choice.candidates[c].method, in);
  }
  const auto best =
      timed > 0 ? std::min_element(choice.candidates.begin(), choice.candidates.begin() + timed,
                                   [](const auto& a, const auto& b) {
                                     return a.measured_ns_per_particle < b.measured_ns_per_particle;
                                   })
                : choice.candidates.begin();
  choice.method = verlet ? "verlet:" + best->method : best->method;
  choice.reason = fmt::format(
      "depth/diameter = {:.2f} ({}), so the paper's rule picks {}. Counted on {} particles{}: ",
      depth_ratio, shallow ? "shallow" : "deep or tilted", choice.paper_rule, position.size(),
      verlet ? " with the Verlet skin as margin (the grid builds the list)" : "");
  for (const MethodEstimate& e : choice.candidates) {
    choice.reason +=
        fmt::format("{} {:.1f} cells + {:.1f} tests/particle{}; ", e.method, e.cells_per_particle,
                    e.tests_per_particle,
                    e.measured_ns_per_particle >= 0.0
                        ? fmt::format(" ({:.0f} ns measured)", e.measured_ns_per_particle)
                        : std::string());
  }
  choice.reason += fmt::format("fastest grid{}: {}. ", verlet ? " for the list" : "", best->method);
  choice.reason += dt > 0.0
                       ? fmt::format(
                             "Expected rebuild interval of a Verlet list (skin {} R_min, speed <= "
                             "{:.2g} m/s): {:.1f} steps, so {}.",
                             skin_factor, speed, steps_between,
                             verlet ? "a Verlet list is used" : "no Verlet list")
                       : "No time step given, so no Verlet list.";
  return choice;
}

}  // namespace drumlab
