#include "app/gui/gui_options.hpp"

#include <algorithm>
#include <charconv>
#include <numbers>

#include <fmt/format.h>

#include "engine/scene/scene_validation.hpp"
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

namespace {

/// The scene's field an --edit KEY names (omega, friction, restitution, wall_friction,
/// fill_fraction, settle_time), or nullptr.
double* edit_field(SceneConfig& scene, std::string_view key) {
  if (key == "omega") return &scene.drum.omega;
  if (key == "friction") return &scene.material.friction;
  if (key == "restitution") return &scene.material.restitution;
  if (key == "wall_friction") return &scene.wall.friction;
  if (key == "fill_fraction") return &scene.fill.volume_fraction;
  if (key == "settle_time") return &scene.fill.settle_time;
  return nullptr;
}

/// The edit's value as a whole number >= 0, or an InputError naming the edit and the scene key.
std::uint64_t whole_number(std::string_view text, const std::string& edit, std::string_view key) {
  std::uint64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty()) {
    throw InputError(
        fmt::format("--edit '{}': {}: must be a whole number >= 0, got '{}'", edit, key, text));
  }
  return v;
}

double number(std::string_view text, const std::string& edit) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty()) {
    throw InputError(fmt::format("--edit: '{}' is not KEY=NUMBER", edit));
  }
  return v;
}

}  // namespace

void apply_edit(SceneConfig& scene, const std::string& edit) {
  const auto eq = edit.find('=');
  if (eq == std::string::npos) {
    throw InputError(fmt::format("--edit: '{}' is not KEY=NUMBER", edit));
  }
  const std::string key = edit.substr(0, eq);
  const std::string_view text = std::string_view(edit).substr(eq + 1);
  if (key == "count") {
    const std::uint64_t count = whole_number(text, edit, "fill.count");
    if (count > 100'000'000) {  // before it becomes a size_t anywhere else
      throw InputError(
          fmt::format("--edit '{}': fill.count: {} is more than 1e8 particles", edit, count));
    }
    scene.fill.count = static_cast<std::size_t>(count);
  } else if (key == "seed") {
    scene.fill.seed = whole_number(text, edit, "fill.seed");
  } else if (double* field = edit_field(scene, key)) {
    *field = number(text, edit);
  } else if (key == "rpm") {
    scene.drum.omega = number(text, edit) * 2.0 * std::numbers::pi / 60.0;
  } else {
    throw InputError(fmt::format(
        "--edit: unknown key in '{}' (omega, rpm, friction, restitution, wall_friction, count, "
        "fill_fraction, seed, settle_time)",
        edit));
  }
  validate(scene, fmt::format("--edit '{}'", edit));
}

}  // namespace drumlab::gui
