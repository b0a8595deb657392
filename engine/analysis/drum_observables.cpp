#include "engine/analysis/drum_observables.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include <fmt/format.h>

#include "engine/drum.hpp"
#include "engine/drum_orbit.hpp"
#include "engine/search/contact_search.hpp"
#include "engine/simulation.hpp"

namespace drumlab {
namespace {

void validate(const Particles& p, const DrumGeometry& drum, const ObservableOptions& o) {
  const std::size_t n = p.size();
  if (p.position.size() != n || p.velocity.size() != n || p.mass.size() != n ||
      p.omega.size() != n || p.inv_inertia.size() != n) {
    throw InputError("drum observables: particle arrays differ in size");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!(p.radius[i] > 0.0) || !p.position[i].allFinite() || !p.velocity[i].allFinite()) {
      throw InputError(fmt::format("drum observables: particle {} has a bad radius or state", i));
    }
  }
  if (!(drum.radius > 0.0)) throw InputError("drum observables: drum radius must be positive");
  if (!(o.end_exclusion >= 0.0 && o.end_exclusion <= 0.45)) {
    throw InputError("drum observables: end_exclusion must lie in [0, 0.45]");
  }
  if (!(o.column_width >= 0.0) || !(o.flight_gap >= 0.0)) {
    throw InputError("drum observables: column_width and flight_gap must be >= 0");
  }
}

double median(std::vector<double> v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2 == 1) return *mid;
  return 0.5 * (*mid + *std::max_element(v.begin(), mid));
}

/// Column tops -> one surface height per carry bin (median over the z columns).
std::vector<SurfaceHeight> surface_points(const Particles& p, const Vec3& up, const Vec3& carry,
                                          double width) {
  std::map<std::pair<long, long>, double> column_top;  // (carry bin, z bin) -> highest top
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3& x = p.position[i];
    const auto key = std::make_pair(static_cast<long>(std::floor(carry.dot(x) / width)),
                                    static_cast<long>(std::floor(x.z() / width)));
    const double top = up.dot(x) + p.radius[i];
    auto [it, inserted] = column_top.try_emplace(key, top);
    if (!inserted) it->second = std::max(it->second, top);
  }
  std::vector<SurfaceHeight> out;
  std::vector<double> tops;
  for (auto it = column_top.begin(); it != column_top.end();) {
    const long bin = it->first.first;
    tops.clear();
    for (; it != column_top.end() && it->first.first == bin; ++it) tops.push_back(it->second);
    out.push_back({(static_cast<double>(bin) + 0.5) * width, median(tops)});
  }
  return out;  // sorted by h (map order)
}

/// Least-squares polynomial of the given degree through the points; coefficients low to high.
Eigen::VectorXd poly_fit(const std::vector<SurfaceHeight>& pts, int degree, double h0) {
  Eigen::MatrixXd a(static_cast<Eigen::Index>(pts.size()), degree + 1);
  Eigen::VectorXd y(static_cast<Eigen::Index>(pts.size()));
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const auto r = static_cast<Eigen::Index>(k);
    double t = 1.0;
    for (int d = 0; d <= degree; ++d) {
      a(r, d) = t;
      t *= pts[k].h - h0;
    }
    y(r) = pts[k].u;
  }
  return a.colPivHouseholderQr().solve(y);
}

double poly_value(const Eigen::VectorXd& c, double t) {
  double v = 0.0;
  for (Eigen::Index d = c.size() - 1; d >= 0; --d) v = v * t + c(d);
  return v;
}

/// Flowing-layer thickness from the downhill velocity profile across depth (see the header).
void measure_flowing_layer(const Particles& p, const Vec3& up, const Vec3& carry,
                           const SurfaceFit& line, DrumObservables& obs) {
  const double len = std::sqrt(1.0 + line.b * line.b);
  const Vec3 along = (carry + line.b * up) / len;  // rises with carry for b > 0
  const Vec3 downhill = line.b >= 0.0 ? Vec3(-along) : along;
  const double bin = 2.0 * p.min_radius();
  std::vector<double> sum_v, sum_d;
  std::vector<std::size_t> count;
  double deepest = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double h = carry.dot(p.position[i]);
    if (h < line.h_lo || h > line.h_hi) continue;
    // Depth of the centre below the line, measured along the line's normal.
    const double depth = ((line.a + line.b * h) - up.dot(p.position[i])) / len;
    if (depth < 0.0) continue;  // above the surface: in flight, not part of the layer profile
    deepest = std::max(deepest, depth);
    const auto k = static_cast<std::size_t>(depth / bin);
    if (k >= count.size()) {
      count.resize(k + 1, 0);
      sum_v.resize(k + 1, 0.0);
      sum_d.resize(k + 1, 0.0);
    }
    ++count[k];
    sum_v[k] += downhill.dot(p.velocity[i]);
    sum_d[k] += depth;
  }
  obs.bed_depth = deepest;
  obs.flowing_layer_thickness = 0.0;
  double prev_v = 0.0, prev_d = 0.0;
  bool have_prev = false;
  for (std::size_t k = 0; k < count.size(); ++k) {
    if (count[k] == 0) continue;
    const double v = sum_v[k] / static_cast<double>(count[k]);
    const double d = sum_d[k] / static_cast<double>(count[k]);
    if (!have_prev) {
      if (v <= 0.0) return;  // the top does not flow downhill: no flowing layer
    } else if (v <= 0.0) {
      obs.flowing_layer_thickness = prev_d + (d - prev_d) * prev_v / (prev_v - v);
      return;
    }
    prev_v = v;
    prev_d = d;
    have_prev = true;
  }
  obs.flowing_layer_thickness = have_prev ? deepest : 0.0;
}

double airborne_fraction(const Particles& p, const DrumGeometry& drum, double gap) {
  auto search = make_search("m5");
  SearchInput in{p.position, p.radius, gap, std::nullopt, drum.period_z};
  std::vector<IndexPair> pairs;
  search->find_pairs(in, pairs);
  std::vector<char> touched(p.size(), 0);
  for (const auto& pr : pairs) touched[pr.i] = touched[pr.j] = 1;
  std::size_t flying = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3& x = p.position[i];
    const double rho = std::hypot(x.x(), x.y());
    if (!touched[i] && rho + p.radius[i] + gap < drum.radius) ++flying;
  }
  return static_cast<double>(flying) / static_cast<double>(p.size());
}

}  // namespace

std::optional<SurfaceFit> fit_surface_profile(const std::vector<SurfaceHeight>& all,
                                              double exclusion) {
  if (all.empty()) return std::nullopt;
  const double lo = all.front().h;
  const double hi = all.back().h;
  const double cut = exclusion * (hi - lo);
  std::vector<SurfaceHeight> pts;
  for (const auto& s : all) {
    if (s.h >= lo + cut - 1e-12 && s.h <= hi - cut + 1e-12) pts.push_back(s);
  }
  if (pts.size() < 3) return std::nullopt;
  const double h0 = 0.5 * (pts.front().h + pts.back().h);
  const Eigen::VectorXd line = poly_fit(pts, 1, h0);
  SurfaceFit out;
  out.a = line(0) - line(1) * h0;
  out.b = line(1);
  out.h_lo = lo + cut;
  out.h_hi = hi - cut;
  double sq = 0.0;
  for (const auto& s : pts) sq += std::pow(s.u - poly_value(line, s.h - h0), 2);
  out.points = pts.size();
  out.chord = pts.back().h - pts.front().h;
  out.rms = std::sqrt(sq / static_cast<double>(pts.size()));
  out.angle_deg = std::atan(out.b) * 180.0 / std::numbers::pi;
  if (pts.size() >= 5 && out.chord > 0.0) {
    const Eigen::VectorXd cubic = poly_fit(pts, 3, h0);
    double dev = 0.0;
    for (const auto& s : pts) {
      dev = std::max(dev, std::abs(poly_value(cubic, s.h - h0) - poly_value(line, s.h - h0)));
    }
    out.curvature = dev / out.chord;
  }
  return out;
}

DrumObservables measure_drum(const Particles& p, const DrumGeometry& drum,
                             const ObservableOptions& options) {
  validate(p, drum, options);
  DrumObservables obs;
  obs.particles = p.size();
  const Vec3 g_cross(drum.gravity.x(), drum.gravity.y(), 0.0);
  if (!(g_cross.norm() > 0.0)) {
    throw InputError("drum observables: gravity has no component across the drum axis");
  }
  obs.up = -g_cross.normalized();
  obs.field = g_cross.norm();
  obs.radius = drum.radius;
  const double drive = drum.omega - drum.field_omega;  // the wall against the field
  obs.carry = (drive < 0.0 ? -1.0 : 1.0) * Vec3::UnitZ().cross(-obs.up);
  if (p.empty()) return obs;

  double mass = 0.0, ke = 0.0, re = 0.0, sb = 0.0, rel = 0.0;
  Vec3 mx = Vec3::Zero();
  std::size_t upper = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3& x = p.position[i];
    const double m = p.mass[i];
    mass += m;
    mx += m * x;
    ke += 0.5 * m * p.velocity[i].squaredNorm();
    re += 0.5 * p.omega[i].squaredNorm() / p.inv_inertia[i];
    sb += 0.5 * m * drum.omega * drum.omega * (x.x() * x.x() + x.y() * x.y());
    rel += (p.velocity[i] - drum.omega * Vec3::UnitZ().cross(x)).norm();
    if (obs.up.dot(x) > 0.0) ++upper;
  }
  const auto n = static_cast<double>(p.size());
  obs.mean_kinetic_energy = ke / n;
  obs.mean_rotational_energy = re / n;
  obs.solid_body_energy = sb / n;
  obs.centre_of_mass = mx / mass;
  obs.com_offset = std::hypot(obs.centre_of_mass.x(), obs.centre_of_mass.y()) / drum.radius;
  obs.com_angle_deg =
      std::atan2(obs.carry.dot(obs.centre_of_mass), -obs.up.dot(obs.centre_of_mass)) * 180.0 /
      std::numbers::pi;
  obs.upper_fraction = static_cast<double>(upper) / n;
  obs.relative_speed = rel / n;
  obs.wall_speed = std::abs(drive) * drum.radius;

  const double width = options.column_width > 0.0 ? options.column_width : 2.0 * p.max_radius();
  const double gap = options.flight_gap > 0.0 ? options.flight_gap : 0.25 * p.min_radius();
  obs.airborne_fraction = airborne_fraction(p, drum, gap);
  obs.surface_profile = surface_points(p, obs.up, obs.carry, width);
  const auto line = fit_surface_profile(obs.surface_profile, options.end_exclusion);
  if (line) {
    obs.surface_found = true;
    obs.angle_of_repose_deg = line->angle_deg;
    obs.surface_points = line->points;
    obs.surface_chord = line->chord;
    obs.surface_rms = line->rms;
    obs.surface_curvature = line->curvature;
    measure_flowing_layer(p, obs.up, obs.carry, *line, obs);
  }
  return obs;
}

DrumObservables measure_drum(const Simulation& sim, const ObservableOptions& options) {
  const auto& d = sim.scene().drum;
  DrumGeometry g;
  g.gravity = sim.body_acceleration();  // gravity, plus a planetary carrier's field
  g.omega = sim.drum_omega();
  // The carrier's field turns with the arm; where it outweighs gravity across the axis, the
  // field turns at the carrier's rate (else gravity keeps its mean direction).
  const Vec3& g0 = sim.gravity();
  if (d.orbit.active() && carrier_field(d.orbit) > std::hypot(g0.x(), g0.y())) {
    g.field_omega = sim.carrier_omega();
  }
  g.radius = 0.5 * d.diameter;
  if (d.ends == DrumEnds::periodic) g.period_z = d.depth;
  return measure_drum(sim.particles(), g, options);
}

}  // namespace drumlab
