#pragma once
// The chart of `drumlab law`: normal force against surface gap for the approach and the retreat
// branch of a probed contact law (engine/contact/law_probe.hpp), the rupture marked by a vertical
// line, written as PNG with the XY charts of render/xy_chart.hpp.
#include <filesystem>

#include "engine/contact/law_probe.hpp"

namespace drumlab::render {

/// Writes `file` (PNG). Throws InputError if it cannot be written.
void write_law_chart(const LawCurve& curve, const std::filesystem::path& file);

}  // namespace drumlab::render
