// drumlab info SCENE [--write-mesh DIR]: derived quantities of a scene, without simulating it;
// its triangle walls written as STL files on request.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "app/cli/commands.hpp"
#include "app/cli/scene_setup.hpp"
#include "app/cli/wall_mesh_files.hpp"
#include "engine/contact/contact_model.hpp"
#include "engine/contact/hertz_mindlin.hpp"
#include "engine/contact/sjkr_cohesion.hpp"
#include "engine/drum_orbit.hpp"
#include "engine/fill/file_fill.hpp"
#include "engine/fill/paper_packing.hpp"
#include "engine/fill/random_fill.hpp"
#include "engine/memory_estimate.hpp"
#include "engine/mesh/wall_meshes.hpp"
#include "engine/scene/scene_features.hpp"
#include "engine/search/auto_select.hpp"
#include "engine/search/search_binning.hpp"
#include "engine/search/search_methods.hpp"
#include "engine/simulation.hpp"

namespace drumlab::cli {

namespace {

/// The "needs / skips" section: each term the engine computes or leaves out for this scene, and
/// why.
void print_features(const SceneConfig& scene) {
  const SceneFeatures f = scene_features(scene);
  fmt::print(
      "needs / skips     (what the engine computes for this scene; `drumlab bench skips` "
      "measures each skip)\n");
  for (const SceneFeature& x : f.list) {
    fmt::print("  {:<15} {:<39} {}\n", feature_use_name(x.use), x.term, x.why);
  }
}

/// Bond numbers of the liquid, and the sjkr pull-off force, per class (at a distribution's mean
/// radius).
void print_cohesion(const SceneConfig& scene) {
  const double g = scene.gravity.norm();
  for (std::size_t c = 0; c < scene.classes.size() && scene.liquid.enabled; ++c) {
    const double r = scene.classes[c].mean_radius();
    const double weight = scene.material.density * 4.0 / 3.0 * std::numbers::pi * r * r * r * g;
    fmt::print(
        "Bond number       {}: Bo = F0 / (m g) = {:.3g} (F0 = 2 pi r gamma cos(theta) = "
        "{:.3g} N, m g = {:.3g} N)\n",
        scene.classes[c].name, bond_number(scene, c), bond_number(scene, c) * weight, weight);
  }
  if (!scene.cohesion.enabled) return;
  const SjkrCohesion sjkr{scene.cohesion.energy_density};
  const Material& m = scene.material;
  const double e_star = effective_youngs_modulus(m, m);
  for (std::size_t c = 0; c < scene.classes.size(); ++c) {
    const double r = scene.classes[c].mean_radius();
    const double weight = m.density * 4.0 / 3.0 * std::numbers::pi * r * r * r * g;
    const double pull = sjkr.pull_off_force(e_star, 0.5 * r);
    fmt::print(
        "sjkr pull-off     {}: {:.3g} N = {:.3g} m g (rest overlap {:.3g} m; Hertz, two "
        "spheres of the class)\n",
        scene.classes[c].name, pull, pull / weight, sjkr.rest_overlap(e_star, 0.5 * r));
  }
}

/// Particles per class: counted in the file, planned by the random fill, or the paper's packing.
std::vector<std::size_t> particle_counts(const SceneConfig& scene) {
  std::vector<std::size_t> counts;
  if (scene.fill.kind == FillKind::file) {
    const Particles p = initial_fill(scene);
    counts.assign(scene.classes.size(), 0);
    for (const std::uint8_t c : p.size_class) ++counts[c];
  } else if (scene.dynamic()) {
    counts = class_counts(scene);
  } else {
    const auto c = paper_packing_counts(scene.fill.box);
    counts.assign(c.begin(), c.end());
  }
  return counts;
}

/// The classes, the particle count, the drum and its fill level; returns the particle count.
std::size_t print_particles_and_drum(const SceneConfig& scene, const std::string& file) {
  const std::vector<std::size_t> counts = particle_counts(scene);
  std::size_t total = 0;
  double solid = 0.0;
  const bool polydisperse = std::any_of(scene.classes.begin(), scene.classes.end(),
                                        [](auto& c) { return c.polydisperse(); });
  fmt::print("scene             {} ({})\n", scene.name, file);
  if (!scene.description.empty()) fmt::print("description       {}\n", scene.description);
  for (std::size_t c = 0; c < scene.classes.size(); ++c) {
    const SizeDistribution size = scene.classes[c].size();
    fmt::print("class {:<11} {}, {} particles\n", scene.classes[c].name, size.describe(),
               counts[c]);
    total += counts[c];
    solid += static_cast<double>(counts[c]) * 4.0 / 3.0 * std::numbers::pi * size.mean_cube();
  }
  const double r_drum = 0.5 * scene.drum.diameter;
  const double drum_volume = std::numbers::pi * r_drum * r_drum * scene.drum.depth;
  fmt::print("particles         {} (solid volume {:.4g} m^3{})\n", total, solid,
             polydisperse ? ", a distribution's at its mean volume" : "");
  fmt::print("drum              D = {} m, H = {} m, omega = {} rad/s, tilt = {:.3g} deg, ends {}\n",
             scene.drum.diameter, scene.drum.depth, scene.drum.omega,
             scene.drum.tilt * 180.0 / std::numbers::pi,
             scene.drum.ends == DrumEnds::caps ? "caps" : "periodic");
  if (scene.dynamic()) {
    fmt::print(
        "fill              {:.1f} % of the drum volume once settled (at solid fraction 0.6)\n",
        100.0 * solid / 0.6 / drum_volume);
  }
  return total;
}

/// The Rayleigh time, the time step, the Froude number and one revolution; returns dt.
double print_time_scales(const SceneConfig& scene, std::size_t total) {
  const double t_r = rayleigh_time(scene.min_radius(), scene.material);
  const double dt = scene.time.dt ? *scene.time.dt : scene.time.dt_factor * t_r;
  fmt::print("Rayleigh time     {:.4g} s (smallest radius {} m)\n", t_r, scene.min_radius());
  const TimeStepLimit limit = time_step_limit(scene, ContactModel(scene), scene.min_radius());
  fmt::print(
      "time step         {:.4g} s = {:.3g} Rayleigh times = {:.3g} of the stability limit of "
      "{} {}{}\n",
      dt, dt / t_r, dt / limit.seconds(), limit.factor, limit.unit,
      dt > limit.seconds() ? "  (ABOVE it: refused without --unsafe-dt)" : "");
  const double fr = froude_number(scene);
  if (scene.drum.orbit.active()) {
    fmt::print(
        "Froude number     {:.4g} against gravity alone (the carrier's field: `orbit` below)\n",
        fr);
  } else {
    fmt::print("Froude number     {:.4g} -> {} regime expected\n", fr, regime_for_froude(fr));
  }
  if (scene.drum.omega != 0.0) {
    const double rev = 2.0 * std::numbers::pi / std::abs(scene.drum.omega);
    fmt::print("one revolution    {:.4g} s = {:.0f} steps = {:.3g} particle-steps\n", rev, rev / dt,
               rev / dt * static_cast<double>(total));
  }
  return dt;
}

/// The search method a run of the scene uses: the scene's own, or auto's pick on the filled scene
/// (`choice`; a static packing is not searched by a run: m5 stands for it).
struct RunSearch {
  std::string method;
  std::optional<SearchChoice> choice;
};

RunSearch run_search(const SceneConfig& scene, double dt) {
  if (scene.search_method != "auto") return {scene.search_method, std::nullopt};
  if (!scene.dynamic()) return {"m5", std::nullopt};
  const Particles fill = initial_fill(scene);
  SearchChoice choice = choose_search_method(scene, dt, fill.position, fill.radius);
  std::string method = choice.method;
  return {std::move(method), std::move(choice)};
}

/// What the engine allocates for a settled bed (engine/memory_estimate.hpp) with the run's search
/// method, and the grid of that method (or of its Verlet list's builder) if it has one cell side.
void print_memory(const SceneConfig& scene, std::size_t total, const RunSearch& search) {
  const std::string& estimated = search.method;
  const auto parsed = parse_search_method(estimated);
  double cells = 0.0;
  std::string grid;
  const SearchMethodInfo* method = parsed ? parsed->method : nullptr;
  if (method != nullptr &&
      (method->cell == CellRule::min_radius || method->cell == CellRule::max_radius)) {
    const double b = method->cell == CellRule::min_radius ? scene.min_radius() : scene.max_radius();
    const double nxy = std::ceil(scene.drum.diameter / b) + 1;
    const double nz = method->grid == SearchGrid::three_d ? std::ceil(scene.drum.depth / b) + 1 : 1;
    cells = nxy * nxy * nz;
    grid = fmt::format(", grid ~{:.0f} x {:.0f} x {:.0f} cells of {} m", nxy, nxy, nz, b);
  }
  MemoryShape shape;
  shape.particles = total;
  shape.listed_pairs_per_particle =
      settled_pairs_per_particle(parsed && parsed->verlet, scene.performance.verlet_skin);
  shape.grid_cells = cells;
  shape.rotation = scene_features(scene).rotation;
  shape.reorder = scene.performance.sort_every > 0;
  const MemoryEstimate memory = estimate_memory(estimated, shape);
  shape.threads = 2;
  const MemoryEstimate parallel = estimate_memory(estimated, shape);
  fmt::print(
      "memory estimate   {:.1f} MiB on 1 thread, {:.1f} MiB on 2 or more ({:.0f} / {:.0f} "
      "B/particle with {:.1f} listed pairs each{}{})\n",
      memory.total() / 1048576.0, parallel.total() / 1048576.0, memory.per_particle,
      parallel.per_particle, shape.listed_pairs_per_particle, grid,
      search.choice                   ? fmt::format("; for auto's pick {}", estimated)
      : scene.search_method == "auto" ? "; for m5"
                                      : "");
}

/// How `method` bins the scene's radii (engine/search/search_binning.hpp).
void print_binning(const SceneConfig& scene, std::string_view method) {
  RadiusRange radii{scene.min_radius(), scene.max_radius(), 0};
  for (const ParticleClass& c : scene.classes) {
    const std::size_t n = c.distribution == SizeKind::table ? c.radii.size() : 1;
    radii.distinct = c.distribution == SizeKind::normal || c.distribution == SizeKind::lognormal
                         ? RadiusRange::kContinuous
                         : std::min(RadiusRange::kContinuous - n, radii.distinct) + n;
  }
  for (const std::string& line : search_binning(method, radii)) {
    fmt::print("search bins       {}\n", line);
  }
}

/// The search method: auto's choice on the filled scene and why, or the scene's own.
void print_search_method(const SceneConfig& scene, const RunSearch& search) {
  if (search.choice) {
    const SearchChoice& choice = *search.choice;
    fmt::print("search method     auto -> {} (paper's rule: {})\n", choice.method,
               choice.paper_rule);
    fmt::print("why               {}\n", choice.reason);
    print_binning(scene, choice.method);
    return;
  }
  fmt::print("search method     {} (set by the scene; `--method` overrides it in `run`)\n",
             scene.search_method);
  if (const auto parsed = parse_search_method(scene.search_method)) {
    fmt::print("                  {}{}\n",
               parsed->verlet ? fmt::format("Verlet list built by {}: ", parsed->method->name)
                              : std::string(),
               parsed->method->description);
  }
  print_binning(scene, scene.search_method);
}

/// Each nozzle: its shape, rate and window, its droplets, and the liquid it adds against the
/// solid volume.
void print_sprays(const SceneConfig& scene) {
  double solid = 0.0;
  const std::vector<std::size_t> counts = particle_counts(scene);
  for (std::size_t c = 0; c < scene.classes.size(); ++c) {
    solid += static_cast<double>(counts[c]) * 4.0 / 3.0 * std::numbers::pi *
             scene.classes[c].size().mean_cube();
  }
  for (const SprayConfig& s : scene.sprays) {
    const double r = s.droplet_radius;
    const double droplet = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    const double added = s.rate * (s.stop - s.start);
    fmt::print(
        "spray             {}: {} of {:g} deg from [{:g}, {:g}, {:g}] m along [{:g}, {:g}, {:g}], "
        "{:.4g} m^3/s from {:g} s {}\n",
        s.name, s.shape == SprayShape::flat_fan ? "flat fan" : "cone", s.angle_deg, s.position.x(),
        s.position.y(), s.position.z(), s.direction.x(), s.direction.y(), s.direction.z(), s.rate,
        s.start, std::isfinite(s.stop) ? fmt::format("to {:g} s", s.stop) : std::string("on"));
    fmt::print("                  {:.4g} droplets/s of r = {:.3g} m at {:g} m/s, {} at the wall",
               s.rate / droplet, r, s.droplet_speed,
               s.at_wall == SprayAtWall::wet ? "wetting it" : "lost");
    if (std::isfinite(added) && solid > 0.0) {
      fmt::print("; adds {:.4g} m^3 = {:.3g} of the solid volume", added, added / solid);
    }
    fmt::print("\n");
  }
}

/// A planetary drum: the carrier's field against gravity, the drum's speed ratio against the
/// critical ratios of the largest and smallest particles, and the regime they predict.
void print_orbit(const SceneConfig& scene) {
  const DrumConfig& d = scene.drum;
  const DrumOrbit& o = d.orbit;
  if (!o.active()) return;
  const double field = carrier_field(o);
  const double g = scene.gravity.norm();
  const double r = 0.5 * d.diameter, r_min = scene.min_radius(), r_max = scene.max_radius();
  fmt::print(
      "orbit             carrier R_o = {:g} m at Omega = {:.4g} rad/s ({:.4g} rpm): field "
      "Omega^2 R_o = {:.4g} m/s^2 = {:.3g} g, turning with the arm\n",
      o.radius, o.omega, o.omega * 30.0 / std::numbers::pi, field, g > 0.0 ? field / g : 0.0);
  fmt::print(
      "                  drum omega = {:.4g} rad/s, speed ratio k = omega / Omega - 1 = {:.4g} "
      "(|1 + k| = {:.4g})\n",
      d.omega, speed_ratio(d), std::abs(1.0 + speed_ratio(d)));
  fmt::print(
      "                  critical |1 + k| = sqrt(R_o / (R - r)): {:.4g} for the largest (r = {:g} "
      "m), {:.4g} for the smallest (r = {:g} m)\n",
      critical_speed_ratio(o, r - r_max), r_max, critical_speed_ratio(o, r - r_min), r_min);
  fmt::print("                  predicted: {}{}\n", regime_text(predicted_regime(d, r_min, r_max)),
             g > 0.1 * field ? " (gravity is not small against the field: a rough guide)" : "");
}

/// The triangle walls, a line each, with the file each was written to (if any).
void print_meshes(const std::vector<WallMesh>& meshes,
                  const std::vector<std::filesystem::path>& files) {
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    fmt::print("wall mesh         {}\n", mesh_summary(meshes[k]));
    if (k < files.size()) fmt::print("                  written to {}\n", files[k].string());
  }
}

void print_info(const std::string& file, const std::string& mesh_dir) {
  const SceneConfig scene = load_scene(file);
  const std::vector<WallMesh> meshes =
      scene.has_meshes() ? build_wall_meshes(scene) : std::vector<WallMesh>{};
  // The files first, all or none: a directory that cannot take them stops info before it prints.
  std::vector<std::filesystem::path> files;
  if (!mesh_dir.empty()) {
    if (meshes.empty()) {
      throw InputError(
          fmt::format("--write-mesh: {} has no [[wall.mesh]] or [[wall.lifters]]", file));
    }
    files = write_mesh_files(meshes, mesh_dir);
  }
  const std::size_t total = print_particles_and_drum(scene, file);
  const double dt = print_time_scales(scene, total);
  const RunSearch search = run_search(scene, dt);
  print_memory(scene, total, search);
  print_search_method(scene, search);
  print_cohesion(scene);
  print_sprays(scene);
  print_orbit(scene);
  print_meshes(meshes, files);
  if (scene.dynamic()) print_features(scene);
  if (!scene.dynamic()) fmt::print("note              static packing: use `drumlab paper-table`\n");
}

}  // namespace

void add_info_command(CLI::App& app) {
  auto file = std::make_shared<std::string>();
  auto mesh_dir = std::make_shared<std::string>();
  CLI::App* cmd =
      app.add_subcommand("info", "Derived quantities of a scene (counts, dt, Froude, memory)");
  cmd->add_option("scene", *file, "scene file (TOML)")->required();
  cmd->add_option("--write-mesh", *mesh_dir,
                  "write each triangle wall as DIR/<key>.stl (lifters_0.stl, mesh_0.stl), as "
                  "built, at drum angle 0");
  cmd->callback([file, mesh_dir] { print_info(*file, *mesh_dir); });
}

}  // namespace drumlab::cli
