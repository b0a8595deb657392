#pragma once
// A frame of a running simulation as plain data: what a picture, a panel or a plot of it needs,
// copied between steps so that another thread can show it while the simulation steps on. The
// workbench's simulation thread takes one after every chunk of steps and hands it to the UI
// thread under a mutex; the renderer draws from it (render::DrumView::render(const
// FrameSnapshot&)), so a picture of a snapshot and of the simulation it was taken from are the
// same. Nothing here refers back to the Simulation.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/mesh/wall_meshes.hpp"
#include "engine/search/contact_search.hpp"
#include "engine/simulation.hpp"

namespace drumlab {

/// What to take besides the particles and the clock.
class CellGridSearch;

struct SnapshotRequest {
  /// Stable id of the particle whose search is replayed (ContactSearch::visit); none: no visit.
  /// An id the simulation does not have gives no visit either (the renderer's index_of_id says so).
  std::optional<Index> focus_id;
  /// Also replay the focus particle's search with each of these methods on the same positions
  /// (each built once on the current state, read-only): the teaching mode's m1..m5.
  std::vector<std::string> compare_methods;
  bool diagnostics = true;  ///< energies and health (Simulation::diagnostics, O(N + contacts))
};

/// Counters of the last step summed over the particles of one size class.
struct ClassCounters {
  std::string name;                 ///< the scene's class name
  double radius = 0.0;              ///< m (a size distribution: its mean radius)
  std::size_t particles = 0;        ///< of this class
  std::uint64_t cells_visited = 0;  ///< by these particles' searches
  std::uint64_t pairs_tested = 0;   ///< by these particles' searches
  std::uint64_t contacts = 0;       ///< sum of their coordination numbers
};

/// One method's replay of the focus particle's search (SnapshotRequest::compare_methods).
struct MethodVisit {
  std::string method;
  SearchVisit visit;
};

struct FrameSnapshot {
  // The scene (constant during a run).
  std::string scene_name;
  double drum_radius = 0.0;  ///< m
  double drum_depth = 0.0;   ///< m
  double scene_omega = 0.0;  ///< the scene's drum angular velocity, rad/s (0 is not "settling")
  std::vector<ParticleClass> classes;
  std::vector<SprayConfig> sprays;  ///< the scene's nozzles ([[spray]])
  /// The triangle walls ([[wall.mesh]], [[wall.lifters]]) in the drum's frame at angle 0, shared
  /// with the simulation, never changed (Simulation::wall_meshes); null without. A mesh attached
  /// to the drum stands at Rz(drum_angle) x, one fixed in the lab as it is.
  std::shared_ptr<const std::vector<WallMesh>> meshes;

  // The particles, in storage order (storage slots change when the engine re-sorts; ids do not).
  std::vector<Vec3> position;  ///< m
  std::vector<Vec3> velocity;  ///< m/s
  std::vector<Vec3> omega;     ///< rad/s
  std::vector<double> radius;  ///< m
  std::vector<Index> id;
  std::vector<std::uint8_t> size_class;
  std::vector<std::uint32_t> coordination;  ///< Simulation::coordination_numbers
  std::vector<Vec3> droplets;               ///< airborne binder droplets (m), [[spray]] only

  // The clock and the drum.
  double time = 0.0;        ///< s
  double dt = 0.0;          ///< s
  double drum_angle = 0.0;  ///< rad
  double drum_omega = 0.0;  ///< rad/s, now (0 while settling)
  /// A planetary drum's carrier ([drum.orbit]): R_o (0 without an orbit), the arm's angle and
  /// the drum centre's offset c from the central axis (Simulation::carrier_offset).
  double orbit_radius = 0.0;           ///< m
  double carrier_angle = 0.0;          ///< rad
  Vec3 carrier_offset = Vec3::Zero();  ///< m
  std::uint64_t steps = 0;

  // The search of the last step.
  std::string search_name;
  std::string search_description;
  SearchCounters counters;       ///< the last step's
  SearchCounters totals;         ///< summed since construction
  SearchTimings search_timings;  ///< the last step's build / visit split
  StepTimers timers;             ///< summed since construction
  std::vector<ClassCounters> per_class;
  /// The cell grid the search laid (a cell grid's own, a Verlet list's builder's if that is a
  /// cell grid; drawn_cell_grid); none for brute force and the multi-level grid.
  std::optional<GridGeometry> grid;
  /// The search is a Verlet list: its structure is the listed pairs (`grid` is its builder's, and
  /// the last step visited cells only if it rebuilt the list).
  bool lists_pairs = false;

  std::optional<Diagnostics> diagnostics;

  // The focus particle (SnapshotRequest::focus_id), when it exists.
  std::optional<Index> focus_index;        ///< its storage index in this snapshot
  std::optional<SearchVisit> focus_visit;  ///< its search by the active method
  std::vector<MethodVisit> compare_visits;

  /// What the picture is coloured by, one value per particle, and the name of that quantity:
  /// filled by the renderer's caller (render::view_snapshot), which knows the colour modes; empty
  /// from take_snapshot alone.
  std::vector<double> color_values;
  std::string color_by;

  std::size_t size() const { return position.size(); }
};

/// The active cell grid of `search` (a cell grid's own; a Verlet list's builder's if that is a
/// cell grid); nullptr for the others.
const CellGridSearch* drawn_cell_grid(const ContactSearch& search);

/// The cell of `x` in `g`, clamped to the grid: the binning of CellGridSearch (for pictures and
/// the teaching mode; the search itself bins in its own loop).
CellCoord cell_containing(const GridGeometry& g, const Vec3& x);

/// Copies the frame between steps (on the thread that steps the simulation). Throws InputError if
/// a compare method is unknown.
FrameSnapshot take_snapshot(const Simulation& sim, const SnapshotRequest& request);

}  // namespace drumlab
