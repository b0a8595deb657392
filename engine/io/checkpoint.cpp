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

Particles read_particles(hid_t file) {
  h5::Handle g = h5::open_group(file, "particles");
  Particles p;
  p.radius = h5::read_doubles(g.get(), "radius", h5::kAnySize);
  const std::size_t n = p.radius.size();
  p.position = h5::read_vec3(g.get(), "position", n);
  p.velocity = h5::read_vec3(g.get(), "velocity", n);
  p.omega = h5::read_vec3(g.get(), "omega", n);
  p.force = h5::read_vec3(g.get(), "force", n);
  p.torque = h5::read_vec3(g.get(), "torque", n);
  p.mass = h5::read_doubles(g.get(), "mass", n);
  p.inv_mass = h5::read_doubles(g.get(), "inv_mass", n);
  p.inv_inertia = h5::read_doubles(g.get(), "inv_inertia", n);
  p.size_class = h5::read_u8(g.get(), "size_class", n);
  p.id = h5::read_u32(g.get(), "id", n);
  if (H5Aexists(g.get(), "extra_arrays") > 0) {
    const std::string names = h5::read_string_attribute(g.get(), "extra_arrays");
    std::size_t begin = 0;
    while (begin < names.size()) {
      const std::size_t end = std::min(names.find(',', begin), names.size());
      const std::string name = names.substr(begin, end - begin);
      std::vector<double>& a =
          p.add_array(name, h5::read_double_attribute(g.get(), "extra_initial_" + name));
      a = h5::read_doubles(g.get(), "extra_" + name, n);
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

void read_contacts(hid_t file, SimulationState& s) {
  const std::size_t n = s.particles.size();
  h5::Handle g = h5::open_group(file, "contacts");
  const std::vector<std::uint64_t> rows = h5::read_u64(g.get(), "row_start", h5::kAnySize);
  s.contact_row_start.assign(rows.begin(), rows.end());
  s.contact_col = h5::read_u32(g.get(), "col", h5::kAnySize);
  s.contact_history = h5::read_vec3(g.get(), "history", s.contact_col.size());
  if (H5Aexists(g.get(), "state_size") > 0) {
    s.contact_state_size = h5::read_u64_attribute(g.get(), "state_size");
    s.contact_state =
        h5::read_doubles(g.get(), "state", s.contact_col.size() * s.contact_state_size);
  }
  h5::Handle w = h5::open_group(file, "walls");
  const std::vector<double> flat = h5::read_doubles(w.get(), "history", 9 * n);
  s.wall_history.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t part = 0; part < kWallParts; ++part) {
      const double* v = flat.data() + 9 * i + 3 * part;
      s.wall_history[i][part] = Vec3(v[0], v[1], v[2]);
    }
  }
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
  h5::write_attribute(f, "steps", state.steps);
  write_particles(f, state.particles, rows.particles);
  write_contacts(f, state, rows);
}

void write_checkpoint(const std::filesystem::path& file, const SimulationState& state,
                      const std::string& scene_name) {
  h5::Handle f = h5::create_memory_file(file.string());
  write_checkpoint_datasets(f.get(), state, scene_name);
  h5::save_memory_file(f, file);
}

Checkpoint read_checkpoint(const std::filesystem::path& file) {
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
  s.steps = h5::read_u64_attribute(f.get(), "steps");
  s.particles = read_particles(f.get());
  read_contacts(f.get(), s);
  return c;
}

}  // namespace drumlab
