#pragma once
// The stages of wet granulation read off a granule-size curve (the rows of an agglomerate table,
// `drumlab analyze --growth`), in the vocabulary of Iveson et al. 2001 and Mills et al. 2000:
//
// * nucleation: from the first granule (a frame with an agglomerate of size >= 2) until the
//   number of granules first reaches 90 % of its largest value: nuclei appear faster than they
//   merge;
// * growth: from there until the mass-weighted d50 has made 90 % of its rise over the run
//   (from its value at the first granule to its largest): granules grow by layering and
//   coalescence;
// * consolidation: the rest, where d50 changes by less than the last 10 % of its rise while the
//   granules densify and exchange particles.
//
// The thresholds are a reading of the curve, not physics: each phase is named with the frames and
// the liquid added (or the time, without a spray) where it starts and ends, so a reader sees what
// was marked. A phase the curve does not show is left out (d50 that never rises: no growth).
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "engine/analysis/agglomerates.hpp"

namespace drumlab {

struct GrowthPhase {
  std::string name;   ///< "nucleation", "growth" or "consolidation"
  std::size_t first;  ///< first row of the phase
  std::size_t last;   ///< last row of the phase (inclusive)
};

/// The phases of the rows (in time order). Empty if no row has a granule.
std::vector<GrowthPhase> growth_phases(std::span<const AgglomerateStats> rows);

}  // namespace drumlab
