#include "engine/search/search_input.hpp"

#include <fmt/format.h>

namespace drumlab {

void ContactSearch::reset_counters(std::size_t n) {
  counters_ = SearchCounters{};
  cells_per_particle_.assign(n, 0);
  tests_per_particle_.assign(n, 0);
}

void validate_search_input(const SearchInput& in) {
  if (in.position.size() != in.radius.size()) {
    throw InputError(
        fmt::format("search: {} positions but {} radii", in.position.size(), in.radius.size()));
  }
  if (!(in.margin >= 0.0) || !std::isfinite(in.margin)) {
    throw InputError(fmt::format("search: margin must be >= 0 and finite, got {}", in.margin));
  }
  const double period = in.period_z.value_or(0.0);
  if (in.period_z && !(period > 0.0 && std::isfinite(period))) {
    throw InputError(fmt::format("search: period_z must be positive, got {}", period));
  }
  for (std::size_t i = 0; i < in.position.size(); ++i) {
    const Vec3& x = in.position[i];
    if (!x.allFinite())
      throw InputError(fmt::format("search: particle {} has a non-finite position", i));
    const double r = in.radius[i];
    if (!(r > 0.0) || !std::isfinite(r)) {
      throw InputError(fmt::format("search: particle {} has radius {} (must be positive)", i, r));
    }
    if (in.domain) {
      const Box& b = *in.domain;
      if ((x.array() < b.lo.array()).any() || (x.array() >= b.hi.array()).any()) {
        throw InputError(fmt::format("search: particle {} at ({}, {}, {}) lies outside the domain",
                                     i, x.x(), x.y(), x.z()));
      }
    }
    if (in.period_z && (x.z() < 0.0 || x.z() >= period)) {
      throw InputError(fmt::format("search: particle {} has z = {} outside the period [0, {})", i,
                                   x.z(), period));
    }
  }
}

}  // namespace drumlab
