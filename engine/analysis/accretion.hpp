#pragma once
// Accretion onto seeds (Vo et al., "Particle dynamics simulation of wet granulation in a rotating
// drum", arXiv:1810.13438): a large wet seed tumbles in a bed of dry or lightly wet fines and
// gathers them. Per frame, the number of primaries held in the seeds' granules (by any granule
// criterion, engine/analysis/granule_criterion.hpp), and the curve fitted to that count against
// time. Vo et al. find the count grows as an exponential that saturates as the free wet particles
// run out: N(t) = N_inf - (N_inf - N_0) exp(-(t - t0) / tau).
#include <cstddef>
#include <cstdint>
#include <span>

#include "engine/analysis/agglomerates.hpp"

namespace drumlab {

/// Primaries in the granules of `frame` that hold a particle of class `seed_class` (size_class
/// in the frame's storage order), the seeds themselves not counted. 0 when no particle is of that
/// class. Throws std::invalid_argument if `size_class` and the frame's labels differ in length.
std::size_t accreted_count(const AgglomerateFrame& frame, std::span<const std::uint8_t> size_class,
                           std::uint8_t seed_class);

/// N(t) = n_inf - (n_inf - n0) exp(-(t - t0) / tau), least squares over the points.
struct SaturatingFit {
  double n0 = 0.0;
  double n_inf = 0.0;
  double tau = 0.0;               ///< s; the grid's longest tau when the points are a straight line
  double t0 = 0.0;                ///< s: the first point's time
  double rms = 0.0;               ///< root-mean-square residual (count)
  double r_squared = 0.0;         ///< 1 - residual / total sum of squares (1 when n is constant)
  double line_r_squared = 0.0;    ///< the same for the straight line n = a + b t, to compare
  bool tau_at_grid_edge = false;  ///< the best tau is the longest tried: the curve has not bent
};

/// Fits the saturating exponential to (t, n): for each tau on a logarithmic grid from a hundredth
/// of the smallest time step to a hundred times the span of t, n0 and n_inf are linear least
/// squares; the best tau is then refined by golden-section search between its grid neighbours.
/// Throws std::invalid_argument for fewer than 3 points, spans of different lengths, times that
/// do not increase or values that are not finite.
SaturatingFit fit_saturating_exponential(std::span<const double> t, std::span<const double> n);

/// The fit's value at time `t`.
double saturating_value(const SaturatingFit& fit, double t);

}  // namespace drumlab
