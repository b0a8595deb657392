#pragma once
// The one table of contact-search methods: each method's name, description and traits (its grid,
// the rule for its cell side, whether it has cells to draw, whether it can build a Verlet list),
// and the parser of search names ("m5", "verlet", "verlet:<grid>"). make_search, the scene's
// needs / skips, auto's candidates, the benchmarks, the help texts and `drumlab info` all read it:
// a new method is one more row in search_methods.cpp.
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/search/contact_search.hpp"

namespace drumlab {

/// The grid a method bins the particles in.
enum class SearchGrid : std::uint8_t {
  none,   ///< no grid (brute force)
  two_d,  ///< x-y cells spanning the depth
  three_d,
};

/// "none", "2D" or "3D".
std::string_view search_grid_name(SearchGrid grid);

/// How the side of a grid cell follows from the radii.
enum class CellRule : std::uint8_t {
  none,        ///< no grid
  min_radius,  ///< the smallest radius
  max_radius,  ///< the largest radius
  per_level,   ///< one grid per size level, its cell about the level's largest diameter
};

struct SearchMethodInfo {
  std::string_view name;         ///< on the command line and in scenes
  std::string_view description;  ///< one line (ContactSearch::description of the method)
  SearchGrid grid = SearchGrid::none;
  CellRule cell = CellRule::none;
  bool draws_cells = false;    ///< one cell grid that `render --grid` draws (also as a Verlet
                               ///< builder); `--focus` draws every method's search
  bool builds_verlet = false;  ///< can build a Verlet list ("verlet:<name>"); auto ranks these
  bool listed_verlet = false;  ///< search_method_names() lists its Verlet list as well
  std::unique_ptr<ContactSearch> (*make)() = nullptr;
};

/// Every method that is not a Verlet list, in a stable order.
std::span<const SearchMethodInfo> search_methods();
/// The method called `name` (not a Verlet list), or nullptr.
const SearchMethodInfo* find_search_method(std::string_view name);
/// The row of `name`; throws std::logic_error if there is none (for the engine's own names).
const SearchMethodInfo& search_method(std::string_view name);

/// The grid that builds the list of plain "verlet".
inline constexpr std::string_view kDefaultVerletBuilder = "m5";

/// A search name, parsed: the method that finds the pairs and whether a Verlet list keeps them.
struct ParsedSearchMethod {
  const SearchMethodInfo* method = nullptr;  ///< for a Verlet list: its builder
  bool verlet = false;
};

/// Parses "brute", "m1".."m5", "mlgrid", "verlet" (built by m5) or "verlet:<grid>" (a grid that
/// builds_verlet); nullopt for any other name.
std::optional<ParsedSearchMethod> parse_search_method(std::string_view name);
/// The name of the Verlet list built by `builder`: "verlet" for m5, else "verlet:<builder>".
std::string verlet_method_name(std::string_view builder);
/// The names of the grids that can build a Verlet list, in table order (auto's candidates).
std::vector<std::string> verlet_builder_names();
/// The names of the methods with cells to draw (draws_cells), in table order.
std::vector<std::string> cell_grid_method_names();
/// The valid names for a help text: "brute, m1, ..., mlgrid, verlet[:GRID] (GRID: m1, ...)".
std::string search_method_help();

}  // namespace drumlab
