#include "engine/analysis/granule_criterion.hpp"

#include <array>

namespace drumlab {
namespace {

constexpr std::array<std::pair<std::string_view, GranuleMethod>, 3> kMethods = {{
    {"age", GranuleMethod::age},
    {"community", GranuleMethod::community},
    {"components", GranuleMethod::components},
}};

}  // namespace

std::string_view granule_method_name(GranuleMethod method) {
  for (const auto& [name, m] : kMethods) {
    if (m == method) return name;
  }
  return "age";
}

std::optional<GranuleMethod> parse_granule_method(std::string_view name) {
  for (const auto& [n, m] : kMethods) {
    if (n == name) return m;
  }
  return std::nullopt;
}

std::string granule_method_choices() {
  std::string s;
  for (const auto& [name, m] : kMethods) {
    if (!s.empty()) s += '|';
    s += name;
  }
  return s;
}

}  // namespace drumlab
