#pragma once
// The user's own initial packing ([fill] kind = "file"), as LIGGGHTS' read_data: particles from a
// CSV x,y,z,r[,vx,vy,vz] (engine/io/particle_csv.hpp), validated against the scene. Policy:
// * every radius must be one of the scene's [[particles]] radii (relative tolerance 1e-6), or lie
//   in a distribution class's [min, max] (or be one of a table's radii), same tolerance; the
//   particle gets that class (so dt, the search grids and the colours stay those of the classes)
//   and, in a class of one radius, exactly its radius;
// * every centre must lie inside the drum (periodic ends: z is wrapped), and no particle may
//   overlap the mantle or an end cap by more than kMaxFileOverlap of its radius;
// * two particles may overlap by at most kMaxFileOverlap of the smaller radius: a larger overlap is
//   refused naming both particles (file lines); smaller ones are pushed apart by the contact law.
//   The release speed is then bounded by the stored elastic energy (v <= sqrt(2 E / m_eff)).
// The file must hold at least one particle. Every problem is one InputError "FILE:LINE: reason".
#include "engine/fill/random_fill.hpp"
#include "engine/io/particle_csv.hpp"
#include "engine/particles.hpp"
#include "engine/scene/scene_config.hpp"

namespace drumlab {

/// Largest initial overlap accepted from a file, as a fraction of the smaller radius.
inline constexpr double kMaxFileOverlap = 0.1;

/// The particles of `table` checked against `scene` (see the policy above); `source` names the
/// file in messages.
Particles particles_from_table(const SceneConfig& scene, const ParticleTable& table,
                               std::string_view source);
/// Reads scene.fill.file and applies particles_from_table. Needs fill.kind == file.
Particles file_fill(const SceneConfig& scene);
/// The scene's initial particles: random_fill or file_fill by fill.kind. Throws InputError for the
/// static paper packing.
Particles initial_fill(const SceneConfig& scene);

}  // namespace drumlab
