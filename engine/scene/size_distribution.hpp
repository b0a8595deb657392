#pragma once
// The radii of one particle class: one radius, a truncated normal or lognormal distribution, or a
// table of radii with number shares (scene keys `distribution`, `radius`, `radius_sigma`,
// `truncate`, `radii`, `shares` of a [[particles]] table; engine/README.md "Size distributions").
// A small value type: its bounds and moments in closed form, and a deterministic draw.
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <vector>

namespace drumlab {

enum class SizeKind : std::uint8_t {
  single,     ///< every particle has `radius`
  normal,     ///< normal radius, mean `radius`, standard deviation `radius_sigma`
  lognormal,  ///< lognormal radius with that mean and standard deviation (of the radius itself)
  table,      ///< `radii` drawn with the number `shares`
};

/// "single", "normal", "lognormal", "table".
std::string_view size_kind_name(SizeKind kind);
/// The kind of a scene's `distribution` value ("normal", "lognormal", "table"); nullopt otherwise.
std::optional<SizeKind> parse_size_kind(std::string_view name);

/// Truncation of the normal and lognormal kinds when the scene gives none (standard deviations).
inline constexpr double kDefaultTruncate = 3.0;

/// Preconditions (scene validation checks them): radii, sigma, truncate and shares > 0 and finite;
/// normal: mean - truncate * sigma > 0; table: radii and shares of the same length.
class SizeDistribution {
 public:
  static SizeDistribution single(double radius);
  /// Radii outside mean +- truncate * sigma are redrawn.
  static SizeDistribution normal(double mean, double sigma, double truncate);
  /// ln r is normal with mu, s chosen so that the untruncated radius has this mean and standard
  /// deviation: s^2 = ln(1 + sigma^2 / mean^2), mu = ln(mean) - s^2 / 2. Truncated in ln r at
  /// mu +- truncate * s (so the smallest radius stays > 0 however wide the spread).
  static SizeDistribution lognormal(double mean, double sigma, double truncate);
  /// Number shares, normalised here.
  static SizeDistribution table(std::vector<double> radii, std::vector<double> shares);

  SizeKind kind() const { return kind_; }
  double min_radius() const { return min_; }
  double max_radius() const { return max_; }
  /// Moments of the radius as drawn (after truncation), in closed form.
  double mean_radius() const { return moment(1); }
  double radius_sd() const;
  /// E[r^3], m^3: a class's particle count from its share of the solid volume uses it.
  double mean_cube() const { return moment(3); }
  /// E[r^k] for k = 1, 2, 3 (as drawn).
  double moment(int k) const;

  /// Whether a particle of radius r can belong to the class: within `rel_tol` (relative) of the
  /// one radius or of one of a table's radii, or inside [min, max] widened by it.
  bool holds(double r, double rel_tol) const;
  /// "r = 0.002 m", "normal: mean 0.002 m, sigma 0.0002 m, truncated at 3 sigma, r in [a, b] m".
  std::string describe() const;

  /// One radius from `rng`. single: the radius, `rng` untouched. The uniforms are the top 53 bits
  /// of one mt19937_64 output (its sequence is fixed by the standard), the normals Box-Muller on
  /// them, the truncation a redraw: no <random> distribution is used, so a seed gives the same
  /// radii with any standard library (and libm).
  double draw(std::mt19937_64& rng) const;

 private:
  SizeKind kind_ = SizeKind::single;
  double a_ = 0.0;         ///< single: radius; normal: mean; lognormal: mu of ln r
  double b_ = 0.0;         ///< normal: sigma; lognormal: s of ln r
  double truncate_ = 0.0;  ///< in standard deviations (of r, of ln r)
  double sigma_ = 0.0;     ///< normal, lognormal: the requested standard deviation of r
  double min_ = 0.0, max_ = 0.0;
  std::vector<double> radii_;       ///< table
  std::vector<double> cumulative_;  ///< table: normalised running sum of the shares
  std::vector<double> shares_;      ///< table: normalised shares
};

}  // namespace drumlab
