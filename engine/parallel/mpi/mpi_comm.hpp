#pragma once
// Thin MPI helpers for the domain decomposition, each timed: the seconds a rank spends inside MPI
// (waiting for others included) are what the run summary reports as time in communication.
#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace drumlab {

class MpiComm {
 public:
  explicit MpiComm(MPI_Comm comm);
  int rank() const { return rank_; }
  int size() const { return size_; }
  MPI_Comm comm() const { return comm_; }
  double max(double v);
  double min(double v);
  double sum(double v);
  std::uint64_t sum(std::uint64_t v);
  void min3(double v[3]);
  /// Element-wise over ranks, in place.
  void max(std::span<double> v);
  void min(std::span<double> v);
  void sum(std::span<std::uint64_t> v);
  /// Element-wise sums reduced on rank 0 and broadcast from there: the same bits on every rank,
  /// whatever order the reduction adds in (for sums that decide something every rank must agree
  /// on).
  void agreed_sum(std::span<double> v);
  /// Sends out[q] to rank q for every q and returns what each rank sent here, by source.
  std::vector<std::vector<std::byte>> all_to_all(const std::vector<std::vector<std::byte>>& out);
  /// Every rank's `mine`, concatenated in rank order, on every rank.
  std::vector<std::uint64_t> all_gather(std::span<const std::uint64_t> mine);
  std::vector<double> all_gather(std::span<const double> mine);
  std::vector<std::byte> all_gather(std::span<const std::byte> mine);
  /// Every rank's bytes on rank 0, by rank (empty elsewhere).
  std::vector<std::vector<std::byte>> gather(std::span<const std::byte> mine);
  /// Rank `root`'s `bytes` on every rank (resized to fit).
  void broadcast(std::vector<std::byte>& bytes, int root = 0);
  /// The message of the lowest rank whose `mine` is not empty ("" if none): an error met by some
  /// ranks, to be thrown alike on all.
  std::string first_error(const std::string& mine);
  /// Runs `work` on every rank; an InputError that any rank meets in it is thrown on every rank
  /// alike (the lowest such rank's message), so that no rank is left waiting for the others in
  /// a later collective. Collective.
  void agree(const std::function<void()>& work);
  /// Point-to-point bytes of any length (in pieces of at most 1 GiB): send to rank `to`, and what
  /// rank `from` sent here.
  void send(int to, std::span<const std::byte> bytes);
  std::vector<std::byte> receive(int from);
  /// Sends `bytes` to rank `to` and returns what rank `from` sends here at the same time.
  std::vector<std::byte> send_receive(int to, std::span<const std::byte> bytes, int from);
  /// Point-to-point doubles: send[q] to q and recv[q].size() doubles from q, for every q with a
  /// non-empty buffer.
  void exchange(const std::vector<std::vector<double>>& send,
                std::vector<std::vector<double>>& recv);
  void exchange(const std::vector<std::vector<std::uint64_t>>& send,
                std::vector<std::vector<std::uint64_t>>& recv);
  /// Seconds spent inside MPI calls so far.
  double seconds() const { return seconds_; }

 private:
  MPI_Comm comm_;
  int rank_ = 0;
  int size_ = 1;
  double seconds_ = 0.0;
};

}  // namespace drumlab
