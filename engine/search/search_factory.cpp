#include <fmt/format.h>
#include <fmt/ranges.h>

#include "engine/search/brute_force.hpp"
#include "engine/search/cell_grid.hpp"
#include "engine/search/contact_search.hpp"
#include "engine/search/multilevel_grid.hpp"
#include "engine/search/verlet_list.hpp"

namespace drumlab {

namespace {

bool is_paper_method(std::string_view name) {
  return name.size() == 2 && name[0] == 'm' && name[1] >= '1' && name[1] <= '5';
}

}  // namespace

std::vector<std::string> search_method_names() {
  return {"brute", "m1", "m2", "m3", "m4", "m5", "mlgrid", "verlet", "verlet:m2", "verlet:mlgrid"};
}

std::unique_ptr<ContactSearch> make_search(std::string_view name, const SearchTuning& tuning) {
  if (name == "brute") return std::make_unique<BruteForceSearch>();
  if (is_paper_method(name)) return std::make_unique<CellGridSearch>(paper_method(name[1] - '0'));
  if (name == "mlgrid") return std::make_unique<MultiLevelGridSearch>();
  // "verlet" lists built by m5; "verlet:mN" by another grid.
  if (name == "verlet" || (name.starts_with("verlet:") &&
                           (is_paper_method(name.substr(7)) || name.substr(7) == "mlgrid"))) {
    const std::string_view builder = name == "verlet" ? "m5" : name.substr(7);
    return std::make_unique<VerletListSearch>(make_search(builder), tuning.verlet_skin);
  }
  throw InputError(fmt::format("unknown search method '{}' (valid: {}, or verlet:<grid>)", name,
                               fmt::join(search_method_names(), ", ")));
}

}  // namespace drumlab
