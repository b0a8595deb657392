#include "engine/session/team_chooser.hpp"

#include <fmt/format.h>

namespace drumlab {

std::string team_report(const TeamChooser& t) {
  return fmt::format("adaptive: {} thread(s) in {} of {} windows of {} steps, 1 in {}", t.threads(),
                     t.full_windows(), t.full_windows() + t.single_windows(),
                     TeamChooser::kWindowSteps, t.single_windows());
}

}  // namespace drumlab
