#include "engine/particles.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <type_traits>

#include <fmt/format.h>

#include "engine/spatial_order.hpp"

namespace drumlab {

void Particles::reserve(std::size_t n) {
  position.reserve(n);
  velocity.reserve(n);
  omega.reserve(n);
  force.reserve(n);
  torque.reserve(n);
  radius.reserve(n);
  mass.reserve(n);
  inv_mass.reserve(n);
  inv_inertia.reserve(n);
  size_class.reserve(n);
  id.reserve(n);
  for (ParticleArray& a : extra) a.values.reserve(n);
}

Index Particles::add(const Vec3& x, double r, double density, std::uint8_t cls) {
  if (!(r > 0.0) || !std::isfinite(r)) {
    throw InputError(fmt::format("particle radius must be positive and finite, got {}", r));
  }
  if (!(density > 0.0) || !std::isfinite(density)) {
    throw InputError(fmt::format("particle density must be positive and finite, got {}", density));
  }
  if (!x.allFinite()) throw InputError("particle position must be finite");
  const double m = density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const auto i = static_cast<Index>(size());
  position.push_back(x);
  velocity.push_back(Vec3::Zero());
  omega.push_back(Vec3::Zero());
  force.push_back(Vec3::Zero());
  torque.push_back(Vec3::Zero());
  radius.push_back(r);
  mass.push_back(m);
  inv_mass.push_back(1.0 / m);
  inv_inertia.push_back(1.0 / (0.4 * m * r * r));
  size_class.push_back(cls);
  id.push_back(i);
  for (ParticleArray& a : extra) a.values.push_back(a.initial);
  return i;
}

void Particles::clear_forces() {
  const auto n = static_cast<std::int64_t>(force.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    force[i].setZero();
    torque[i].setZero();
  }
}

void Particles::reorder(std::span<const Index> order, ReorderBuffers& scratch) {
  for_each_array([&]<class T>(std::string_view, std::vector<T>& a) {
    if constexpr (std::is_same_v<T, Vec3>) {
      apply_order(a, order, scratch.vec3);
    } else if constexpr (std::is_same_v<T, double>) {
      apply_order(a, order, scratch.real);
    } else if constexpr (std::is_same_v<T, std::uint8_t>) {
      apply_order(a, order, scratch.byte);
    } else {
      static_assert(std::is_same_v<T, Index>);
      apply_order(a, order, scratch.index);
    }
  });
}

std::vector<double>& Particles::add_array(std::string_view name, double initial) {
  bool taken = name.empty() || name.find(',') != std::string_view::npos;
  for_each_array([&](std::string_view have, const auto&) { taken = taken || have == name; });
  if (taken) {
    throw InputError(
        fmt::format("particle array '{}': empty, with a comma, or already registered", name));
  }
  extra.push_back(ParticleArray{std::string(name), std::vector<double>(size(), initial), initial});
  return extra.back().values;
}

std::vector<double>* Particles::find_array(std::string_view name) {
  for (ParticleArray& a : extra) {
    if (a.name == name) return &a.values;
  }
  return nullptr;
}

const std::vector<double>* Particles::find_array(std::string_view name) const {
  for (const ParticleArray& a : extra) {
    if (a.name == name) return &a.values;
  }
  return nullptr;
}

double Particles::min_radius() const {
  return radius.empty() ? 0.0 : *std::min_element(radius.begin(), radius.end());
}

double Particles::max_radius() const {
  return radius.empty() ? 0.0 : *std::max_element(radius.begin(), radius.end());
}

}  // namespace drumlab
