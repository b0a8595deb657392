#pragma once
// Each particle's history against the triangle walls (engine/mesh/): kMeshSlots slots, each the
// patch it touches (numbered across all meshes, + 1; 0: a free slot), the tangential spring xi
// and, with the rolling spring, xi_r. Kept in per-particle arrays (Particles::extra), so
// re-ordering, checkpoints and MPI migration carry them like every other array; only a scene
// with [[wall.mesh]] or [[wall.lifters]] registers them. A contact keeps its history while it
// lasts on the same patch, whichever triangle of the patch holds it (the history follows the
// contact across the patch's edges); a patch no longer touched loses it. Slot k holds the
// particle's k-th contact by patch number (packed: a free slot 0 means no history at all).
#include <array>
#include <string_view>

namespace drumlab {

/// Patches a particle can touch at once with history: a sphere at a lifter's foot touches its
/// blade, the mantle (analytic) and at most one more face; a fifth contact would act without
/// tangential history (its spring restarts every step).
inline constexpr std::size_t kMeshSlots = 4;

inline constexpr std::array<std::string_view, kMeshSlots> kMeshPatchArrays = {
    "mesh_patch_0", "mesh_patch_1", "mesh_patch_2", "mesh_patch_3"};
inline constexpr std::array<std::array<std::string_view, 3>, kMeshSlots> kMeshSpringArrays = {{
    {"mesh_xi_x_0", "mesh_xi_y_0", "mesh_xi_z_0"},
    {"mesh_xi_x_1", "mesh_xi_y_1", "mesh_xi_z_1"},
    {"mesh_xi_x_2", "mesh_xi_y_2", "mesh_xi_z_2"},
    {"mesh_xi_x_3", "mesh_xi_y_3", "mesh_xi_z_3"},
}};
inline constexpr std::array<std::array<std::string_view, 3>, kMeshSlots> kMeshRollingArrays = {{
    {"mesh_rolling_x_0", "mesh_rolling_y_0", "mesh_rolling_z_0"},
    {"mesh_rolling_x_1", "mesh_rolling_y_1", "mesh_rolling_z_1"},
    {"mesh_rolling_x_2", "mesh_rolling_y_2", "mesh_rolling_z_2"},
    {"mesh_rolling_x_3", "mesh_rolling_y_3", "mesh_rolling_z_3"},
}};

}  // namespace drumlab
