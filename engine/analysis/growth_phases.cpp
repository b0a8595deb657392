#include "engine/analysis/growth_phases.hpp"

#include <algorithm>

namespace drumlab {

std::vector<GrowthPhase> growth_phases(std::span<const AgglomerateStats> rows) {
  std::vector<GrowthPhase> out;
  const auto first =
      std::find_if(rows.begin(), rows.end(), [](const AgglomerateStats& r) { return r.count > 0; });
  if (first == rows.end()) return out;
  const auto start = static_cast<std::size_t>(first - rows.begin());
  const std::size_t end = rows.size() - 1;
  std::size_t most = 0;
  double d50_max = rows[start].d50;
  for (std::size_t k = start; k <= end; ++k) {
    most = std::max(most, rows[k].count);
    d50_max = std::max(d50_max, rows[k].d50);
  }
  std::size_t nucleated = start;
  while (nucleated < end &&
         static_cast<double>(rows[nucleated].count) < 0.9 * static_cast<double>(most)) {
    ++nucleated;
  }
  out.push_back({"nucleation", start, nucleated});
  const double d50_start = rows[start].d50;
  const double rise = d50_max - d50_start;
  if (!(rise > 0.0) || nucleated == end) return out;
  std::size_t grown = nucleated;
  while (grown < end && rows[grown].d50 < d50_start + 0.9 * rise) ++grown;
  if (grown > nucleated) out.push_back({"growth", nucleated, grown});
  if (grown < end) out.push_back({"consolidation", grown, end});
  return out;
}

}  // namespace drumlab
