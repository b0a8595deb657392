#pragma once
// The composed law's run-time choices (normal law, tangential spring, rolling part) turned into
// template arguments of a force loop, so the chosen law inlines (contact_model.cpp, the pair and
// analytic-wall loops; mesh_wall_loop.cpp, the triangle walls).
#include <stdexcept>
#include <type_traits>
#include <variant>

#include "engine/contact/contact_model.hpp"

namespace drumlab {

template <class Normal>
ContactLaw<Normal> make_law(const Normal& n, const MindlinTangential& t, const RollingResistance& r,
                            const RollingSpring& spring) {
  return {n, t, r, spring};
}

// Calls loop.template operator()<Normal, Tangential, Rolling>(law) with the scene's runtime
// choices turned into template arguments, so the chosen law inlines into the loop.
// The spring is compiled for the linear viscoelastic law only (the one it needs).
template <class Loop>
void with_law(const ContactLaw<NormalVariant>& parts, bool tangential, RollingKind rolling,
              Loop&& loop) {
  std::visit(
      [&](const auto& normal) {
        const auto law = make_law(normal, parts.tangential, parts.rolling, parts.rolling_spring);
        using N = std::decay_t<decltype(normal)>;
        const auto with_rolling = [&]<RollingKind R>() {
          if (tangential) {
            loop.template operator()<N, true, R>(law);
          } else {
            loop.template operator()<N, false, R>(law);
          }
        };
        if (rolling == RollingKind::torque) {
          with_rolling.template operator()<RollingKind::torque>();
        } else if (rolling == RollingKind::none) {
          with_rolling.template operator()<RollingKind::none>();
        } else if constexpr (std::is_same_v<N, LinearViscoelastic>) {
          with_rolling.template operator()<RollingKind::spring>();
        } else {
          throw std::logic_error("rolling spring without the linear viscoelastic law");
        }
      },
      parts.normal);
}

inline RollingKind rolling_kind(bool rolling, bool spring) {
  if (!rolling) return RollingKind::none;
  return spring ? RollingKind::spring : RollingKind::torque;
}

}  // namespace drumlab
