#pragma once
// Particles as a struct of arrays. Index i is the storage slot (may change when particles are
// re-sorted); id[i] is the stable identity given at creation.
#include <cstddef>
#include <span>
#include <vector>

#include "engine/types.hpp"

namespace drumlab {

struct ReorderBuffers;

struct Particles {
  std::vector<Vec3> position;  ///< m
  std::vector<Vec3> velocity;  ///< m/s
  std::vector<Vec3> omega;     ///< angular velocity, rad/s
  std::vector<Vec3> force;     ///< N, accumulated each step
  std::vector<Vec3> torque;    ///< N m, accumulated each step
  std::vector<double> radius;  ///< m
  std::vector<double> mass;    ///< kg
  std::vector<double> inv_mass;
  std::vector<double> inv_inertia;       ///< 1 / (2/5 m r^2)
  std::vector<std::uint8_t> size_class;  ///< index into the scene's particle classes
  std::vector<Index> id;                 ///< stable id, 0..N-1 at creation

  std::size_t size() const { return radius.size(); }
  bool empty() const { return radius.empty(); }
  void reserve(std::size_t n);
  /// Appends a solid sphere at rest. Throws InputError for a non-positive radius or density.
  Index add(const Vec3& x, double r, double density, std::uint8_t cls = 0);
  void clear_forces();
  /// Re-orders every array: slot k gets the particle now at order[k] (a permutation of 0..n-1).
  void reorder(std::span<const Index> order, ReorderBuffers& scratch);
  double min_radius() const;
  double max_radius() const;
};

}  // namespace drumlab
