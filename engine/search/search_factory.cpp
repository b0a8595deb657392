#include <fmt/format.h>
#include <fmt/ranges.h>

#include "engine/search/brute_force.hpp"
#include "engine/search/contact_search.hpp"

namespace drumlab {

std::vector<std::string> search_method_names() { return {"brute"}; }

std::unique_ptr<ContactSearch> make_search(std::string_view name) {
  if (name == "brute") return std::make_unique<BruteForceSearch>();
  throw InputError(fmt::format("unknown search method '{}' (valid: {})", name,
                               fmt::join(search_method_names(), ", ")));
}

}  // namespace drumlab
