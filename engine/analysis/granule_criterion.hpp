#pragma once
// What a granule is, as the user asks for it (`--granule-criterion`, `--granule-age`,
// `--granule-resolution` of run, analyze, sweep and render). granule_options
// (engine/analysis/agglomerates.hpp) turns it into the options of one frame's analysis.
//
// * age (the default): particles joined by bonds at least `age` old (s; < 0: one drum
//   revolution), the persistence criterion of engine/analysis/agglomerates.hpp.
// * components: the connected components of every bond (age 0). In a dense wet bed they
//   percolate (Jain et al. 2025): shown for comparison.
// * community: communities of the bond network weighted by each bond's attractive force, found
//   by the Leiden algorithm maximising modularity at `resolution` (engine/analysis/
//   granule_communities.hpp).
#include <optional>
#include <string>
#include <string_view>

namespace drumlab {

enum class GranuleMethod { age, community, components };

struct GranuleCriterion {
  GranuleMethod method = GranuleMethod::age;
  double age = -1.0;        ///< age: bonds at least this old join (s); < 0: one drum revolution
  double resolution = 1.0;  ///< community: the modularity's resolution (> 0; 1: Newman-Girvan)
};

/// "age", "community" or "components".
std::string_view granule_method_name(GranuleMethod method);
/// The method of a name granule_method_name gives; nullopt for any other.
std::optional<GranuleMethod> parse_granule_method(std::string_view name);
/// The names, for help texts: "age|community|components".
std::string granule_method_choices();

}  // namespace drumlab
