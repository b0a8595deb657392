#include "engine/scene/size_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include <fmt/format.h>

namespace drumlab {
namespace {

/// Uniform in [0, 1): the top 53 bits of one output (fixed by the standard for mt19937_64).
double uniform01(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

/// Standard normal, Box-Muller on two uniforms (the cosine branch only).
double standard_normal(std::mt19937_64& rng) {
  const double u1 = 1.0 - uniform01(rng);  // (0, 1]: the log stays finite
  const double u2 = uniform01(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

/// A standard normal redrawn until |z| <= t.
double truncated_normal(std::mt19937_64& rng, double t) {
  for (;;) {
    const double z = standard_normal(rng);
    if (std::abs(z) <= t) return z;
  }
}

double normal_cdf(double x) {
  return 0.5 * std::erfc(-x / std::numbers::sqrt2);
}

double normal_pdf(double x) {
  return std::exp(-0.5 * x * x) / std::sqrt(2.0 * std::numbers::pi);
}

}  // namespace

std::string_view size_kind_name(SizeKind kind) {
  switch (kind) {
    case SizeKind::normal:
      return "normal";
    case SizeKind::lognormal:
      return "lognormal";
    case SizeKind::table:
      return "table";
    case SizeKind::single:
      break;
  }
  return "single";
}

std::optional<SizeKind> parse_size_kind(std::string_view name) {
  for (const SizeKind k : {SizeKind::normal, SizeKind::lognormal, SizeKind::table}) {
    if (name == size_kind_name(k)) return k;
  }
  return std::nullopt;
}

SizeDistribution SizeDistribution::single(double radius) {
  SizeDistribution d;
  d.a_ = d.min_ = d.max_ = radius;
  return d;
}

SizeDistribution SizeDistribution::normal(double mean, double sigma, double truncate) {
  SizeDistribution d;
  d.kind_ = SizeKind::normal;
  d.sigma_ = sigma;
  d.a_ = mean;
  d.b_ = sigma;
  d.truncate_ = truncate;
  d.min_ = mean - truncate * sigma;
  d.max_ = mean + truncate * sigma;
  return d;
}

SizeDistribution SizeDistribution::lognormal(double mean, double sigma, double truncate) {
  SizeDistribution d;
  d.kind_ = SizeKind::lognormal;
  d.sigma_ = sigma;
  const double s2 = std::log1p((sigma / mean) * (sigma / mean));
  d.b_ = std::sqrt(s2);
  d.a_ = std::log(mean) - 0.5 * s2;
  d.truncate_ = truncate;
  d.min_ = std::exp(d.a_ - truncate * d.b_);
  d.max_ = std::exp(d.a_ + truncate * d.b_);
  return d;
}

SizeDistribution SizeDistribution::table(std::vector<double> radii, std::vector<double> shares) {
  SizeDistribution d;
  d.kind_ = SizeKind::table;
  const double total = std::accumulate(shares.begin(), shares.end(), 0.0);
  double running = 0.0;
  for (double& s : shares) {
    s /= total;
    running += s;
    d.cumulative_.push_back(running);
  }
  if (!d.cumulative_.empty()) d.cumulative_.back() = 1.0;
  d.min_ = radii.empty() ? 0.0 : *std::min_element(radii.begin(), radii.end());
  d.max_ = radii.empty() ? 0.0 : *std::max_element(radii.begin(), radii.end());
  d.radii_ = std::move(radii);
  d.shares_ = std::move(shares);
  return d;
}

double SizeDistribution::moment(int k) const {
  switch (kind_) {
    case SizeKind::single:
      return std::pow(a_, k);
    case SizeKind::normal: {
      // Symmetric truncation at +-t: the mean stays, the variance shrinks by
      // 1 - 2 t phi(t) / (2 Phi(t) - 1); the third central moment is 0.
      const double t = truncate_;
      const double var = b_ * b_ * (1.0 - 2.0 * t * normal_pdf(t) / (2.0 * normal_cdf(t) - 1.0));
      if (k == 1) return a_;
      if (k == 2) return a_ * a_ + var;
      return a_ * a_ * a_ + 3.0 * a_ * var;
    }
    case SizeKind::lognormal: {
      // E[r^k | |z| <= t] = exp(k mu + k^2 s^2 / 2) (Phi(t - k s) - Phi(-t - k s)) / (2 Phi(t) -
      // 1).
      const double ks = k * b_;
      const double kept = normal_cdf(truncate_ - ks) - normal_cdf(-truncate_ - ks);
      return std::exp(k * a_ + 0.5 * ks * ks) * kept / (2.0 * normal_cdf(truncate_) - 1.0);
    }
    case SizeKind::table: {
      double sum = 0.0;
      for (std::size_t i = 0; i < radii_.size(); ++i) sum += shares_[i] * std::pow(radii_[i], k);
      return sum;
    }
  }
  return 0.0;
}

double SizeDistribution::radius_sd() const {
  const double mean = moment(1);
  return std::sqrt(std::max(0.0, moment(2) - mean * mean));
}

bool SizeDistribution::holds(double r, double rel_tol) const {
  const auto near = [&](double x) { return std::abs(r - x) <= rel_tol * x; };
  if (kind_ == SizeKind::single) return near(a_);
  if (kind_ == SizeKind::table) return std::any_of(radii_.begin(), radii_.end(), near);
  return r >= min_ * (1.0 - rel_tol) && r <= max_ * (1.0 + rel_tol);
}

std::string SizeDistribution::describe() const {
  if (kind_ == SizeKind::single) return fmt::format("r = {} m", a_);
  std::string what;
  if (kind_ == SizeKind::table) {
    what = fmt::format("{} radii", radii_.size());
  } else {
    what = fmt::format("sigma {:.4g} m, truncated at {} sigma{}", sigma_, truncate_,
                       kind_ == SizeKind::lognormal ? " of ln r" : "");
  }
  return fmt::format("{}: mean {:.4g} m, sd {:.4g} m as drawn ({}), r in [{:.4g}, {:.4g}] m",
                     size_kind_name(kind_), mean_radius(), radius_sd(), what, min_, max_);
}

double SizeDistribution::draw(std::mt19937_64& rng) const {
  switch (kind_) {
    case SizeKind::single:
      return a_;
    case SizeKind::normal:
      return a_ + b_ * truncated_normal(rng, truncate_);
    case SizeKind::lognormal:
      return std::clamp(std::exp(a_ + b_ * truncated_normal(rng, truncate_)), min_, max_);
    case SizeKind::table: {
      const double u = uniform01(rng);
      const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), u);
      const auto i = std::min<std::size_t>(static_cast<std::size_t>(it - cumulative_.begin()),
                                           radii_.size() - 1);
      return radii_[i];
    }
  }
  return a_;
}

}  // namespace drumlab
