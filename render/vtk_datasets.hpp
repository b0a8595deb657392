#pragma once
// VTK datasets built from the simulation's public state (read only), for the VTU/PVD series.
#include <cstdint>
#include <span>

#include <vtkSmartPointer.h>

#include "engine/io/h5_series.hpp"
#include "engine/simulation.hpp"

class vtkImageData;
class vtkPolyData;
class vtkUnstructuredGrid;

namespace drumlab::render {

/// Point names of the particle dataset, in order.
inline constexpr const char* kParticleArrays[] = {
    "id", "radius", "size_class", "velocity", "speed", "angular_velocity", "force", "coordination"};

/// One point (and one vertex cell) per particle, at its centre, with the arrays of
/// kParticleArrays: id (UInt32), radius (m), size_class (UInt8), velocity (m/s), speed (m/s),
/// angular_velocity (rad/s), force (N, the engine's contact force, pairs and walls, without
/// gravity), coordination (UInt32, particle-particle contacts with overlap > 0). A scene with
/// bonds (scene_has_bonds) adds agglomerate_id (UInt32, engine/analysis/agglomerates.hpp, with the
/// criterion of granule_age: see granule_options) and liquid_volume (m^3, the film; 0 without one).
vtkSmartPointer<vtkUnstructuredGrid> particles_dataset(const Simulation& sim,
                                                       double granule_age = -1.0);

/// The per-particle fields a particle dataset is built from, as plain spans over one storage
/// order. position, id, radius, size_class, velocity and omega are required; force and
/// coordination are written when non-empty; agglomerate_id and liquid_volume together, when
/// non-empty.
struct ParticleFields {
  std::span<const Vec3> position, velocity, omega, force;
  std::span<const double> radius;
  std::span<const std::uint32_t> id;
  std::span<const std::uint8_t> size_class;
  std::span<const std::uint32_t> coordination;
  std::span<const std::uint32_t> agglomerate_id;
  std::span<const double> liquid_volume;
};
vtkSmartPointer<vtkUnstructuredGrid> particles_dataset(const ParticleFields& f);

/// A frame of an HDF5 series (engine/io/h5_series.hpp) as a particle dataset: the arrays of
/// kParticleArrays the series stores (no force, no coordination), and agglomerate_id and
/// liquid_volume for a frame with a bond graph.
vtkSmartPointer<vtkUnstructuredGrid> particles_dataset(const SeriesFrame& frame);

/// The bond graph of a series frame as lines from centre to centre (minimum image across
/// periodic ends, as contacts_dataset). Cell data: bridge_volume (m^3), bridge_force (N,
/// attractive, >= 0), age (s), id_a, id_b (stable ids). Empty for a frame without bonds.
vtkSmartPointer<vtkPolyData> bonds_dataset(const SeriesFrame& frame);

/// The analytic drum wall as a surface: the cylinder (quads) and, unless the ends are periodic,
/// the two end caps (polygons). Cell data: part (0 cylinder, 1 cap z = 0, 2 cap z = H) and
/// marker (1 on a stripe of the cylinder that turns with the drum angle, so rotation is visible).
/// Field data: drum_angle (rad), drum_omega (rad/s).
vtkSmartPointer<vtkPolyData> drum_dataset(const Simulation& sim, int segments = 96);

/// The particle-particle contacts of the current state as lines from centre to centre (minimum
/// image across periodic ends). Cell data: force_magnitude (N), force (N, on the first particle),
/// id_a, id_b (stable ids). A scene with bonds also has a line for every bond whose spheres do
/// not touch (force 0) and the cell data bridge_volume (m^3) and bridge_force (N, attractive,
/// >= 0), 0 on a line without a bond.
vtkSmartPointer<vtkPolyData> contacts_dataset(const Simulation& sim);

/// The contact-search grid of the last step with the particles per cell as cell data "particles"
/// (UInt32). Returns null if the search method has no grid (brute force). Throws InputError if the
/// grid has more than max_cells cells.
vtkSmartPointer<vtkImageData> grid_dataset(const Simulation& sim,
                                           std::size_t max_cells = 32u << 20);

}  // namespace drumlab::render
