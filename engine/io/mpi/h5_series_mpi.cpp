#include "engine/io/mpi/h5_series_mpi.hpp"

#include "engine/io/mpi/h5_mpi.hpp"
#include "engine/parallel/mpi/bond_frame_mpi.hpp"

namespace drumlab {

H5Series::Access mpi_series_access(MpiComm& comm, const std::filesystem::path& file) {
  const MPI_Comm c = comm.comm();
  h5::on_root(c, [&] { h5::check_writable(file); });
  H5Series::Access a;
  a.create = [c](const std::filesystem::path& f) {
    return h5::create_mpi_file(c, f, h5::FileFormat::streamed);
  };
  a.open = [c](const std::filesystem::path& f) { return h5::open_mpi_file_rw(c, f); };
  a.close = [c](h5::Handle& h, const std::filesystem::path& f) { h5::close_mpi_file(c, h, f); };
  const std::uint64_t root_row[] = {0};
  a.scalar = h5::rows_of(c, h5::collective_transfer(),
                         std::span<const std::uint64_t>(root_row, comm.rank() == 0 ? 1 : 0), 1);
  a.rows = h5::rows_of(c, h5::collective_transfer(), {}, 0);
  a.root = comm.rank() == 0;
  return a;
}

void write_frame_mpi(H5Series& series, MpiDomain& domain, const Simulation& sim,
                     const GranuleCriterion& granule) {
  MpiComm& comm = domain.comm();
  const SimulationState local = sim.state();
  const h5::OwnedParticles o = h5::owned_particles(comm, local, sim.ghost_mask(), domain.slots());
  series.set_rows(h5::rows_of(comm.comm(), h5::collective_transfer(), o.slot, o.total));
  if (!scene_has_bonds(sim.scene())) {
    series.write_frame(o.particles, local.time, local.steps);
    return;
  }
  const double omega = sim.scene().drum.omega;
  MpiBondFrame f = mpi_bond_frame(domain, sim, granule_options(omega, granule));
  const SeriesBondFrame b{std::move(f.bonds),
                          f.label,
                          sim.search_input().period_z.value_or(0.0),
                          omega,
                          f.wall_liquid,
                          h5::rows_of(comm.comm(), h5::collective_transfer(), f.row, f.total)};
  series.write_frame(o.particles, local.time, local.steps, &b);
}

}  // namespace drumlab
