#include "render/particle_colors.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "engine/analysis/agglomerates.hpp"
#include "render/palette.hpp"

namespace drumlab::render {

namespace {

/// Size classes: the distinct radii (mm), named after the scene's classes where one has that
/// radius (or a table class lists it); none if there are more radii than colours (a continuous map
/// then).
std::vector<std::pair<double, std::string>> size_categories(const FrameSnapshot& s,
                                                            const std::vector<double>& mm) {
  std::vector<double> distinct;
  for (const double v : mm) {
    if (std::find(distinct.begin(), distinct.end(), v) != distinct.end()) continue;
    if (distinct.size() == kMaxCategories) return {};
    distinct.push_back(v);
  }
  std::sort(distinct.begin(), distinct.end());
  std::vector<std::pair<double, std::string>> out;
  for (const double v : distinct) {
    std::string name = fmt::format("r = {:.3g} mm", v);
    for (const ParticleClass& c : s.classes) {
      if (c.size().holds(v / 1000.0, 1e-9)) name = fmt::format("{} ({:.3g} mm)", c.name, v);
    }
    out.emplace_back(v, std::move(name));
  }
  return out;
}

}  // namespace

std::vector<double> particle_color_values(const Simulation& sim, ColorBy by,
                                          const GranuleCriterion& granule) {
  const Particles& p = sim.particles();
  if (by == ColorBy::agglomerate) {
    const std::vector<std::uint32_t> label = agglomerate_labels(sim, granule);
    std::vector<std::uint32_t> sorted(label);
    std::sort(sorted.begin(), sorted.end());
    std::vector<double> values(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) {
      const auto range = std::equal_range(sorted.begin(), sorted.end(), label[i]);
      const bool alone = range.second - range.first == 1;
      values[i] = alone ? 0.0 : 1.0 + static_cast<double>(label[i] % kMaxCategories);
    }
    return values;
  }
  if (by == ColorBy::coordination) {  // the engine's count, as the VTU's coordination array
    std::vector<std::uint32_t> count;
    sim.coordination_numbers(count);
    return {count.begin(), count.end()};
  }
  std::vector<double> values(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    switch (by) {
      case ColorBy::size:
        values[i] = 1000.0 * p.radius[i];
        break;
      case ColorBy::speed:
        values[i] = p.velocity[i].norm();
        break;
      case ColorBy::omega:
        values[i] = p.omega[i].norm();
        break;
      case ColorBy::id:
        values[i] = static_cast<double>(p.id[i]);
        break;
      case ColorBy::coordination:
      case ColorBy::agglomerate:
        break;
    }
  }
  return values;
}

namespace {

constexpr ColorByName kColorByNames[] = {{ColorBy::size, "size"},
                                         {ColorBy::speed, "speed"},
                                         {ColorBy::omega, "omega"},
                                         {ColorBy::id, "id"},
                                         {ColorBy::coordination, "coordination"},
                                         {ColorBy::agglomerate, "agglomerate"}};

}  // namespace

std::span<const ColorByName> color_by_names() {
  return kColorByNames;
}

std::string_view color_by_name(ColorBy by) {
  for (const ColorByName& c : kColorByNames) {
    if (c.value == by) return c.name;
  }
  throw std::logic_error("color_by_name: a ColorBy value without a name");
}

ColorBy parse_color_by(std::string_view s) {
  std::vector<std::string_view> names;
  for (const ColorByName& c : kColorByNames) {
    if (c.name == s) return c.value;
    names.push_back(c.name);
  }
  throw InputError(fmt::format("unknown colour mode '{}' ({})", s, fmt::join(names, ", ")));
}

ColorMap color_map(const FrameSnapshot& s, ColorBy by) {
  const bool empty = s.radius.empty();
  const double r_min = empty ? 0.0 : *std::min_element(s.radius.begin(), s.radius.end());
  const double r_max = empty ? 0.0 : *std::max_element(s.radius.begin(), s.radius.end());
  const double v_ref = std::max(0.1, std::abs(s.scene_omega) * s.drum_radius);
  ColorMap c;
  c.values = s.color_values;
  switch (by) {
    case ColorBy::size:
      c.lo = empty ? 0.0 : 1000.0 * r_min;
      c.hi = empty ? 1.0 : 1000.0 * r_max;
      c.title = "size class";
      c.categories = size_categories(s, c.values);
      if (c.categories.empty()) c.title = "radius (mm)";
      break;
    case ColorBy::speed:
      c.hi = 1.5 * v_ref;
      c.title = "speed (m/s)";
      break;
    case ColorBy::omega:
      c.hi = empty ? 1.0 : v_ref / r_min;
      c.title = "|omega| (rad/s)";
      break;
    case ColorBy::id:
      c.hi = std::max(1.0, static_cast<double>(s.size()) - 1.0);
      c.title = "particle id";
      break;
    case ColorBy::coordination:
      c.hi = 12.0;
      c.title = "contacts";
      break;
    case ColorBy::agglomerate:
      c.hi = static_cast<double>(kMaxCategories);
      c.title = "agglomerate";
      c.first_grey = true;
      c.categories.emplace_back(0.0, "alone");
      for (std::size_t k = 1; k <= kMaxCategories; ++k) {
        c.categories.emplace_back(static_cast<double>(k), fmt::format("id mod 7 = {}", k - 1));
      }
      break;
  }
  if (!(c.hi > c.lo)) c.hi = c.lo + 1.0;
  return c;
}

}  // namespace drumlab::render
