#pragma once
// `auto`: choose the contact search for a scene and say why. The paper's rule (shallow drum ->
// m2, deep -> m5) is the baseline; drumlab counts each candidate's operations on the actual
// particles, ranks them with a per-operation cost model, times the leaders, and adds a Verlet
// list when the expected motion per step leaves several steps between rebuilds.
#include <span>
#include <string>
#include <vector>

#include "engine/scene/scene_config.hpp"
#include "engine/types.hpp"

namespace drumlab {

struct MethodEstimate {
  std::string method;
  double cells_per_particle = 0.0;
  double tests_per_particle = 0.0;
  double model_ns_per_particle = 0.0;      ///< cost model, ns per particle per search
  double measured_ns_per_particle = -1.0;  ///< timed, -1 if not timed
};

struct SearchChoice {
  std::string method;      ///< a name make_search accepts
  std::string paper_rule;  ///< what the paper's rule would pick
  std::string reason;      ///< one paragraph for people
  std::vector<MethodEstimate> candidates;
};

/// Chooses a search for `scene` (time step dt, s) given a representative particle state (e.g. the
/// initial fill). `timed_candidates` leaders of the model ranking are timed (0: model only).
SearchChoice choose_search_method(const SceneConfig& scene, double dt,
                                  std::span<const Vec3> position, std::span<const double> radius,
                                  int timed_candidates = 3);

}  // namespace drumlab
