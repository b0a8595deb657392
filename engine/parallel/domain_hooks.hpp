#pragma once
// The seam between a Simulation and a domain decomposition over MPI ranks (engine/parallel/mpi/,
// built into drumlab-mpi only). A rank's Simulation holds its owned particles and, interleaved in
// the serial run's order, its ghosts (Simulation::ghost_mask()). The hooks make every global
// decision global and keep the ghosts current; a serial run has none, so none of this runs there.
#include <cstdint>
#include <span>

namespace drumlab {

class BridgeEventHooks;
class Simulation;

class DomainHooks {
 public:
  virtual ~DomainHooks() = default;
  /// Reductions over all ranks (every rank calls them at the same point of the run).
  virtual double max(double v) = 0;
  /// Element-wise maxima of a few values in one reduction.
  virtual void max(std::span<double> v) = 0;
  virtual double min(double v) = 0;
  virtual double sum(double v) = 0;
  virtual std::uint64_t sum(std::uint64_t v) = 0;
  /// At a re-ordering step (performance.sort_every), in place of the serial Morton re-ordering.
  virtual void reorder(Simulation& sim) = 0;
  /// Between the drift and the search of every step: the ghosts' positions, velocities and
  /// angular velocities from their owners (and migration with a new ghost layer when due).
  /// `moved`: a bound on how far any particle of any rank moved in this drift (m).
  virtual void refresh_ghosts(Simulation& sim, double moved) = 0;
  /// The replay of the liquid's bridge events across ranks (parallel/bridge_events.hpp), which
  /// Simulation::compute_forces runs between the cohesive parts' parallel and ordered passes of
  /// a scene with liquid migration; nullptr where the ranks' own films suffice (one rank).
  virtual BridgeEventHooks* bridge_events() { return nullptr; }
};

}  // namespace drumlab
