#include "engine/contact/law_probe.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "engine/contact/cohesion_loops.hpp"
#include "engine/contact/contact_model.hpp"
#include "engine/contact/liquid_start.hpp"
#include "engine/drum.hpp"

namespace drumlab {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Time between positions (s): only the ages of bridges and contacts advance with it.
constexpr double kProbeDt = 1e-6;

std::uint8_t checked_class(const SceneConfig& scene, std::uint8_t c) {
  if (c >= scene.classes.size()) {
    throw InputError(fmt::format("law: particle class {} out of range (the scene has {})", c,
                                 scene.classes.size()));
  }
  return c;
}

// The probe's bodies: their particles with the scene's liquid arrays, and a function that puts
// them at gap s and returns (normal force, bridge volume) from the model.
struct Bodies {
  Particles p;
  ContactList contacts;
  PairForceBuffers buffers;
  WallHistory wall_history;
};

}  // namespace

LawCurve probe_law(const SceneConfig& scene, const LawProbeOptions& o) {
  const ContactModel model(scene);
  const Drum drum(scene.drum);
  const ParticleClass& a = scene.classes.at(checked_class(scene, o.class_a));
  const ParticleClass& b = scene.classes.at(checked_class(scene, o.class_b));
  // A size distribution is probed at its mean radius.
  const double ra = a.mean_radius();
  const double rb = b.mean_radius();
  const double r_min = o.wall ? ra : std::min(ra, rb);
  const double overlap = o.overlap < 0.0 ? 0.02 * r_min : o.overlap;
  if (!(overlap > 0.0) || !(overlap < r_min)) {
    throw InputError(fmt::format("law: overlap must be in (0, {}) m, got {}", r_min, overlap));
  }
  const double start = o.start_gap < 0.0 ? 0.1 * r_min : o.start_gap;
  const double range = o.wall ? model.wall_range() : model.max_pair_range();
  const double end = o.end_gap < 0.0 ? 1.5 * range + start : o.end_gap;
  const std::size_t steps = std::max<std::size_t>(o.steps, 2);

  Bodies bodies;
  Particles& p = bodies.p;
  p.add(Vec3::Zero(), ra, scene.material.density, o.class_a);
  if (!o.wall) p.add(Vec3::Zero(), rb, scene.material.density, o.class_b);
  for (const std::string_view name : model.particle_arrays(kWallParts)) {
    p.add_array(name, 0.0);
  }
  if (p.find_array(kLiquidFilmArray) != nullptr) {
    std::vector<double> reserve;
    fill_films(scene, p, reserve);  // the reserve: no contacts
  }
  bodies.contacts.set_state_size(model.pair_state_size());
  bodies.wall_history.assign(p.size(), {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()});
  const std::vector<IndexPair> pair = {{0, 1}};
  const std::vector<Index> candidate = {0};
  // The mantle's lowest point: the wall normal (into the particle) is +y.
  const Vec3 wall_centre(0.0, 0.0, 0.5 * drum.depth());

  const auto sample = [&](double gap, bool retreat) {
    LawSample s{gap, 0.0, 0.0, retreat};
    p.clear_forces();
    if (o.wall) {
      p.position[0] = wall_centre + Vec3(0.0, -(drum.radius() - ra - gap), 0.0);
      model.add_wall_forces(p, candidate, drum, 0.0, bodies.wall_history, kProbeDt, kProbeDt);
      s.normal_force = p.force[0].y();
      if (const auto* v = p.find_array(kWallBridgeVolumeArrays[0])) s.bridge_volume = (*v)[0];
    } else {
      // Particle 0 on the +x side of particle 1: the normal towards 0 is +x.
      p.position[0] = Vec3(ra + rb + gap, 0.0, 0.0);
      p.position[1] = Vec3::Zero();
      bodies.contacts.update(pair, 2);
      model.add_pair_forces(p, bodies.contacts, bodies.buffers, 0.0, kProbeDt, kProbeDt);
      s.normal_force = p.force[0].x();
      if (model.part<LiquidBridge>() != nullptr) {
        const std::size_t at = model.cohesive_parts().offset<LiquidBridge>();
        s.bridge_volume = LiquidBridge::liquid(bodies.contacts.find_state(0, 1) + at);
      }
    }
    return s;
  };

  LawCurve curve;
  curve.label = o.wall ? fmt::format("{}-wall", a.name) : fmt::format("{}-{}", a.name, b.name);
  curve.last_bridged_gap = kNaN;
  curve.rupture_gap = kNaN;
  curve.predicted_rupture = kNaN;
  for (std::size_t k = 0; k < steps; ++k) {
    const double t = static_cast<double>(k) / static_cast<double>(steps - 1);
    curve.samples.push_back(sample(start + t * (-overlap - start), false));
  }
  for (std::size_t k = 0; k < steps; ++k) {
    const double t = static_cast<double>(k) / static_cast<double>(steps - 1);
    const LawSample s = sample(-overlap + t * (end + overlap), true);
    if (s.bridge_volume > 0.0) {
      curve.last_bridged_gap = s.gap;
      const LiquidBridge& bridge = *model.part<LiquidBridge>();
      const BridgeLiquid& liquid = o.wall ? bridge.wall : bridge.pair;
      curve.predicted_rupture = liquid.rupture_distance(s.bridge_volume);
    } else if (!std::isnan(curve.last_bridged_gap) && std::isnan(curve.rupture_gap)) {
      curve.rupture_gap = s.gap;
    }
    curve.samples.push_back(s);
  }
  return curve;
}

}  // namespace drumlab
