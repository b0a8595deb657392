#include <fmt/format.h>
#include <fmt/ranges.h>

#include "engine/search/brute_force.hpp"
#include "engine/search/cell_grid.hpp"
#include "engine/search/contact_search.hpp"

namespace drumlab {

std::vector<std::string> search_method_names() {
  return {"brute", "m1", "m2", "m3", "m4", "m5"};
}

std::unique_ptr<ContactSearch> make_search(std::string_view name) {
  if (name == "brute") return std::make_unique<BruteForceSearch>();
  if (name.size() == 2 && name[0] == 'm' && name[1] >= '1' && name[1] <= '5') {
    return std::make_unique<CellGridSearch>(paper_method(name[1] - '0'));
  }
  throw InputError(fmt::format("unknown search method '{}' (valid: {})", name,
                               fmt::join(search_method_names(), ", ")));
}

}  // namespace drumlab
