#pragma once
// The default Verlet skin, in units of the smallest radius: the one place of this rule, read by
// the scene's [performance] defaults and by SearchTuning.
//
// 1 R_min: on the demo, deep, tilted and periodic drums it rebuilds half as often as 0.5 R_min
// and is faster on each (app/bench/README.md, "The skin again" under Roofline); a larger skin
// lists more pairs that never touch and gains nothing more.

namespace drumlab {

inline constexpr double kDefaultVerletSkin = 1.0;

}  // namespace drumlab
