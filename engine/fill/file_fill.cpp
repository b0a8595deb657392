#include "engine/fill/file_fill.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/drum.hpp"
#include "engine/periodic.hpp"
#include "engine/search/contact_search.hpp"

namespace drumlab {

namespace {

/// Index of the class that r belongs to, or throws: a class of one radius (relative 1e-6) first,
/// then a distribution whose radii hold r (SizeDistribution::holds, same tolerance).
std::uint8_t class_of(const SceneConfig& scene, double r, std::string_view source,
                      std::size_t line) {
  for (const bool spread : {false, true}) {
    for (std::size_t c = 0; c < scene.classes.size(); ++c) {
      const ParticleClass& k = scene.classes[c];
      if (k.polydisperse() == spread && k.size().holds(r, 1e-6)) {
        return static_cast<std::uint8_t>(c);
      }
    }
  }
  std::string radii;
  for (const ParticleClass& c : scene.classes) {
    const std::string one = c.polydisperse()
                                ? fmt::format("[{}, {}]", c.min_radius(), c.max_radius())
                                : fmt::format("{}", c.radius);
    radii += fmt::format("{}{}", radii.empty() ? "" : ", ", one);
  }
  throw InputError(fmt::format(
      "{}:{}: radius {} m is not one of the scene's [[particles]] radii or ranges ({} m)", source,
      line, r, radii));
}

void check_inside(const Drum& drum, Vec3& x, double r, std::string_view source, std::size_t line) {
  if (drum.periodic()) x.z() = drum.wrap_z(x.z());
  if (!drum.contains_centre(x, 0.0)) {
    throw InputError(fmt::format(
        "{}:{}: particle at ({:.6g}, {:.6g}, {:.6g}) m lies outside the drum (R = {} m, H = {} m)",
        source, line, x.x(), x.y(), x.z(), drum.radius(), drum.depth()));
  }
  for (std::size_t part = 0; part < kWallParts; ++part) {
    const WallContact c = drum.contact(static_cast<WallPart>(part), x, r);
    if (c.overlap > kMaxFileOverlap * r) {
      throw InputError(fmt::format(
          "{}:{}: particle at ({:.6g}, {:.6g}, {:.6g}) m overlaps the drum wall by {:.3g} of its "
          "radius (at most {} allowed)",
          source, line, x.x(), x.y(), x.z(), c.overlap / r, kMaxFileOverlap));
    }
  }
}

void check_pair_overlaps(const Drum& drum, const Particles& p, const ParticleTable& table,
                         std::string_view source) {
  SearchInput in;
  in.position = p.position;
  in.radius = p.radius;
  if (drum.periodic()) in.period_z = drum.depth();
  std::vector<IndexPair> pairs;
  make_search("m5")->find_pairs(in, pairs);
  const double period = drum.period();
  for (const IndexPair& pr : pairs) {
    const Vec3 dx = nearest_image(p.position[pr.i], p.position[pr.j], period);
    const double r_small = std::min(p.radius[pr.i], p.radius[pr.j]);
    const double overlap = p.radius[pr.i] + p.radius[pr.j] - dx.norm();
    if (overlap > kMaxFileOverlap * r_small) {
      throw InputError(fmt::format(
          "{}:{}: particle overlaps the particle of line {} by {:.3g} of the smaller radius (at "
          "most {} allowed; separate them or shrink the packing)",
          source, table.line[pr.j], table.line[pr.i], overlap / r_small, kMaxFileOverlap));
    }
  }
}

}  // namespace

Particles particles_from_table(const SceneConfig& scene, const ParticleTable& table,
                               std::string_view source) {
  const std::size_t n = table.position.size();
  if (n == 0) throw InputError(fmt::format("{}: no particles (header only)", source));
  const Drum drum(scene.drum);
  Particles p;
  p.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t line = i < table.line.size() ? table.line[i] : i + 2;
    const double r = table.radius[i];
    if (!(r > 0.0) || !std::isfinite(r)) {
      throw InputError(fmt::format("{}:{}: radius {} must be positive", source, line, r));
    }
    const std::uint8_t cls = class_of(scene, r, source, line);
    Vec3 x = table.position[i];
    if (!x.allFinite()) throw InputError(fmt::format("{}:{}: position not finite", source, line));
    // A class of one radius gives its particles exactly that radius; a distribution keeps r.
    const ParticleClass& k = scene.classes[cls];
    const double radius = k.polydisperse() ? r : k.radius;
    check_inside(drum, x, radius, source, line);
    p.add(x, radius, scene.material.density, cls);
    if (!table.velocity.empty()) {
      if (!table.velocity[i].allFinite())
        throw InputError(fmt::format("{}:{}: velocity not finite", source, line));
      p.velocity[i] = table.velocity[i];
    }
  }
  check_pair_overlaps(drum, p, table, source);
  return p;
}

Particles file_fill(const SceneConfig& scene) {
  if (scene.fill.kind != FillKind::file) {
    throw InputError(fmt::format("{}: fill.kind: file_fill needs kind = \"file\"", scene.source));
  }
  const ParticleTable table = read_particle_csv(scene.fill.file);
  return particles_from_table(scene, table, scene.fill.file.string());
}

Particles initial_fill(const SceneConfig& scene) {
  switch (scene.fill.kind) {
    case FillKind::random:
      return random_fill(scene);
    case FillKind::file:
      return file_fill(scene);
    case FillKind::paper_packing:
      break;
  }
  throw InputError(fmt::format(
      "{}: fill.kind: 'paper_packing' is a static packing for `drumlab paper-table`, not a "
      "dynamic run",
      scene.source));
}

}  // namespace drumlab
