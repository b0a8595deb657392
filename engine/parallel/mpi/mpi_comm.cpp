#include "engine/parallel/mpi/mpi_comm.hpp"

#include <algorithm>
#include <numeric>

#include "engine/types.hpp"

namespace drumlab {

namespace {

/// Adds the seconds of its lifetime to `total`.
struct Timed {
  double& total;
  double start = MPI_Wtime();
  explicit Timed(double& t) : total(t) {}
  ~Timed() { total += MPI_Wtime() - start; }
  Timed(const Timed&) = delete;
  Timed& operator=(const Timed&) = delete;
};

/// The largest piece of one MPI call on bytes (its counts are ints).
constexpr std::size_t kPiece = std::size_t{1} << 30;

std::vector<int> displacements(const std::vector<int>& counts) {
  std::vector<int> d(counts.size(), 0);
  if (!counts.empty()) std::partial_sum(counts.begin(), counts.end() - 1, d.begin() + 1);
  return d;
}

}  // namespace

MpiComm::MpiComm(MPI_Comm comm) : comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

double MpiComm::max(double v) {
  Timed t(seconds_);
  double r = v;
  MPI_Allreduce(&v, &r, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return r;
}

double MpiComm::min(double v) {
  Timed t(seconds_);
  double r = v;
  MPI_Allreduce(&v, &r, 1, MPI_DOUBLE, MPI_MIN, comm_);
  return r;
}

double MpiComm::sum(double v) {
  Timed t(seconds_);
  double r = v;
  MPI_Allreduce(&v, &r, 1, MPI_DOUBLE, MPI_SUM, comm_);
  return r;
}

std::uint64_t MpiComm::sum(std::uint64_t v) {
  Timed t(seconds_);
  std::uint64_t r = v;
  MPI_Allreduce(&v, &r, 1, MPI_UINT64_T, MPI_SUM, comm_);
  return r;
}

void MpiComm::max(std::span<double> v) {
  Timed t(seconds_);
  std::vector<double> r(v.size());
  MPI_Allreduce(v.data(), r.data(), static_cast<int>(v.size()), MPI_DOUBLE, MPI_MAX, comm_);
  std::copy(r.begin(), r.end(), v.begin());
}

void MpiComm::min(std::span<double> v) {
  Timed t(seconds_);
  std::vector<double> r(v.size());
  MPI_Allreduce(v.data(), r.data(), static_cast<int>(v.size()), MPI_DOUBLE, MPI_MIN, comm_);
  std::copy(r.begin(), r.end(), v.begin());
}

void MpiComm::sum(std::span<std::uint64_t> v) {
  Timed t(seconds_);
  std::vector<std::uint64_t> r(v.size());
  MPI_Allreduce(v.data(), r.data(), static_cast<int>(v.size()), MPI_UINT64_T, MPI_SUM, comm_);
  std::copy(r.begin(), r.end(), v.begin());
}

void MpiComm::agreed_sum(std::span<double> v) {
  Timed t(seconds_);
  std::vector<double> r(v.size());
  MPI_Reduce(v.data(), r.data(), static_cast<int>(v.size()), MPI_DOUBLE, MPI_SUM, 0, comm_);
  MPI_Bcast(r.data(), static_cast<int>(r.size()), MPI_DOUBLE, 0, comm_);
  std::copy(r.begin(), r.end(), v.begin());
}

void MpiComm::min3(double v[3]) {
  Timed t(seconds_);
  double r[3];
  MPI_Allreduce(v, r, 3, MPI_DOUBLE, MPI_MIN, comm_);
  for (int k = 0; k < 3; ++k) v[k] = r[k];
}

std::vector<std::vector<std::byte>> MpiComm::all_to_all(
    const std::vector<std::vector<std::byte>>& out) {
  Timed t(seconds_);
  std::vector<int> send_counts(static_cast<std::size_t>(size_)), recv_counts(send_counts.size());
  std::vector<std::byte> send;
  for (std::size_t q = 0; q < out.size(); ++q) {
    send_counts[q] = static_cast<int>(out[q].size());
    send.insert(send.end(), out[q].begin(), out[q].end());
  }
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm_);
  const auto sd = displacements(send_counts), rd = displacements(recv_counts);
  std::vector<std::byte> recv(static_cast<std::size_t>(rd.back() + recv_counts.back()));
  MPI_Alltoallv(send.data(), send_counts.data(), sd.data(), MPI_BYTE, recv.data(),
                recv_counts.data(), rd.data(), MPI_BYTE, comm_);
  std::vector<std::vector<std::byte>> in(static_cast<std::size_t>(size_));
  for (std::size_t q = 0; q < in.size(); ++q) {
    in[q].assign(recv.begin() + rd[q], recv.begin() + rd[q] + recv_counts[q]);
  }
  return in;
}

namespace {

template <class T>
std::vector<T> gather_all(std::span<const T> mine, MPI_Datatype type, MPI_Comm comm, int size) {
  const int n = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(size));
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  const auto d = displacements(counts);
  std::vector<T> all(static_cast<std::size_t>(d.back() + counts.back()));
  MPI_Allgatherv(mine.data(), n, type, all.data(), counts.data(), d.data(), type, comm);
  return all;
}

}  // namespace

std::vector<std::uint64_t> MpiComm::all_gather(std::span<const std::uint64_t> mine) {
  Timed t(seconds_);
  return gather_all(mine, MPI_UINT64_T, comm_, size_);
}

std::vector<double> MpiComm::all_gather(std::span<const double> mine) {
  Timed t(seconds_);
  return gather_all(mine, MPI_DOUBLE, comm_, size_);
}

std::vector<std::byte> MpiComm::all_gather(std::span<const std::byte> mine) {
  Timed t(seconds_);
  return gather_all(mine, MPI_BYTE, comm_, size_);
}

std::vector<std::vector<std::byte>> MpiComm::gather(std::span<const std::byte> mine) {
  Timed t(seconds_);
  const int n = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(size_));
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm_);
  const auto d = displacements(counts);
  std::vector<std::byte> all(rank_ == 0 ? static_cast<std::size_t>(d.back() + counts.back()) : 0);
  MPI_Gatherv(mine.data(), n, MPI_BYTE, all.data(), counts.data(), d.data(), MPI_BYTE, 0, comm_);
  std::vector<std::vector<std::byte>> out;
  if (rank_ != 0) return out;
  out.resize(counts.size());
  for (std::size_t q = 0; q < out.size(); ++q) {
    out[q].assign(all.begin() + d[q], all.begin() + d[q] + counts[q]);
  }
  return out;
}

void MpiComm::broadcast(std::vector<std::byte>& bytes, int root) {
  Timed t(seconds_);
  auto n = static_cast<std::uint64_t>(bytes.size());
  MPI_Bcast(&n, 1, MPI_UINT64_T, root, comm_);
  bytes.resize(static_cast<std::size_t>(n));
  for (std::size_t at = 0; at < bytes.size(); at += kPiece) {
    const auto count = static_cast<int>(std::min(kPiece, bytes.size() - at));
    MPI_Bcast(bytes.data() + at, count, MPI_BYTE, root, comm_);
  }
}

std::vector<std::byte> MpiComm::send_receive(int to, std::span<const std::byte> bytes, int from) {
  Timed t(seconds_);
  const auto out = static_cast<std::uint64_t>(bytes.size());
  std::uint64_t in = 0;
  MPI_Sendrecv(&out, 1, MPI_UINT64_T, to, 12, &in, 1, MPI_UINT64_T, from, 12, comm_,
               MPI_STATUS_IGNORE);
  std::vector<std::byte> got(static_cast<std::size_t>(in));
  std::vector<MPI_Request> requests;
  for (std::size_t at = 0; at < got.size(); at += kPiece) {
    requests.emplace_back();
    MPI_Irecv(got.data() + at, static_cast<int>(std::min(kPiece, got.size() - at)), MPI_BYTE, from,
              13, comm_, &requests.back());
  }
  for (std::size_t at = 0; at < bytes.size(); at += kPiece) {
    requests.emplace_back();
    MPI_Isend(bytes.data() + at, static_cast<int>(std::min(kPiece, bytes.size() - at)), MPI_BYTE,
              to, 13, comm_, &requests.back());
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  return got;
}

std::string MpiComm::first_error(const std::string& mine) {
  int me = mine.empty() ? size_ : rank_, first = size_;
  {
    Timed t(seconds_);
    MPI_Allreduce(&me, &first, 1, MPI_INT, MPI_MIN, comm_);
  }
  if (first == size_) return {};
  const auto* b = reinterpret_cast<const std::byte*>(mine.data());
  std::vector<std::byte> bytes(b, b + (rank_ == first ? mine.size() : 0));
  broadcast(bytes, first);
  return std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

void MpiComm::agree(const std::function<void()>& work) {
  std::string error;
  try {
    work();
  } catch (const InputError& e) {
    error = e.what();
  }
  error = first_error(error);
  if (!error.empty()) throw InputError(error);
}

void MpiComm::send(int to, std::span<const std::byte> bytes) {
  Timed t(seconds_);
  const auto n = static_cast<std::uint64_t>(bytes.size());
  MPI_Send(&n, 1, MPI_UINT64_T, to, 11, comm_);
  for (std::size_t at = 0; at < bytes.size(); at += kPiece) {
    const auto count = static_cast<int>(std::min(kPiece, bytes.size() - at));
    MPI_Send(bytes.data() + at, count, MPI_BYTE, to, 11, comm_);
  }
}

std::vector<std::byte> MpiComm::receive(int from) {
  Timed t(seconds_);
  std::uint64_t n = 0;
  MPI_Recv(&n, 1, MPI_UINT64_T, from, 11, comm_, MPI_STATUS_IGNORE);
  std::vector<std::byte> bytes(static_cast<std::size_t>(n));
  for (std::size_t at = 0; at < bytes.size(); at += kPiece) {
    const auto count = static_cast<int>(std::min(kPiece, bytes.size() - at));
    MPI_Recv(bytes.data() + at, count, MPI_BYTE, from, 11, comm_, MPI_STATUS_IGNORE);
  }
  return bytes;
}

namespace {

template <class T>
void point_to_point(const std::vector<std::vector<T>>& send, std::vector<std::vector<T>>& recv,
                    MPI_Datatype type, MPI_Comm comm) {
  std::vector<MPI_Request> requests;
  for (std::size_t q = 0; q < recv.size(); ++q) {
    if (recv[q].empty()) continue;
    requests.emplace_back();
    MPI_Irecv(recv[q].data(), static_cast<int>(recv[q].size()), type, static_cast<int>(q), 7, comm,
              &requests.back());
  }
  for (std::size_t q = 0; q < send.size(); ++q) {
    if (send[q].empty()) continue;
    requests.emplace_back();
    MPI_Isend(send[q].data(), static_cast<int>(send[q].size()), type, static_cast<int>(q), 7, comm,
              &requests.back());
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
}

}  // namespace

void MpiComm::exchange(const std::vector<std::vector<double>>& send,
                       std::vector<std::vector<double>>& recv) {
  Timed t(seconds_);
  point_to_point(send, recv, MPI_DOUBLE, comm_);
}

void MpiComm::exchange(const std::vector<std::vector<std::uint64_t>>& send,
                       std::vector<std::vector<std::uint64_t>>& recv) {
  Timed t(seconds_);
  point_to_point(send, recv, MPI_UINT64_T, comm_);
}

}  // namespace drumlab
