#pragma once
// The registered cohesive law parts (cohesive_part.hpp says what a part declares). A new part is
// one header in engine/contact/ and one entry here. The order is the order in which the parts'
// forces add up on a pair (and their scalars sit in a contact's state): it fixes the bits, so a
// new part goes last.
#include "engine/contact/cohesive_part.hpp"
#include "engine/contact/liquid_bridge.hpp"
#include "engine/contact/sjkr_cohesion.hpp"

namespace drumlab {

using CohesiveParts = CohesivePartsOf<LiquidBridge, SjkrCohesion>;

}  // namespace drumlab
