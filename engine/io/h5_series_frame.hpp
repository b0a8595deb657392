#pragma once
// One frame of a Simulation into an HDF5 series (engine/io/h5_series.hpp), as `drumlab run --h5`
// and `drumlab-mpi run --h5` both write it: a scene with bonds (scene_has_bonds) with its bond
// graph and agglomerate labels, any other scene with its particles only.
#include <vector>

#include "engine/analysis/granule_criterion.hpp"
#include "engine/contact/bond.hpp"
#include "engine/io/h5_series.hpp"

namespace drumlab {

class Simulation;

/// Appends sim's current state to `series`. The agglomerate labels use the criterion
/// granule_options(scene omega, granule) (engine/analysis/agglomerates.hpp); `bonds` is
/// scratch, kept by the caller so that a long series does not reallocate it every frame.
void write_series_frame(H5Series& series, const Simulation& sim, const GranuleCriterion& granule,
                        std::vector<Bond>& bonds);

}  // namespace drumlab
