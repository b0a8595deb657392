#pragma once
// The liquid's initial condition (a scene with [liquid] and migration): each particle's liquid
// (liquid_content x its solid volume, or x the volume of a sphere of film_radius) split between its
// film and the bridges of the contacts present at the start (LiquidConfig::film_share). Run once,
// before the first step; the step's loops are cohesion_loops.hpp.
#include <vector>

#include "engine/contact/cohesive_laws.hpp"
#include "engine/contact/contact_history.hpp"
#include "engine/particles.hpp"
#include "engine/scene/scene_config.hpp"

namespace drumlab {

/// Fills the film array (registered) from the scene's liquid content (its class's
/// liquid_content where the class sets one, else [liquid].liquid_content): film_share of each
/// particle's liquid (content x its solid volume) in its film, the rest in `reserve`
/// (seed_bridges).
void fill_films(const SceneConfig& scene, Particles& p, std::vector<double>& reserve);

/// The initial split (LiquidConfig::film_share < 1): every touching listed pair gets a bridge from
/// the reserves of both particles (m^3 each, not in their films): each particle's reserve divided
/// equally among its touching pairs, the bridge capped at the maximum volume (both shares scaled
/// down alike); what a particle's reserve does not give goes to its film. Emptied on return.
void seed_bridges(const CohesiveParts& parts, Particles& p, ContactList& contacts, double period,
                  std::vector<double>& reserve);

}  // namespace drumlab
