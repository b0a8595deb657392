#pragma once
// A cohesive link between two particles, as the analysis of agglomerates sees it: a live liquid
// bridge (engine/contact/liquid_bridge.hpp) or, once a law has it, an adhesive contact. The bond
// graph of a frame is ContactModel::bonds() / Simulation::bonds(); engine/analysis builds
// agglomerates on it and the HDF5 series stores it.
#include <string_view>

#include "engine/types.hpp"

namespace drumlab {

struct Bond {
  Index i = 0;          ///< storage slot, i < j
  Index j = 0;          ///< storage slot
  double volume = 0.0;  ///< liquid held by the bridge (m^3); 0 for a dry adhesive contact
  double force = 0.0;   ///< attractive normal force of the link at the current state (N), >= 0
  double age = 0.0;     ///< time since the link formed (s)
};

/// Name of the per-particle array (Particles::extra) holding each particle's liquid film volume
/// (m^3), registered by a scene with liquid migration.
inline constexpr std::string_view kLiquidFilmArray = "liquid_film";

}  // namespace drumlab
