#pragma once
// Agglomerates of one frame: connected components (union-find) of the particles joined by a bond
// (engine/contact/bond.hpp: a liquid bridge or an adhesive contact), and the frame's statistics.
//
// * Agglomerate id: the smallest stable particle id among the members. It stays the same from
//   frame to frame as long as that particle stays in the agglomerate (a granule that grows keeps
//   its id unless it swallows a particle with a smaller id; two that merge keep the smaller id).
//   A free primary (no bond) is an agglomerate of size 1 whose id is its own.
// * Centre: mass-weighted, with the members unwrapped along the bonds (each bond's minimum image
//   across periodic ends, engine/periodic.hpp), so a cluster across the ends is not torn; its z is
//   wrapped back into [0, period).
// * Volume-equivalent diameter: (sum d_i^3)^(1/3), the sphere of the members' solid volume.
// * Liquid held: the members' films (kLiquidFilmArray; absent: 0) plus the volume of every bond
//   with both ends in the agglomerate.
//
// Granule criterion (AgglomerateOptions::min_bond_age). In a dense wet flowing bed every particle
// is bridged to its neighbours, so plain components return one cluster that percolates through
// the bed (Jain et al. 2025, arXiv 2510.04867). A granule is a set of particles whose links have
// survived the shear of the flowing layer; links between neighbours that merely touch in passing
// are young. With min_bond_age = T > 0 only bonds with age >= T join particles. The default T
// (default_granule_age) is one drum revolution 2 pi / |omega|: every particle of a rolling or
// cascading bed crosses the flowing layer at least once per circulation, and a circulation (the
// rigid-body ride in the passive region plus the avalanche) takes less than a revolution, so a
// bond older than that has survived at least one pass through the shear zone. The plain largest
// component is always reported beside it (largest_plain_share) so a percolating network shows.
// The community criterion (AgglomerateOptions::community, engine/analysis/granule_communities.hpp)
// groups the particles by communities of the force-weighted bond network instead.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "engine/analysis/granule_criterion.hpp"
#include "engine/contact/bond.hpp"
#include "engine/scene/scene_config.hpp"
#include "engine/spray/spray_liquid.hpp"
#include "engine/types.hpp"

namespace drumlab {

class Simulation;

/// One frame's particles (storage order) and bonds (storage slots) as the analysis reads them:
/// from a live Simulation (agglomerate_input) or from an HDF5 series frame.
struct AgglomerateInput {
  std::span<const Vec3> position;
  std::span<const double> radius;
  std::span<const double> mass;
  std::span<const std::uint32_t> id;  ///< stable ids
  std::span<const double> film;       ///< liquid film volume per particle (m^3); empty: 0
  std::span<const Bond> bonds;
  double wall_liquid = 0.0;  ///< liquid in bridges with the drum wall (m^3), in no agglomerate
  SprayLiquid spray{};       ///< the spray's terms (scenes with [[spray]])
  double period = 0.0;       ///< z period of periodic ends; <= 0: none
  double time = 0.0;         ///< s
};

struct AgglomerateOptions {
  double min_bond_age = 0.0;  ///< s; 0: plain connected components of all bonds
  bool community = false;     ///< communities of the force-weighted bond network instead
  double resolution = 1.0;    ///< community: the modularity's resolution (> 0)
};

struct Agglomerate {
  std::uint32_t id = 0;             ///< smallest stable particle id among the members
  std::size_t primaries = 0;        ///< member count
  double mass = 0.0;                ///< kg
  double diameter = 0.0;            ///< volume-equivalent diameter (m)
  Vec3 centre = Vec3::Zero();       ///< mass-weighted (m), z wrapped into the period
  double radius_of_gyration = 0.0;  ///< mass-weighted (m)
  double liquid = 0.0;              ///< films + bonds inside (m^3)
};

/// The statistics of a frame (one CSV row of `run --agglomerates` and `analyze`).
struct AgglomerateStats {
  double time = 0.0;
  std::string criterion;    ///< "components", "bond_age>=T" (T in s) or "community(resolution=R)"
  std::size_t count = 0;    ///< agglomerates of size >= 2
  double mean_size = 0.0;   ///< mean primaries of those (0 when there are none)
  std::size_t largest = 0;  ///< primaries of the largest agglomerate (1 without bonds)
  double d10 = 0.0;         ///< mass-weighted percentiles of the volume-equivalent diameter
  double d50 = 0.0;         ///< over all agglomerates, free primaries included (m)
  double d90 = 0.0;
  std::size_t bonds = 0;             ///< bonds in the frame (all ages)
  double free_liquid = 0.0;          ///< sum of the films (m^3)
  double bridge_liquid = 0.0;        ///< sum of the bond volumes (m^3)
  double wall_liquid = 0.0;          ///< liquid in wall bridges (m^3): free + bridge + wall
                                     ///< = all the liquid
  double largest_plain_share = 0.0;  ///< share of the particles in the largest plain component
  SprayLiquid
      spray{};  ///< sprayed, airborne and lost liquid (m^3): free + bridge + wall + airborne
                ///< + lost - sprayed = the scene's initial liquid
};

struct AgglomerateFrame {
  std::vector<Agglomerate> agglomerates;  ///< every agglomerate (size 1 included), by id
  std::vector<std::uint32_t> label;       ///< agglomerate id of each particle (storage order)
  std::vector<std::size_t> size_of;       ///< primaries of each particle's agglomerate
  AgglomerateStats stats;
};

/// Whether bond `b` joins its two particles under the age criterion `options` (its age; every
/// bond for components; the community criterion joins by community instead).
bool bond_joins(const Bond& b, const AgglomerateOptions& options);

/// Finds the agglomerates of one frame with the given criterion. Throws std::invalid_argument if
/// the spans disagree in length or a bond names a slot out of range.
AgglomerateFrame find_agglomerates(const AgglomerateInput& in, const AgglomerateOptions& options);

/// Whether a scene can form bonds (today: [liquid]); only such scenes get the bond graph and the
/// agglomerate arrays in their outputs.
bool scene_has_bonds(const SceneConfig& scene);

/// One drum revolution 2 pi / |omega| (s, omega in rad/s); 0 for a drum at rest.
double default_granule_age(double omega);

/// The options of a criterion: age: its age, or for age < 0 (not given) one revolution
/// (default_granule_age; plain components for a drum at rest); components: age 0; community:
/// its resolution. Throws InputError for a resolution that is not positive and finite.
AgglomerateOptions granule_options(double omega, const GranuleCriterion& criterion);

/// The criterion's name as the outputs print it.
std::string criterion_name(const AgglomerateOptions& options);

/// The live frame of `sim`; `bonds` must outlive the returned spans (it is refilled).
AgglomerateInput agglomerate_input(const Simulation& sim, std::vector<Bond>& bonds);

/// Agglomerate id of each particle of `sim` (storage order) with the criterion `granule`
/// (granule_options with the scene's omega): the one quantity the VTU, the HDF5 series and
/// `render --color-by agglomerate` show.
std::vector<std::uint32_t> agglomerate_labels(const Simulation& sim,
                                              const GranuleCriterion& granule);

/// The CSV header and one row (SI units; diameters in m, liquid in m^3, 12 significant digits:
/// free_liquid + bridge_liquid + wall_bridge_liquid + airborne_liquid + lost_liquid
/// - sprayed_liquid is the scene's initial liquid).
std::string agglomerate_csv_header();
std::string agglomerate_csv_row(const AgglomerateStats& s);

}  // namespace drumlab
