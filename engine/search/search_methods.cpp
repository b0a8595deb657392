#include "engine/search/search_methods.hpp"

#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "engine/search/brute_force.hpp"
#include "engine/search/cell_grid.hpp"
#include "engine/search/multilevel_grid.hpp"
#include "engine/search/verlet_list.hpp"

namespace drumlab {

namespace {

template <int Method>
std::unique_ptr<ContactSearch> make_paper_method() {
  return std::make_unique<CellGridSearch>(paper_method(Method));
}

template <class Search>
std::unique_ptr<ContactSearch> make_plain() {
  return std::make_unique<Search>();
}

using G = SearchGrid;
using C = CellRule;

// m1..m5: the five methods of Lobovikov et al. (2021), cited in engine/search/cell_grid.hpp.
// name, description, grid, cell side, draws cells, builds a Verlet list, its list is listed, make
const SearchMethodInfo kMethods[] = {
    {"brute", "all N(N-1)/2 pairs tested (test oracle, O(N^2))", G::none, C::none, false, false,
     false, make_plain<BruteForceSearch>},
    {"m1", "paper method 1: 2D grid, cell = R_min, per-size half stencil", G::two_d, C::min_radius,
     true, true, false, make_paper_method<1>},
    {"m2", "paper method 2: as m1, smallest particles skip far cells", G::two_d, C::min_radius,
     true, true, true, make_paper_method<2>},
    {"m3", "paper method 3: 3D grid, cell = R_min, per-size half shell", G::three_d, C::min_radius,
     true, true, false, make_paper_method<3>},
    {"m4", "paper method 4: 2D grid, cell = R_max, one stencil", G::two_d, C::max_radius, true,
     true, false, make_paper_method<4>},
    {"m5", "paper method 5: 3D grid, cell = R_max, one half shell", G::three_d, C::max_radius, true,
     true, true, make_paper_method<5>},
    {"mlgrid",
     "multi-level grid: a 3D grid per size level, cross-level spheres from the larger side",
     G::three_d, C::per_level, false, true, true, make_plain<MultiLevelGridSearch>},
};

constexpr std::string_view kVerletPrefix = "verlet:";

std::vector<std::string> names_where(bool SearchMethodInfo::*trait) {
  std::vector<std::string> names;
  for (const SearchMethodInfo& m : kMethods) {
    if (m.*trait) names.emplace_back(m.name);
  }
  return names;
}

}  // namespace

std::string_view search_grid_name(SearchGrid grid) {
  constexpr std::string_view kNames[] = {"none", "2D", "3D"};
  return kNames[static_cast<std::size_t>(grid)];
}

std::span<const SearchMethodInfo> search_methods() {
  return kMethods;
}

const SearchMethodInfo* find_search_method(std::string_view name) {
  for (const SearchMethodInfo& m : kMethods) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

const SearchMethodInfo& search_method(std::string_view name) {
  const SearchMethodInfo* m = find_search_method(name);
  if (m == nullptr) throw std::logic_error(fmt::format("no search method '{}' in the table", name));
  return *m;
}

std::optional<ParsedSearchMethod> parse_search_method(std::string_view name) {
  if (const SearchMethodInfo* m = find_search_method(name)) return ParsedSearchMethod{m, false};
  std::string_view builder;
  if (name == "verlet") {
    builder = kDefaultVerletBuilder;
  } else if (name.starts_with(kVerletPrefix)) {
    builder = name.substr(kVerletPrefix.size());
  } else {
    return std::nullopt;
  }
  const SearchMethodInfo* m = find_search_method(builder);
  if (m == nullptr || !m->builds_verlet) return std::nullopt;
  return ParsedSearchMethod{m, true};
}

std::string verlet_method_name(std::string_view builder) {
  return builder == kDefaultVerletBuilder ? std::string("verlet")
                                          : fmt::format("{}{}", kVerletPrefix, builder);
}

std::vector<std::string> verlet_builder_names() {
  return names_where(&SearchMethodInfo::builds_verlet);
}

std::vector<std::string> cell_grid_method_names() {
  return names_where(&SearchMethodInfo::draws_cells);
}

std::string search_method_help() {
  std::vector<std::string_view> names;
  for (const SearchMethodInfo& m : kMethods) names.push_back(m.name);
  return fmt::format("{}, verlet[:GRID] (GRID: {}; verlet alone: {})", fmt::join(names, ", "),
                     fmt::join(verlet_builder_names(), ", "), kDefaultVerletBuilder);
}

std::vector<std::string> search_method_names() {
  std::vector<std::string> names;
  for (const SearchMethodInfo& m : kMethods) names.emplace_back(m.name);
  // The Verlet lists after the plain methods, plain "verlet" first.
  if (search_method(kDefaultVerletBuilder).listed_verlet) names.emplace_back("verlet");
  for (const SearchMethodInfo& m : kMethods) {
    if (m.listed_verlet && m.name != kDefaultVerletBuilder) {
      names.push_back(verlet_method_name(m.name));
    }
  }
  return names;
}

std::unique_ptr<ContactSearch> make_search(std::string_view name, const SearchTuning& tuning) {
  const auto parsed = parse_search_method(name);
  if (!parsed) {
    throw InputError(fmt::format("unknown search method '{}' (valid: {}, or verlet:<grid>)", name,
                                 fmt::join(search_method_names(), ", ")));
  }
  if (!parsed->verlet) return parsed->method->make();
  return std::make_unique<VerletListSearch>(parsed->method->make(), tuning.verlet_skin);
}

}  // namespace drumlab
