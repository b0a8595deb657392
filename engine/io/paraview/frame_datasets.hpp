#pragma once
// The datasets of a VTU/PVD frame, from the simulation's public state (read only) or from a frame
// of an HDF5 series, without VTK (dataset.hpp): render/ writes them with VTK, drumlab-mpi with
// xml_writer.hpp. Every array is defined here once.
#include <cstdint>
#include <span>

#include "engine/analysis/granule_criterion.hpp"
#include "engine/io/paraview/dataset.hpp"
#include "engine/io/series_frame.hpp"
#include "engine/simulation.hpp"

namespace drumlab::paraview {

/// Point data names of the particle dataset, in order.
inline constexpr const char* kParticleArrays[] = {
    "id", "radius", "size_class", "velocity", "speed", "angular_velocity", "force", "coordination"};

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

/// One point (and one vertex) per particle, at its centre, with the point data of
/// kParticleArrays: id (UInt32), radius (m), size_class (UInt8), velocity (m/s), speed (m/s),
/// angular_velocity (rad/s), force (N), coordination (UInt32); then agglomerate_id (UInt32) and
/// liquid_volume (m^3) where given. Active scalars radius, vectors velocity.
DataSet particles(const ParticleFields& f);

/// The particles of the current state: force is the engine's contact force (pairs and walls,
/// without gravity), coordination the particle-particle contacts with overlap > 0. A scene with
/// bonds (scene_has_bonds) adds agglomerate_id (engine/analysis/agglomerates.hpp, with the
/// criterion of granule: see granule_options) and liquid_volume (the film; 0 without one).
DataSet particles(const Simulation& sim, const GranuleCriterion& granule = {});

/// A frame of an HDF5 series: the arrays of kParticleArrays the series stores (no force, no
/// coordination), and agglomerate_id and liquid_volume for a frame with a bond graph.
DataSet particles(const SeriesFrame& frame);

/// The analytic drum wall as a surface: the cylinder (quads) and, unless the ends are periodic,
/// the two end caps (polygons). Cell data: part (UInt8: 0 cylinder, 1 cap z = 0, 2 cap z = H)
/// and marker (UInt8: 1 on a stripe of the cylinder that turns with the drum angle, so rotation
/// is visible). Field data: drum_angle (rad), drum_omega (rad/s).
DataSet drum(const Simulation& sim, int segments = 96);

/// The particle-particle contacts of the current state as lines from centre to centre (minimum
/// image across periodic ends). Cell data: force_magnitude (N), force (N, on the first particle),
/// id_a, id_b (stable ids). A scene with bonds also has a line for every bond whose spheres do
/// not touch (force 0) and the cell data bridge_volume (m^3) and bridge_force (N, attractive,
/// >= 0), 0 on a line without a bond. Active scalars force_magnitude.
DataSet contacts(const Simulation& sim);

/// The airborne binder droplets of a scene with [[spray]] as points (an empty set without).
/// Point data: velocity (m/s), radius (m), spray (UInt32, the nozzle's index in the scene).
DataSet droplets(const Simulation& sim);

/// The nozzles of a scene with [[spray]] and the spray each opens: lines from the nozzle along
/// the edge of its cone (16 rays and the ring joining their ends) or across its fan (9 rays and
/// the arc), a quarter of the drum diameter long, and its axis. Cell data: spray (UInt32).
DataSet nozzles(std::span<const SprayConfig> sprays, double drum_diameter);

/// The bond graph of a series frame as lines from centre to centre (minimum image across
/// periodic ends, as contacts). Cell data: bridge_volume (m^3), bridge_force (N, attractive,
/// >= 0), age (s), id_a, id_b (stable ids). Active scalars bridge_force.
DataSet bonds(const SeriesFrame& frame);

}  // namespace drumlab::paraview
