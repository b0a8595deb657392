#include "engine/io/h5_series_frame.hpp"

#include "engine/analysis/agglomerates.hpp"
#include "engine/simulation.hpp"

namespace drumlab {

void write_series_frame(H5Series& series, const Simulation& sim, const GranuleCriterion& granule,
                        std::vector<Bond>& bonds) {
  if (!scene_has_bonds(sim.scene())) {  // a dry scene's series: the particles only
    series.write_frame(sim.particles(), sim.time(), sim.steps());
    return;
  }
  const double omega = sim.scene().drum.omega;
  const AgglomerateInput in = agglomerate_input(sim, bonds);
  const AgglomerateFrame frame = find_agglomerates(in, granule_options(omega, granule));
  SeriesBondFrame b{series_bond_rows(sim.particles(), bonds), frame.label, in.period, omega,
                    in.wall_liquid};
  b.spray = in.spray;
  series.write_frame(sim.particles(), sim.time(), sim.steps(), &b);
}

}  // namespace drumlab
