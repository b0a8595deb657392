#include "app/gui/gui_options.hpp"

#include <charconv>

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

}  // namespace drumlab::gui
