#include "engine/io/checkpoint.hpp"

#include <fmt/format.h>

#include "engine/io/checkpoint_layout.hpp"
#include "engine/io/h5_file.hpp"

namespace drumlab {
namespace {

constexpr const char* kFormat = "drumlab-checkpoint";
constexpr std::uint64_t kVersion = 1;

void write_particles(hid_t file, const Particles& p, const h5::Rows& rows) {
  h5::Handle g = h5::create_group(file, "particles");
  const std::size_t n = p.size();
  h5::write_vec3(g.get(), "position", p.position, rows);
  h5::write_vec3(g.get(), "velocity", p.velocity, rows);
  h5::write_vec3(g.get(), "omega", p.omega, rows);
  h5::write_vec3(g.get(), "force", p.force, rows);
  h5::write_vec3(g.get(), "torque", p.torque, rows);
  h5::write(g.get(), "radius", p.radius, {n}, rows);
  h5::write(g.get(), "mass", p.mass, {n}, rows);
  h5::write(g.get(), "inv_mass", p.inv_mass, {n}, rows);
  h5::write(g.get(), "inv_inertia", p.inv_inertia, {n}, rows);
  h5::write(g.get(), "size_class", std::span<const std::uint8_t>(p.size_class), rows);
  h5::write(g.get(), "id", std::span<const std::uint32_t>(p.id), rows);
  // The registered extra arrays (Particles::extra), by name; a dry scene has none and writes
  // nothing more, so its checkpoint is the one from before.
  if (p.extra.empty()) return;
  std::string names;
  for (const ParticleArray& a : p.extra) {
    names += (names.empty() ? "" : ",") + a.name;
    h5::write(g.get(), "extra_" + a.name, a.values, {n}, rows);
    h5::write_attribute(g.get(), "extra_initial_" + a.name, a.initial);
  }
  h5::write_attribute(g.get(), "extra_arrays", names);
}

/// A per-particle (or per-contact) column: a dataset of shape (N).
std::vector<double> column(hid_t g, const std::string& name, std::size_t n,
                           const h5::RowRange& range = {}) {
  h5::check_row_shape(g, name, {});
  return h5::read_doubles(g, name, n, range);
}

/// The per-particle datasets of /particles: vectors (N x 3) or columns (N), N the particles.
constexpr std::pair<const char*, bool> kParticleSets[] = {
    {"radius", false},      {"position", true},    {"velocity", true}, {"omega", true},
    {"force", true},        {"torque", true},      {"mass", false},    {"inv_mass", false},
    {"inv_inertia", false}, {"size_class", false}, {"id", false}};

/// The particles of `range` (all by default) of the file's n.
Particles read_particles(hid_t file, const std::string& label, std::size_t n,
                         const h5::RowRange& range) {
  h5::Handle g = h5::open_group(file, "particles");
  for (const auto& [name, vector] : kParticleSets) {
    if (vector) {
      h5::check_row_shape(g.get(), name, {3});
    } else {
      h5::check_row_shape(g.get(), name, {});
    }
  }
  for (const auto& [name, vector] : kParticleSets) {
    if (const std::size_t rows = h5::rows_of(g.get(), name); rows != n) {
      throw InputError(fmt::format("{}: particles/{} has {} rows, particles/radius {} (damaged?)",
                                   label, name, rows, n));
    }
  }
  Particles p;
  p.radius = column(g.get(), "radius", n, range);
  p.position = h5::read_vec3(g.get(), "position", n, range);
  p.velocity = h5::read_vec3(g.get(), "velocity", n, range);
  p.omega = h5::read_vec3(g.get(), "omega", n, range);
  p.force = h5::read_vec3(g.get(), "force", n, range);
  p.torque = h5::read_vec3(g.get(), "torque", n, range);
  p.mass = column(g.get(), "mass", n, range);
  p.inv_mass = column(g.get(), "inv_mass", n, range);
  p.inv_inertia = column(g.get(), "inv_inertia", n, range);
  p.size_class = h5::read_u8(g.get(), "size_class", n, range);
  p.id = h5::read_u32(g.get(), "id", n, range);
  if (H5Aexists(g.get(), "extra_arrays") > 0) {
    const std::string names = h5::read_string_attribute(g.get(), "extra_arrays");
    std::size_t begin = 0;
    while (begin < names.size()) {
      const std::size_t end = std::min(names.find(',', begin), names.size());
      const std::string name = names.substr(begin, end - begin);
      std::vector<double>& a =
          p.add_array(name, h5::read_double_attribute(g.get(), "extra_initial_" + name));
      a = column(g.get(), "extra_" + name, n, range);
      begin = end + 1;
    }
  }
  return p;
}

static_assert(sizeof(std::array<Vec3, kWallParts>) == 3 * kWallParts * sizeof(double));

void write_contacts(hid_t file, const SimulationState& s, const CheckpointRows& rows) {
  h5::Handle g = h5::create_group(file, "contacts");
  std::vector<std::uint64_t> starts(s.contact_row_start.begin(), s.contact_row_start.end());
  h5::write(g.get(), "row_start", std::span<const std::uint64_t>(starts), rows.row_start);
  h5::write(g.get(), "col", std::span<const std::uint32_t>(s.contact_col), rows.records);
  h5::write_vec3(g.get(), "history", s.contact_history, rows.records);
  // The law parts' per-contact scalars, only if the law keeps any (a dry checkpoint is unchanged).
  if (s.contact_state_size > 0) {
    h5::write_attribute(g.get(), "state_size", std::uint64_t{s.contact_state_size});
    h5::write(g.get(), "state", s.contact_state, {s.contact_col.size(), s.contact_state_size},
              rows.records);
  }
  h5::Handle w = h5::create_group(file, "walls");
  const double* raw = s.wall_history.empty() ? nullptr : s.wall_history.front().front().data();
  h5::write(w.get(), "history", std::span<const double>(raw, 9 * s.wall_history.size()),
            {s.wall_history.size(), kWallParts, 3}, rows.particles);
}

/// The contacts of the rows `range` (all by default) of the file's n particles: row_start from 0,
/// contact_col the partners' rows in the file; and those rows' wall history.
void read_contacts(hid_t file, const std::string& label, std::size_t n, const h5::RowRange& range,
                   SimulationState& s) {
  const std::size_t rows = range.all ? n : static_cast<std::size_t>(range.count);
  h5::Handle g = h5::open_group(file, "contacts");
  const std::size_t m = h5::rows_of(g.get(), "col");
  // An empty row_start (a state whose contact list was never built) has no rows to range over.
  h5::check_row_shape(g.get(), "row_start", {});
  h5::check_row_shape(g.get(), "col", {});
  const bool listed = h5::rows_of(g.get(), "row_start") > 0;
  std::vector<std::uint64_t> starts = h5::read_u64(
      g.get(), "row_start", h5::kAnySize,
      range.all || !listed ? h5::RowRange{} : h5::RowRange::of(range.first, range.count + 1));
  h5::RowRange records;  // all, or the rows' records
  if (!range.all && !starts.empty()) {
    if (starts.front() > starts.back() || starts.back() > m) {
      throw InputError(fmt::format("{}: contacts/row_start out of order", label));
    }
    records = h5::RowRange::of(starts.front(), starts.back() - starts.front());
    const std::uint64_t base = starts.front();
    for (std::uint64_t& v : starts) v -= base;
  }
  s.contact_row_start.assign(starts.begin(), starts.end());
  s.contact_col = h5::read_u32(g.get(), "col", m, records);
  s.contact_history = h5::read_vec3(g.get(), "history", m, records);
  if (H5Aexists(g.get(), "state_size") > 0) {
    s.contact_state_size = h5::read_u64_attribute(g.get(), "state_size");
    if (s.contact_state_size == 0 || s.contact_state_size > 64) {
      throw InputError(
          fmt::format("{}: contacts/state_size {} (damaged?)", label, s.contact_state_size));
    }
    h5::check_row_shape(g.get(), "state", {s.contact_state_size});
    s.contact_state = h5::read_doubles(g.get(), "state", m * s.contact_state_size, records);
  }
  h5::Handle w = h5::open_group(file, "walls");
  h5::check_row_shape(w.get(), "history", {kWallParts, 3});
  const std::vector<double> flat = h5::read_doubles(w.get(), "history", 9 * n, range);
  s.wall_history.resize(rows);
  for (std::size_t i = 0; i < rows; ++i) {
    for (std::size_t part = 0; part < kWallParts; ++part) {
      const double* v = flat.data() + 9 * i + 3 * part;
      s.wall_history[i][part] = Vec3(v[0], v[1], v[2]);
    }
  }
}

/// /spray (a scene with [[spray]]): the airborne droplets, each nozzle's counts and the wall
/// film's patches. Serial runs only (a decomposed run refuses a spraying scene).
void write_spray(hid_t file, const SprayState& s) {
  h5::Handle g = h5::create_group(file, "spray");
  std::vector<Vec3> position, velocity;
  std::vector<std::uint64_t> serial;
  std::vector<std::uint32_t> nozzle;
  for (const Droplet& d : s.droplets) {
    position.push_back(d.position);
    velocity.push_back(d.velocity);
    serial.push_back(d.serial);
    nozzle.push_back(d.spray);
  }
  h5::write_vec3(g.get(), "droplet_position", position);
  h5::write_vec3(g.get(), "droplet_velocity", velocity);
  h5::write(g.get(), "droplet_serial", std::span<const std::uint64_t>(serial));
  h5::write(g.get(), "droplet_nozzle", std::span<const std::uint32_t>(nozzle));
  h5::write(g.get(), "emitted", std::span<const std::uint64_t>(s.emitted));
  h5::write(g.get(), "absorbed", std::span<const std::uint64_t>(s.absorbed));
  h5::write(g.get(), "lost", std::span<const std::uint64_t>(s.lost));
  h5::write(g.get(), "walled", std::span<const std::uint64_t>(s.walled));
  h5::write(g.get(), "wall_film", std::span<const double>(s.wall_film), {s.wall_film.size()});
}

SprayState read_spray(hid_t file) {
  SprayState s;
  if (!h5::exists(file, "spray")) return s;
  h5::Handle g = h5::open_group(file, "spray");
  const std::vector<std::uint64_t> serial = h5::read_u64(g.get(), "droplet_serial", h5::kAnySize);
  const std::size_t n = serial.size();
  const std::vector<std::uint32_t> nozzle = h5::read_u32(g.get(), "droplet_nozzle", n);
  const std::vector<Vec3> position = h5::read_vec3(g.get(), "droplet_position", n);
  const std::vector<Vec3> velocity = h5::read_vec3(g.get(), "droplet_velocity", n);
  for (std::size_t k = 0; k < n; ++k) {
    s.droplets.push_back({position[k], velocity[k], serial[k], nozzle[k]});
  }
  s.emitted = h5::read_u64(g.get(), "emitted", h5::kAnySize);
  const std::size_t m = s.emitted.size();
  s.absorbed = h5::read_u64(g.get(), "absorbed", m);
  s.lost = h5::read_u64(g.get(), "lost", m);
  s.walled = h5::read_u64(g.get(), "walled", m);
  s.wall_film = h5::read_doubles(g.get(), "wall_film", h5::kAnySize);
  return s;
}

}  // namespace

void write_checkpoint_datasets(hid_t f, const SimulationState& state, const std::string& scene_name,
                               const CheckpointRows& rows) {
  h5::write_attribute(f, "format", std::string(kFormat));
  h5::write_attribute(f, "version", kVersion);
  h5::write_attribute(f, "scene", scene_name);
  h5::write_attribute(f, "search_method", state.search_method);
  h5::write_attribute(f, "time", state.time);
  h5::write_attribute(f, "dt", state.dt);
  h5::write_attribute(f, "drum_omega", state.drum_omega);
  h5::write_attribute(f, "drum_angle", state.drum_angle);
  if (state.carrier_angle != 0.0 || state.carrier_omega != 0.0) {
    h5::write_attribute(f, "carrier_angle", state.carrier_angle);
    h5::write_attribute(f, "carrier_omega", state.carrier_omega);
  }
  h5::write_attribute(f, "steps", state.steps);
  write_particles(f, state.particles, rows.particles);
  write_contacts(f, state, rows);
  if (!state.spray.empty()) write_spray(f, state.spray);
}

void write_checkpoint(const std::filesystem::path& file, const SimulationState& state,
                      const std::string& scene_name) {
  h5::StagedFile f(file);
  f.write([&](hid_t id) { write_checkpoint_datasets(id, state, scene_name); });
  f.commit();
}

namespace {

Checkpoint read_rows(const std::filesystem::path& file, const h5::RowRange& range) {
  h5::Handle f = h5::open_file(file);
  if (!H5Aexists(f.get(), "format") || h5::read_string_attribute(f.get(), "format") != kFormat) {
    throw InputError(fmt::format("{}: not a drumlab checkpoint", file.string()));
  }
  const std::uint64_t version = h5::read_u64_attribute(f.get(), "version");
  if (version != kVersion) {
    throw InputError(fmt::format("{}: checkpoint version {} (this build reads {})", file.string(),
                                 version, kVersion));
  }
  Checkpoint c;
  c.scene_name = h5::read_string_attribute(f.get(), "scene");
  SimulationState& s = c.state;
  s.search_method = h5::read_string_attribute(f.get(), "search_method");
  s.time = h5::read_double_attribute(f.get(), "time");
  s.dt = h5::read_double_attribute(f.get(), "dt");
  s.drum_omega = h5::read_double_attribute(f.get(), "drum_omega");
  s.drum_angle = h5::read_double_attribute(f.get(), "drum_angle");
  if (H5Aexists(f.get(), "carrier_angle") > 0) {
    s.carrier_angle = h5::read_double_attribute(f.get(), "carrier_angle");
    s.carrier_omega = h5::read_double_attribute(f.get(), "carrier_omega");
  }
  s.steps = h5::read_u64_attribute(f.get(), "steps");
  {
    h5::Handle g = h5::open_group(f.get(), "particles");
    c.particles = h5::rows_of(g.get(), "radius");
  }
  s.particles = read_particles(f.get(), file.string(), c.particles, range);
  read_contacts(f.get(), file.string(), c.particles, range, s);
  s.spray = read_spray(f.get());
  return c;
}

}  // namespace

Checkpoint read_checkpoint(const std::filesystem::path& file) {
  return read_rows(file, {});
}

Checkpoint read_checkpoint_rows(const std::filesystem::path& file, std::size_t first,
                                std::size_t count) {
  return read_rows(file, h5::RowRange::of(first, count));
}

}  // namespace drumlab
