#include "engine/analysis/accretion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace drumlab {

std::size_t accreted_count(const AgglomerateFrame& frame, std::span<const std::uint8_t> size_class,
                           std::uint8_t seed_class) {
  if (size_class.size() != frame.label.size() || frame.size_of.size() != frame.label.size()) {
    throw std::invalid_argument("accreted_count: size_class, labels and sizes differ in length");
  }
  std::vector<std::uint32_t> granules;
  std::size_t seeds = 0;
  std::size_t held = 0;
  for (std::size_t i = 0; i < size_class.size(); ++i) {
    if (size_class[i] != seed_class) continue;
    ++seeds;
    if (std::find(granules.begin(), granules.end(), frame.label[i]) != granules.end()) continue;
    granules.push_back(frame.label[i]);
    held += frame.size_of[i];
  }
  return held - seeds;
}

namespace {

struct Candidate {
  double tau = 0.0;
  double n0 = 0.0;
  double n_inf = 0.0;
  double residual = std::numeric_limits<double>::infinity();
};

/// n = a + b x least squares; returns a, b and the residual sum of squares.
Candidate linear_fit(std::span<const double> x, std::span<const double> n) {
  const double count = static_cast<double>(x.size());
  double sx = 0.0, sn = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sx += x[k];
    sn += n[k];
  }
  const double mx = sx / count, mn = sn / count;
  double sxx = 0.0, sxn = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sxx += (x[k] - mx) * (x[k] - mx);
    sxn += (x[k] - mx) * (n[k] - mn);
  }
  Candidate c;
  const double b = sxx > 0.0 ? sxn / sxx : 0.0;
  c.n0 = mn - b * mx;  // a
  c.n_inf = b;         // b
  c.residual = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double r = n[k] - (c.n0 + b * x[k]);
    c.residual += r * r;
  }
  return c;
}

/// For a fixed tau the model is n = n_inf + (n0 - n_inf) e_k, e_k = exp(-(t_k - t0) / tau):
/// linear in e with intercept n_inf and slope n0 - n_inf.
Candidate at_tau(std::span<const double> t, std::span<const double> n, double tau) {
  std::vector<double> e(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) e[k] = std::exp(-(t[k] - t.front()) / tau);
  const Candidate line = linear_fit(e, n);
  Candidate c;
  c.tau = tau;
  c.n_inf = line.n0;
  c.n0 = line.n0 + line.n_inf;
  c.residual = line.residual;
  return c;
}

}  // namespace

SaturatingFit fit_saturating_exponential(std::span<const double> t, std::span<const double> n) {
  if (t.size() != n.size()) throw std::invalid_argument("fit: times and counts differ in length");
  if (t.size() < 3) throw std::invalid_argument("fit: needs at least 3 points");
  double smallest_step = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (!std::isfinite(t[k]) || !std::isfinite(n[k])) {
      throw std::invalid_argument("fit: a time or a count is not finite");
    }
    if (k > 0) {
      if (!(t[k] > t[k - 1])) throw std::invalid_argument("fit: times must increase");
      smallest_step = std::min(smallest_step, t[k] - t[k - 1]);
    }
  }
  const double span = t.back() - t.front();
  const double low = 0.01 * smallest_step, high = 100.0 * span;
  constexpr int kGrid = 400;
  std::vector<Candidate> grid;
  grid.reserve(kGrid + 1);
  for (int g = 0; g <= kGrid; ++g) {
    grid.push_back(at_tau(t, n, low * std::pow(high / low, static_cast<double>(g) / kGrid)));
  }
  const auto best_it = std::min_element(grid.begin(), grid.end(), [](const auto& a, const auto& b) {
    return a.residual < b.residual;
  });
  const std::size_t g = static_cast<std::size_t>(best_it - grid.begin());
  Candidate best = *best_it;
  // Golden section on log tau between the grid neighbours.
  double a = std::log(grid[g == 0 ? 0 : g - 1].tau),
         b = std::log(grid[std::min<std::size_t>(g + 1, kGrid)].tau);
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = b - phi * (b - a), x2 = a + phi * (b - a);
  Candidate c1 = at_tau(t, n, std::exp(x1)), c2 = at_tau(t, n, std::exp(x2));
  for (int it = 0; it < 100 && b - a > 1e-12; ++it) {
    if (c1.residual < c2.residual) {
      b = x2;
      x2 = x1;
      c2 = c1;
      x1 = b - phi * (b - a);
      c1 = at_tau(t, n, std::exp(x1));
    } else {
      a = x1;
      x1 = x2;
      c1 = c2;
      x2 = a + phi * (b - a);
      c2 = at_tau(t, n, std::exp(x2));
    }
  }
  for (const Candidate& c : {c1, c2}) {
    if (c.residual < best.residual) best = c;
  }
  double mean = 0.0;
  for (const double v : n) mean += v;
  mean /= static_cast<double>(n.size());
  double total = 0.0;
  for (const double v : n) total += (v - mean) * (v - mean);
  SaturatingFit fit;
  fit.n0 = best.n0;
  fit.n_inf = best.n_inf;
  fit.tau = best.tau;
  fit.t0 = t.front();
  fit.rms = std::sqrt(best.residual / static_cast<double>(n.size()));
  fit.r_squared = total > 0.0 ? 1.0 - best.residual / total : 1.0;
  const Candidate line = linear_fit(t, n);
  fit.line_r_squared = total > 0.0 ? 1.0 - line.residual / total : 1.0;
  fit.tau_at_grid_edge = g == static_cast<std::size_t>(kGrid);
  return fit;
}

double saturating_value(const SaturatingFit& fit, double t) {
  return fit.n_inf - (fit.n_inf - fit.n0) * std::exp(-(t - fit.t0) / fit.tau);
}

}  // namespace drumlab
