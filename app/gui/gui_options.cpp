#include "app/gui/gui_options.hpp"

#include <algorithm>
#include <charconv>
#include <numbers>

#include <fmt/format.h>

#include "engine/search/search_methods.hpp"

namespace drumlab::gui {

void check_method(const std::string& name, const std::string& flag) {
  if (name == "auto" || parse_search_method(name)) return;
  throw InputError(
      fmt::format("{}: unknown search method '{}' (auto, {})", flag, name, search_method_help()));
}

ScheduledSwitch parse_switch_at(const std::string& text) {
  const auto colon = text.find(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == text.size()) {
    throw InputError(fmt::format("--switch-at: '{}' is not STEP:METHOD (e.g. 100:m2)", text));
  }
  ScheduledSwitch s;
  const char* first = text.data();
  const char* last = text.data() + colon;
  const auto [end, ec] = std::from_chars(first, last, s.step);
  if (ec != std::errc() || end != last) {
    throw InputError(
        fmt::format("--switch-at: '{}' is not a step count in '{}'", text.substr(0, colon), text));
  }
  s.method = text.substr(colon + 1);
  check_method(s.method, "--switch-at");
  return s;
}

void apply_edit(SceneConfig& scene, const std::string& edit) {
  const auto eq = edit.find('=');
  const std::string key = edit.substr(0, eq);
  double v = 0.0;
  if (eq != std::string::npos) {
    const char* first = edit.data() + eq + 1;
    const char* last = edit.data() + edit.size();
    const auto [end, ec] = std::from_chars(first, last, v);
    if (ec != std::errc() || end != last || first == last) {
      throw InputError(fmt::format("--edit: '{}' is not KEY=NUMBER", edit));
    }
  } else {
    throw InputError(fmt::format("--edit: '{}' is not KEY=NUMBER", edit));
  }
  if (key == "omega") {
    scene.drum.omega = v;
  } else if (key == "rpm") {
    scene.drum.omega = v * 2.0 * std::numbers::pi / 60.0;
  } else if (key == "friction") {
    scene.material.friction = v;
  } else if (key == "restitution") {
    scene.material.restitution = v;
  } else if (key == "wall_friction") {
    scene.wall.friction = v;
  } else if (key == "count" && v >= 0.0) {
    scene.fill.count = static_cast<std::size_t>(v);
  } else if (key == "fill_fraction") {
    scene.fill.volume_fraction = v;
  } else if (key == "seed" && v >= 0.0) {
    scene.fill.seed = static_cast<std::uint64_t>(v);
  } else if (key == "settle_time") {
    scene.fill.settle_time = v;
  } else {
    throw InputError(fmt::format(
        "--edit: unknown key in '{}' (omega, rpm, friction, restitution, wall_friction, count, "
        "fill_fraction, seed, settle_time)",
        edit));
  }
}

std::array<double, 2> parse_pair(const std::string& text, const std::string& flag) {
  std::array<double, 2> v{};
  const auto comma = text.find(',');
  const char* bounds[3] = {text.data(), text.data() + std::min(comma, text.size()),
                           text.data() + text.size()};
  for (std::size_t k = 0; k < 2 && comma != std::string::npos; ++k) {
    const char* first = bounds[k] + (k == 1 ? 1 : 0);
    const auto [end, ec] = std::from_chars(first, bounds[k + 1], v[k]);
    if (ec != std::errc() || end != bounds[k + 1] || first == bounds[k + 1]) break;
    if (k == 1) return v;
  }
  throw InputError(fmt::format("{}: '{}' is not two numbers A,B", flag, text));
}

}  // namespace drumlab::gui
