#include "engine/io/h5_journal.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "engine/types.hpp"

namespace drumlab::h5 {

namespace {

constexpr std::uint64_t kPage = 4096;
constexpr char kMagic[16] = {'d', 'r', 'u', 'm', 'l', 'a', 'b', ' ',
                             'h', '5', ' ', 'u', 'n', 'd', 'o', '1'};
constexpr std::size_t kHeaderBytes = sizeof kMagic + 2 * sizeof(std::uint64_t);

std::atomic<long> g_fault_at{-1};
std::atomic<long> g_io_count{0};
void (*g_fault_action)() = nullptr;

/// Every write to the disk passes here first (fault injection for the tests).
void io_point() {
  const long at = g_fault_at.load();
  if (at >= 0 && g_io_count.fetch_add(1) == at && g_fault_action) g_fault_action();
}

std::uint64_t fnv1a(const unsigned char* p, std::size_t n, std::uint64_t h) {
  for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ULL;
  return h;
}

std::uint64_t checksum(std::uint64_t a, std::uint64_t b, const unsigned char* p, std::size_t n) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  h = fnv1a(reinterpret_cast<const unsigned char*>(&a), sizeof a, h);
  h = fnv1a(reinterpret_cast<const unsigned char*>(&b), sizeof b, h);
  return fnv1a(p, n, h);
}

/// pread or pwrite of n bytes at `at`, retried until done; false on an error or the end of file.
template <class Byte, class Io>
bool whole(Io io, int fd, Byte* p, std::size_t n, std::uint64_t at) {
  while (n > 0) {
    const ssize_t r = io(fd, p, n, static_cast<off_t>(at));
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return false;
    p += r;
    n -= static_cast<std::size_t>(r);
    at += static_cast<std::uint64_t>(r);
  }
  return true;
}

bool read_all(int fd, void* buf, std::size_t n, std::uint64_t at) {
  return whole(::pread, fd, static_cast<unsigned char*>(buf), n, at);
}

bool write_all(int fd, const void* buf, std::size_t n, std::uint64_t at) {
  return whole(::pwrite, fd, static_cast<const unsigned char*>(buf), n, at);
}

/// A journal's content: the file's length when it was opened and the pages as they were then.
struct Journal {
  bool valid = false;  ///< the header is whole (else no page of the file was written yet)
  std::uint64_t old_length = 0;
  std::map<std::uint64_t, std::vector<unsigned char>> pages;  ///< offset -> old bytes
};

/// Reads a journal up to its first torn or damaged record (a record is appended whole before the
/// bytes it guards are written, so a torn one guarded nothing).
Journal parse_journal(int fd) {
  Journal j;
  unsigned char head[kHeaderBytes];
  if (!read_all(fd, head, sizeof head, 0) || std::memcmp(head, kMagic, sizeof kMagic) != 0)
    return j;
  std::uint64_t check = 0;
  std::memcpy(&j.old_length, head + sizeof kMagic, 8);
  std::memcpy(&check, head + sizeof kMagic + 8, 8);
  if (check != checksum(j.old_length, kPage, nullptr, 0)) return j;
  j.valid = true;
  std::uint64_t at = kHeaderBytes;
  for (;;) {
    std::uint64_t rec[2];
    if (!read_all(fd, rec, sizeof rec, at)) break;
    if (rec[1] == 0 || rec[1] > (std::uint64_t{1} << 32) || rec[0] + rec[1] > j.old_length) break;
    std::vector<unsigned char> bytes(rec[1]);
    std::uint64_t sum = 0;
    if (!read_all(fd, bytes.data(), bytes.size(), at + sizeof rec) ||
        !read_all(fd, &sum, sizeof sum, at + sizeof rec + rec[1]) ||
        sum != checksum(rec[0], rec[1], bytes.data(), bytes.size())) {
      break;
    }
    // Pages are journaled once each; a record never overlaps an earlier one.
    j.pages.emplace(rec[0], std::move(bytes));
    at += sizeof rec + rec[1] + sizeof sum;
  }
  return j;
}

struct State {
  int fd = -1;
  dev_t device = 0;
  ino_t inode = 0;
  haddr_t eoa = 0;
  haddr_t eof = 0;
  // Writing: the journal and the pages of the old file already in it.
  std::string journal;
  int journal_fd = -1;
  std::uint64_t journal_end = 0;
  std::uint64_t old_length = 0;
  std::vector<bool> saved;
  bool failed = false;
  // Reading through a journal in use: the old pages over the file.
  Journal overlay;
};

/// The driver's file: HDF5's public part first, as the VFD interface requires.
struct JournalFile {
  H5FD_t pub;
  State* state;
};

State& state_of(const H5FD_t* f) {
  return *reinterpret_cast<const JournalFile*>(f)->state;
}

/// Copies the old bytes of the pages in [from, to) not copied yet into the journal.
bool save_pages(State& s, std::uint64_t from, std::uint64_t to) {
  to = std::min(to, s.old_length);
  if (s.journal_fd < 0 || from >= to) return true;
  std::uint64_t p = from / kPage;
  const std::uint64_t last = (to - 1) / kPage;
  while (p <= last) {
    if (s.saved[p]) {
      ++p;
      continue;
    }
    std::uint64_t q = p;
    while (q + 1 <= last && !s.saved[q + 1]) ++q;
    const std::uint64_t at = p * kPage;
    const std::uint64_t n = std::min((q + 1) * kPage, s.old_length) - at;
    std::vector<unsigned char> rec(16 + n + 8);
    std::memcpy(rec.data(), &at, 8);
    std::memcpy(rec.data() + 8, &n, 8);
    if (!read_all(s.fd, rec.data() + 16, n, at)) return false;
    const std::uint64_t sum = checksum(at, n, rec.data() + 16, n);
    std::memcpy(rec.data() + 16 + n, &sum, 8);
    io_point();
    if (!write_all(s.journal_fd, rec.data(), rec.size(), s.journal_end)) return false;
    s.journal_end += rec.size();
    for (std::uint64_t k = p; k <= q; ++k) s.saved[k] = true;
    p = q + 1;
  }
  return true;
}

/// Starts a journal for a file opened for writing: written under a temporary name, locked, then
/// renamed into place, so that a reader never finds an unlocked journal of a live writer.
bool start_journal(State& s, const std::string& file) {
  s.journal = file + ".journal";
  const std::string fresh = s.journal + ".new";
  s.journal_fd = ::open(fresh.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (s.journal_fd < 0) return false;
  unsigned char head[kHeaderBytes];
  std::memcpy(head, kMagic, sizeof kMagic);
  const std::uint64_t check = checksum(s.old_length, kPage, nullptr, 0);
  std::memcpy(head + sizeof kMagic, &s.old_length, 8);
  std::memcpy(head + sizeof kMagic + 8, &check, 8);
  if (::flock(s.journal_fd, LOCK_EX | LOCK_NB) != 0 ||
      !write_all(s.journal_fd, head, sizeof head, 0)) {
    ::unlink(fresh.c_str());
    return false;
  }
  io_point();
  if (::rename(fresh.c_str(), s.journal.c_str()) != 0) {
    ::unlink(fresh.c_str());
    return false;
  }
  s.journal_end = sizeof head;
  s.saved.assign((s.old_length + kPage - 1) / kPage, false);
  return true;
}

void release(State* s) {
  if (s->fd >= 0) ::close(s->fd);
  if (s->journal_fd >= 0) ::close(s->journal_fd);
  delete s;
}

H5FD_t* open_file(const char* name, unsigned flags, hid_t /*fapl*/, haddr_t /*maxaddr*/) {
  auto* s = new State;
  const bool writing = (flags & H5F_ACC_RDWR) != 0;
  const std::string journal = std::string(name) + ".journal";
  int mode = writing ? O_RDWR : O_RDONLY;
  if (flags & H5F_ACC_TRUNC) mode |= O_TRUNC;
  if (flags & H5F_ACC_CREAT) mode |= O_CREAT;
  if (flags & H5F_ACC_EXCL) mode |= O_EXCL;
  if (writing && (flags & H5F_ACC_TRUNC)) ::unlink(journal.c_str());  // of the file it replaces
  if (writing && ::access(journal.c_str(), F_OK) == 0) {  // hot or in use: recover_journal first
    release(s);
    return nullptr;
  }
  s->fd = ::open(name, mode | O_CLOEXEC, 0644);
  struct stat st {};
  if (s->fd < 0 || ::fstat(s->fd, &st) != 0) {
    release(s);
    return nullptr;
  }
  s->device = st.st_dev;
  s->inode = st.st_ino;
  s->eof = static_cast<haddr_t>(st.st_size);
  s->old_length = s->eof;
  if (writing && !start_journal(*s, name)) {
    release(s);
    return nullptr;
  }
  if (!writing) {
    const int jfd = ::open(journal.c_str(), O_RDONLY | O_CLOEXEC);
    if (jfd >= 0) {
      s->overlay = parse_journal(jfd);
      ::close(jfd);
      if (s->overlay.valid) s->eof = s->overlay.old_length;
    }
  }
  auto* f = new JournalFile{};
  f->state = s;
  return &f->pub;
}

herr_t close_file(H5FD_t* f) {
  State* s = reinterpret_cast<JournalFile*>(f)->state;
  herr_t status = 0;
  if (s->journal_fd >= 0 && !s->failed) {
    io_point();
    if (::unlink(s->journal.c_str()) != 0) status = -1;  // the commit
  }
  release(s);
  delete reinterpret_cast<JournalFile*>(f);
  return status;
}

int compare(const H5FD_t* a, const H5FD_t* b) {
  const State& x = state_of(a);
  const State& y = state_of(b);
  if (x.device != y.device) return x.device < y.device ? -1 : 1;
  if (x.inode != y.inode) return x.inode < y.inode ? -1 : 1;
  return 0;
}

herr_t query(const H5FD_t* /*f*/, unsigned long* flags) {
  if (flags) {
    *flags = H5FD_FEAT_AGGREGATE_METADATA | H5FD_FEAT_ACCUMULATE_METADATA | H5FD_FEAT_DATA_SIEVE |
             H5FD_FEAT_AGGREGATE_SMALLDATA;
  }
  return 0;
}

haddr_t get_eoa(const H5FD_t* f, H5FD_mem_t /*type*/) {
  return state_of(f).eoa;
}

herr_t set_eoa(H5FD_t* f, H5FD_mem_t /*type*/, haddr_t addr) {
  state_of(f).eoa = addr;
  return 0;
}

haddr_t get_eof(const H5FD_t* f, H5FD_mem_t /*type*/) {
  return state_of(f).eof;
}

herr_t get_handle(H5FD_t* f, hid_t /*fapl*/, void** handle) {
  if (!handle) return -1;
  *handle = &state_of(f).fd;
  return 0;
}

herr_t read(H5FD_t* f, H5FD_mem_t /*type*/, hid_t /*dxpl*/, haddr_t addr, size_t size, void* buf) {
  State& s = state_of(f);
  auto* out = static_cast<unsigned char*>(buf);
  std::size_t done = 0;
  while (done < size) {  // past the end of the file: zeros, as HDF5's sec2 driver reads
    const ssize_t r = ::pread(s.fd, out + done, size - done, static_cast<off_t>(addr + done));
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) return -1;
    if (r == 0) {
      std::memset(out + done, 0, size - done);
      break;
    }
    done += static_cast<std::size_t>(r);
  }
  if (!s.overlay.valid) return 0;
  if (addr + size > s.overlay.old_length) {  // the part a killed writer added
    const std::uint64_t from = std::max<std::uint64_t>(addr, s.overlay.old_length);
    std::memset(out + (from - addr), 0, addr + size - from);
  }
  auto it = s.overlay.pages.upper_bound(addr);
  if (it != s.overlay.pages.begin()) --it;
  for (; it != s.overlay.pages.end() && it->first < addr + size; ++it) {
    const std::uint64_t lo = std::max<std::uint64_t>(it->first, addr);
    const std::uint64_t hi = std::min<std::uint64_t>(it->first + it->second.size(), addr + size);
    if (lo < hi) std::memcpy(out + (lo - addr), it->second.data() + (lo - it->first), hi - lo);
  }
  return 0;
}

herr_t write(H5FD_t* f, H5FD_mem_t /*type*/, hid_t /*dxpl*/, haddr_t addr, size_t size,
             const void* buf) {
  State& s = state_of(f);
  if (!save_pages(s, addr, addr + size)) {
    s.failed = true;
    return -1;
  }
  io_point();
  if (!write_all(s.fd, buf, size, addr)) {
    s.failed = true;
    return -1;
  }
  s.eof = std::max<haddr_t>(s.eof, addr + size);
  return 0;
}

herr_t truncate(H5FD_t* f, hid_t /*dxpl*/, hbool_t /*closing*/) {
  State& s = state_of(f);
  if (s.eoa == s.eof) return 0;
  if (!save_pages(s, s.eoa, s.eof)) {
    s.failed = true;
    return -1;
  }
  io_point();
  if (::ftruncate(s.fd, static_cast<off_t>(s.eoa)) != 0) {
    s.failed = true;
    return -1;
  }
  s.eof = s.eoa;
  return 0;
}

herr_t no_lock(H5FD_t* /*f*/, hbool_t /*rw*/) {
  return 0;
}

herr_t no_unlock(H5FD_t* /*f*/) {
  return 0;
}

H5FD_class_t make_class() {
  H5FD_class_t c{};
  c.name = "drumlab_journal";
  c.maxaddr = (haddr_t{1} << 63) - 1;  // off_t's largest
  c.fc_degree = H5F_CLOSE_WEAK;
  c.open = open_file;
  c.close = close_file;
  c.cmp = compare;
  c.query = query;
  c.get_eoa = get_eoa;
  c.set_eoa = set_eoa;
  c.get_eof = get_eof;
  c.get_handle = get_handle;
  c.read = read;
  c.write = write;
  c.truncate = truncate;
  c.lock = no_lock;
  c.unlock = no_unlock;
  const H5FD_mem_t map[H5FD_MEM_NTYPES] = H5FD_FLMAP_DICHOTOMY;  // as HDF5's sec2 driver
  std::copy(std::begin(map), std::end(map), std::begin(c.fl_map));
  return c;
}

hid_t driver_id() {
  static const H5FD_class_t cls = make_class();
  static const hid_t id = H5FDregister(&cls);
  return id;
}

[[noreturn]] void cannot_recover(const std::filesystem::path& journal, const char* what) {
  throw InputError(fmt::format("{}: cannot roll back the file it guards: {} ({})", journal.string(),
                               what, std::strerror(errno)));
}

}  // namespace

std::filesystem::path journal_path(const std::filesystem::path& file) {
  return file.string() + ".journal";
}

void use_journal_driver(hid_t fapl) {
  if (H5Pset_driver(fapl, driver_id(), nullptr) < 0) {
    throw InputError("cannot set up HDF5's journal driver");
  }
}

JournalState recover_journal(const std::filesystem::path& file) {
  const std::filesystem::path jp = journal_path(file);
  int jfd = ::open(jp.c_str(), O_RDWR | O_CLOEXEC);
  if (jfd < 0 && errno == ENOENT) return JournalState::none;
  if (jfd < 0) return JournalState::in_use;  // not ours to change: read through it
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{jfd};
  if (::flock(jfd, LOCK_EX | LOCK_NB) != 0) return JournalState::in_use;  // its writer lives
  struct stat st {};
  if (::fstat(jfd, &st) != 0) cannot_recover(jp, "stat");
  if (st.st_nlink == 0) return JournalState::none;  // committed while this opened it
  const Journal j = parse_journal(jfd);
  if (j.valid) {
    const int fd = ::open(file.c_str(), O_RDWR | O_CLOEXEC);
    if (fd < 0 && (errno == EACCES || errno == EROFS || errno == EPERM)) {
      return JournalState::in_use;
    }
    if (fd < 0) cannot_recover(jp, "open");
    const Closer file_closer{fd};
    for (const auto& [at, bytes] : j.pages) {
      if (!write_all(fd, bytes.data(), bytes.size(), at)) cannot_recover(jp, "write");
    }
    if (::ftruncate(fd, static_cast<off_t>(j.old_length)) != 0) cannot_recover(jp, "truncate");
    if (::fsync(fd) != 0) cannot_recover(jp, "fsync");
  }
  // An invalid header: the writer died before its first write to the file.
  if (::unlink(jp.c_str()) != 0 && errno != ENOENT) cannot_recover(jp, "remove");
  return JournalState::rolled_back;
}

namespace journal_testing {
void before_io(long n, void (*action)()) {
  g_fault_action = action;
  g_io_count = 0;
  g_fault_at = n;
}
}  // namespace journal_testing

}  // namespace drumlab::h5
