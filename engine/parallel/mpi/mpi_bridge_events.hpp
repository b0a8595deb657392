#pragma once
// The replay of the liquid's bridge events on MPI ranks (engine/parallel/bridge_events.hpp): each
// rank sends its events with an owned first particle and its owned particles' films in any of its
// events, one MPI_Allgatherv a step, and replays all of them (BridgeReplay).
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

  void replay(const LiquidBridge& bridge, std::span<const BridgeEvent> events, const double* film,
              BridgeEventFilms& out) override;

  /// Events replayed so far, over all steps (every rank the same).
  std::uint64_t replayed() const { return replayed_; }

 private:
  bool owned(Index i) const { return (*ghost_)[i] == 0; }
  /// All ranks' events and their owners' films, gathered from this rank's.
  void gather(const LiquidBridge& bridge, std::span<const BridgeEvent> events, const double* film);

  MpiComm& comm_;
  const std::vector<std::uint64_t>& slot_;
  const std::vector<std::uint8_t>* ghost_ = nullptr;
  BridgeReplay replay_;
  std::uint64_t replayed_ = 0;
};

}  // namespace drumlab
