#pragma once
// Particles as a struct of arrays. Index i is the storage slot (may change when particles are
// re-sorted); id[i] is the stable identity given at creation.
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/types.hpp"

namespace drumlab {

struct ReorderBuffers;

/// An extra per-particle array of doubles registered by a law part (e.g. a liquid film volume,
/// m^3): re-ordering, checkpoints and (later) migration between ranks carry it like the fixed
/// arrays, through Particles::for_each_array.
struct ParticleArray {
  std::string name;
  std::vector<double> values;
  double initial = 0.0;  ///< value of a particle added later
};

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
  /// Registered extra arrays (add_array); empty for a dry scene. Not touched by the hot loops.
  std::vector<ParticleArray> extra;

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

  /// Registers an extra per-particle array named `name` (every particle gets `initial`) and
  /// returns it; particles added later get `initial` too. Throws InputError if the name is taken
  /// (by a fixed or an extra array), empty or holds a comma.
  std::vector<double>& add_array(std::string_view name, double initial = 0.0);
  /// The extra array `name`, or nullptr.
  std::vector<double>* find_array(std::string_view name);
  const std::vector<double>* find_array(std::string_view name) const;

  /// Calls f(name, array) for every per-particle array, fixed then extra, in a fixed order: the
  /// one list that reorder(), checkpoints and (later) migration pack. `array` is a
  /// std::vector<T>& for T in Vec3, double, std::uint8_t, Index.
  template <class F>
  void for_each_array(F&& f) {
    visit_arrays(*this, f);
  }
  template <class F>
  void for_each_array(F&& f) const {
    visit_arrays(*this, f);
  }

 private:
  template <class Self, class F>
  static void visit_arrays(Self& p, F& f) {
    f("position", p.position);
    f("velocity", p.velocity);
    f("omega", p.omega);
    f("force", p.force);
    f("torque", p.torque);
    f("radius", p.radius);
    f("mass", p.mass);
    f("inv_mass", p.inv_mass);
    f("inv_inertia", p.inv_inertia);
    f("size_class", p.size_class);
    f("id", p.id);
    for (auto& a : p.extra) f(std::string_view(a.name), a.values);
  }
};

}  // namespace drumlab
