#pragma once
// Every colour the drum pictures use, in one place (RGB in [0, 1]): the continuous map, the
// categorical palette, the frame's greys, and the focus picture's colours. The focus colours are
// chosen apart from the categorical palette: each is at least 40 CIE76 Delta E from every
// category colour and from the neutral grey, and they are at least 30 apart from each other
// (tests/render/test_palette.cpp checks it), so a highlighted candidate never reads as a particle
// of a size class.
#include <cstddef>
#include <iterator>

namespace drumlab::render {

/// Viridis (van der Walt and Smith, matplotlib 2.0's default map, perceptually uniform and
/// readable in grey and by colour-blind readers): matplotlib's published table sampled at
/// t = 0, 0.1, ..., 1; the 256 colours of the map are interpolated linearly between them.
inline constexpr double kViridis[11][3] = {
    {0.267004, 0.004874, 0.329415}, {0.282623, 0.140926, 0.457517}, {0.253935, 0.265254, 0.529983},
    {0.206756, 0.371758, 0.553117}, {0.163625, 0.471133, 0.558148}, {0.127568, 0.566949, 0.550556},
    {0.134692, 0.658636, 0.517649}, {0.266941, 0.748751, 0.440573}, {0.477504, 0.821444, 0.318195},
    {0.741388, 0.873449, 0.149561}, {0.993248, 0.906157, 0.143936}};

/// Categories (size classes, agglomerates): the Okabe-Ito palette (Okabe and Ito 2008, "Color
/// Universal Design"), distinct for colour-blind readers; black is left out (the background is
/// dark). Orange, sky blue, bluish green, yellow, blue, vermillion, reddish purple.
inline constexpr double kCategories[7][3] = {
    {0.902, 0.624, 0.000}, {0.337, 0.706, 0.914}, {0.000, 0.620, 0.451}, {0.941, 0.894, 0.259},
    {0.000, 0.447, 0.698}, {0.835, 0.369, 0.000}, {0.800, 0.475, 0.655}};
inline constexpr std::size_t kMaxCategories = std::size(kCategories);

/// Grey of a particle alone in its agglomerate, and of every particle with "grey particles".
inline constexpr double kNeutralGrey[3] = {0.55, 0.57, 0.6};
/// Background colour of every frame.
inline constexpr double kBackground[3] = {0.11, 0.12, 0.15};
/// Colour of the back end cap, the plate behind the bed: light enough that viridis' dark low end
/// (slow particles) stands out against it.
inline constexpr double kBackCapColor[3] = {0.32, 0.33, 0.37};

/// Colour of the triangle walls ([[wall.mesh]], [[wall.lifters]]): a light, warm steel, apart
/// from the mantle's blue-grey, the back cap and the neutral grey of plain particles.
inline constexpr double kMeshWallColor[3] = {0.80, 0.78, 0.72};

/// The focus picture (render/grid_overlay.hpp): the focus particle (white), its own cell (crimson),
/// the forward half-stencil cells it visits (lime), the backward half it skips (dark red), method
/// 2's extra backward ring (blue-violet), the candidates it tests (cyan markers), the contacts it
/// finds (magenta markers and lines), a multi-level grid's smaller levels (lavender).
inline constexpr double kFocusParticleColor[3] = {1.0, 1.0, 1.0};
inline constexpr double kOwnCellColor[3] = {1.0, 0.0, 0.3};
inline constexpr double kForwardCellColor[3] = {0.55, 1.0, 0.0};
inline constexpr double kSkippedCellColor[3] = {0.55, 0.0, 0.1};
inline constexpr double kBackwardRingColor[3] = {0.2, 0.2, 1.0};
inline constexpr double kCandidateColor[3] = {0.0, 1.0, 1.0};
inline constexpr double kContactColor[3] = {1.0, 0.0, 1.0};
inline constexpr double kSmallerLevelColor[3] = {0.65, 0.35, 1.0};

}  // namespace drumlab::render
