// The colour table (render/palette.hpp): the focus picture's colours stand apart from the
// categorical palette, the neutral grey and each other, in CIE76 Delta E (sRGB, D65), so a focus
// candidate never reads as a particle of a size class.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "render/palette.hpp"

namespace drumlab::test {
namespace {

std::array<double, 3> lab(const double* rgb) {
  double c[3];
  for (int k = 0; k < 3; ++k) {  // sRGB to linear
    c[k] = rgb[k] <= 0.04045 ? rgb[k] / 12.92 : std::pow((rgb[k] + 0.055) / 1.055, 2.4);
  }
  const double xyz[3] = {(0.4124 * c[0] + 0.3576 * c[1] + 0.1805 * c[2]) / 0.95047,
                         0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2],
                         (0.0193 * c[0] + 0.1192 * c[1] + 0.9505 * c[2]) / 1.08883};
  double f[3];
  for (int k = 0; k < 3; ++k) {
    f[k] = xyz[k] > 0.008856 ? std::cbrt(xyz[k]) : 7.787 * xyz[k] + 16.0 / 116.0;
  }
  return {116.0 * f[1] - 16.0, 500.0 * (f[0] - f[1]), 200.0 * (f[1] - f[2])};
}

double delta_e(const double* a, const double* b) {
  const auto p = lab(a), q = lab(b);
  return std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
}

TEST(Palette, LabOfKnownColours) {
  const double white[3] = {1.0, 1.0, 1.0}, black[3] = {0.0, 0.0, 0.0};
  EXPECT_NEAR(lab(white)[0], 100.0, 0.01);
  EXPECT_NEAR(lab(white)[1], 0.0, 0.05);
  EXPECT_NEAR(lab(black)[0], 0.0, 1e-9);
  EXPECT_NEAR(delta_e(white, black), 100.0, 0.05);
}

TEST(Palette, FocusColoursStandApartFromTheCategoriesAndEachOther) {
  const std::vector<std::pair<std::string, const double*>> focus = {
      {"focus particle", render::kFocusParticleColor},
      {"own cell", render::kOwnCellColor},
      {"forward", render::kForwardCellColor},
      {"skipped", render::kSkippedCellColor},
      {"backward ring", render::kBackwardRingColor},
      {"candidate", render::kCandidateColor},
      {"contact", render::kContactColor},
      {"smaller level", render::kSmallerLevelColor}};
  for (const auto& [name, c] : focus) {
    for (std::size_t k = 0; k < render::kMaxCategories; ++k) {
      EXPECT_GE(delta_e(c, render::kCategories[k]), 40.0) << name << " vs category " << k;
    }
    EXPECT_GE(delta_e(c, render::kNeutralGrey), 40.0) << name << " vs the neutral grey";
    EXPECT_GE(delta_e(c, render::kBackground), 40.0) << name << " vs the background";
  }
  for (std::size_t i = 0; i < focus.size(); ++i) {
    for (std::size_t j = i + 1; j < focus.size(); ++j) {
      EXPECT_GE(delta_e(focus[i].second, focus[j].second), 30.0)
          << focus[i].first << " vs " << focus[j].first;
    }
  }
}

}  // namespace
}  // namespace drumlab::test
