#pragma once
// Granule growth as a PNG (`drumlab analyze --growth`): left, the mass-weighted d10 / d50 / d90
// (mm) against the liquid sprayed (m^3; against time for a run without spray); right, the number
// of granules (size >= 2) and the largest one (primaries); third, d50 and the count against time
// (after the spray stops, time goes on where the liquid axis stands still). The phases of
// engine/analysis/growth_phases.hpp are marked on both by vertical lines at their starts.
#include <filesystem>
#include <vector>

#include "engine/analysis/growth_phases.hpp"

namespace drumlab::render {

/// Writes the chart. Throws InputError if it cannot be written or there are no rows.
void write_growth_chart(const std::vector<AgglomerateStats>& rows,
                        const std::vector<GrowthPhase>& phases, const std::filesystem::path& file);

}  // namespace drumlab::render
