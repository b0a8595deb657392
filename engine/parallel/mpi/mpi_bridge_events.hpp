#pragma once
// The ordered pass of the liquid's migration on MPI ranks (engine/parallel/bridge_events.hpp):
// each rank sends its events with an owned first particle and its owned particles' films in any
// of its events, one MPI_Allgatherv a step, and replays all of them (BridgeReplay).
#include <cstdint>
#include <span>
#include <vector>

#include "engine/parallel/bridge_events.hpp"
#include "engine/parallel/mpi/mpi_comm.hpp"

namespace drumlab {

class MpiBridgeEvents final : public BridgeEventHooks {
 public:
  /// `slot`: the serial slot of each local particle (MpiDomain::slots(), increasing); `ghost`: the
  /// rank's Simulation::ghost_mask(). Both are read at every call, so they may change in between.
  MpiBridgeEvents(MpiComm& comm, const std::vector<std::uint64_t>& slot)
      : comm_(comm), slot_(slot) {}
  void set_ghosts(const std::vector<std::uint8_t>* ghost) { ghost_ = ghost; }

  void begin(const LiquidBridge& bridge, std::span<const Event> events,
             const double* film) override;
  bool before(Index i, Index j, double* film) override;
  void end(double* film) override;

  /// Events replayed so far, over all steps (every rank the same).
  std::uint64_t replayed() const { return replayed_; }

 private:
  bool owned(Index i) const { return (*ghost_)[i] == 0; }

  MpiComm& comm_;
  const std::vector<std::uint64_t>& slot_;
  const std::vector<std::uint8_t>* ghost_ = nullptr;
  BridgeReplay replay_;
  std::uint64_t replayed_ = 0;
};

}  // namespace drumlab
