// libFuzzer harness: the values of a checkpoint, through the restart path. fuzz_checkpoint.cpp
// mutates a file's bytes, and since every dataset and all metadata carry checksums nearly every
// mutation stops at the checksum: the checks behind it (finite values, row bounds, the scene's
// radii and masses, the law parts' arrays) are seldom reached. Here the input is a list of edits
// to a valid state: (array, row, component, value), the value a special one (NaN, +-inf, 0, -0,
// +-1e300, -1e-300, the value negated, doubled or moved by an ulp, an index at or past the end)
// or eight raw bytes. The state, one of three small drums (tests/fuzz/scenes/: dry, wet with
// pendular bridges, films with migration and wall bridges) stepped 300 steps, is edited and
// written whole (write_checkpoint: valid checksums), then restarted as `drumlab run SCENE
// --restart FILE` starts it and stepped twice. A refusal must be an InputError (or the run stop
// as UnstableError); an accepted state must step to finite positions and a finite liquid total.
// Anything else (another exception, a crash, a sanitizer report, a NaN) is a finding.
//
// Input: byte 0 picks the drum (mod 3); then edits of 12 bytes each (at most 16): the array
// (mod the count of arrays), row (2 bytes), component, the value's kind, then 7 bytes of value
// (kind 15: the raw double of those 7 bytes and the next).
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "engine/fill/random_fill.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/session/run_session.hpp"
#include "tests/fuzz/restart_and_step.hpp"
#include "tests/fuzz/scratch_file.hpp"

namespace {

namespace fs = std::filesystem;

constexpr const char* kScenes[] = {"dry", "wet", "films"};

struct Drum {
  drumlab::SceneConfig scene;
  drumlab::SimulationState state;
};

const Drum& drum(std::size_t k) {
  static const std::array<Drum, 3> drums = [] {
    std::array<Drum, 3> d;
    for (std::size_t i = 0; i < d.size(); ++i) {
      d[i].scene = drumlab::load_scene(std::string(DRUMLAB_FUZZ_SCENES "/") + kScenes[i] + ".toml");
      drumlab::Simulation sim(d[i].scene, drumlab::random_fill(d[i].scene));
      sim.advance(300);
      d[i].state = sim.state();
    }
    return d;
  }();
  return drums[k];
}

/// Reads the input's bytes in order; zeros once they run out.
class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  bool empty() const { return at_ >= size_; }
  std::uint8_t next() { return at_ < size_ ? data_[at_++] : 0; }
  std::uint64_t next_u64(int bytes) {
    std::uint64_t v = 0;
    for (int k = 0; k < bytes; ++k) v = v << 8 | next();
    return v;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
};

/// The new value of a double `old` by `kind`; raw: eight bytes of the input.
double edited(double old, unsigned kind, std::uint64_t raw) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  switch (kind % 16) {
    case 0:
      return std::numeric_limits<double>::quiet_NaN();
    case 1:
      return inf;
    case 2:
      return -inf;
    case 3:
      return 0.0;
    case 4:
      return -0.0;
    case 5:
      return 1e300;
    case 6:
      return -1e300;
    case 7:
      return -1e-300;
    case 8:
      return -old;
    case 9:
      return 2.0 * old;
    case 10:
      return std::nextafter(old, inf);
    case 11:
      return std::nextafter(old, -inf);
    case 12:
      return old * 1e-6;
    case 13:
      return old + 1.0;
    case 14:
      return -1.0;
    default:
      return std::bit_cast<double>(raw);
  }
}

/// The new value of an index `old` in [0, n): at or past the end, 0, another row, or raw bits.
template <class T>
T edited_index(T old, std::size_t n, unsigned kind, std::uint64_t raw) {
  switch (kind % 6) {
    case 0:
      return static_cast<T>(n);
    case 1:
      return static_cast<T>(n + 1);
    case 2:
      return T{0};
    case 3:
      return static_cast<T>(old + 1);
    case 4:
      return static_cast<T>(old - 1);
    default:
      return static_cast<T>(raw);
  }
}

/// One edit of the state: `pick` chooses among every array of it (the fixed particle arrays, the
/// law parts' arrays, the contact list, the wall history, the scalars).
void edit(drumlab::SimulationState& s, Bytes& in) {
  const std::uint8_t pick = in.next();
  const std::size_t row_pick = in.next_u64(2);
  const unsigned component = in.next() % 3;
  const unsigned kind = in.next();
  const std::uint64_t raw = in.next_u64(8);
  drumlab::Particles& p = s.particles;
  const std::size_t n = p.size();
  std::vector<std::vector<drumlab::Vec3>*> vectors = {&p.position, &p.velocity, &p.omega,
                                                      &p.force,    &p.torque,   &s.contact_history};
  std::vector<std::vector<double>*> reals = {&p.radius, &p.mass, &p.inv_mass, &p.inv_inertia,
                                             &s.contact_state};
  for (drumlab::ParticleArray& a : p.extra) reals.push_back(&a.values);
  double* scalars[] = {&s.time,          &s.dt,           &s.drum_omega, &s.drum_angle,
                       &s.carrier_angle, &s.carrier_omega};
  // vectors, reals, scalars, then id, size_class, contact_col, contact_row_start, wall history.
  const std::size_t arrays = vectors.size() + reals.size() + std::size(scalars) + 5;
  std::size_t k = pick % arrays;
  const auto row = [&](std::size_t size) { return row_pick % size; };
  if (k < vectors.size()) {
    std::vector<drumlab::Vec3>& v = *vectors[k];
    if (v.empty()) return;
    double& x = v[row(v.size())][component];
    x = edited(x, kind, raw);
    return;
  }
  k -= vectors.size();
  if (k < reals.size()) {
    std::vector<double>& v = *reals[k];
    if (v.empty()) return;
    double& x = v[row(v.size())];
    x = edited(x, kind, raw);
    return;
  }
  k -= reals.size();
  if (k < std::size(scalars)) {
    *scalars[k] = edited(*scalars[k], kind, raw);
    return;
  }
  k -= std::size(scalars);
  switch (k) {
    case 0:
      if (n > 0) p.id[row(n)] = edited_index(p.id[row(n)], n, kind, raw);
      break;
    case 1:
      if (n > 0) p.size_class[row(n)] = edited_index(p.size_class[row(n)], 2, kind, raw);
      break;
    case 2:
      if (!s.contact_col.empty()) {
        auto& c = s.contact_col[row(s.contact_col.size())];
        c = edited_index(c, n, kind, raw);
      }
      break;
    case 3:
      if (!s.contact_row_start.empty()) {
        auto& r = s.contact_row_start[row(s.contact_row_start.size())];
        r = edited_index(r, s.contact_col.size(), kind, raw);
      }
      break;
    default:
      if (!s.wall_history.empty()) {
        auto& parts = s.wall_history[row(s.wall_history.size())];
        double& x = parts[component][static_cast<int>(raw % 3)];
        x = edited(x, kind, raw);
      }
      break;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const drumlab::fuzz::ScratchFile scratch("drumlab-fuzz-values");
  const fs::path& file = scratch.path();
  Bytes in(data, size);
  const Drum& d = drum(in.next() % 3);
  drumlab::SimulationState state = d.state;
  for (int k = 0; k < 16 && !in.empty(); ++k) edit(state, in);
  write_checkpoint(file, state, d.scene.name);
  try {
    drumlab::fuzz::restart_and_step(d.scene, file);
  } catch (const drumlab::InputError&) {
  }
  return 0;
}
