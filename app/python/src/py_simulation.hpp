#pragma once
// drumlab.Simulation and its array context (py_simulation.cpp).
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "app/python/src/py_scene.hpp"
#include "engine/session/run_session.hpp"

namespace drumlab::python {

class PySimulation {
 public:
  PySimulation(const PyScene& scene, const std::string& method, int threads, double dt_factor);
  void settle();
  std::uint64_t run(std::optional<std::uint64_t> steps, std::optional<double> revolutions,
                    const pybind11::object& callback, std::uint64_t every);
  pybind11::dict observables() const;
  pybind11::dict agglomerates(const std::string& criterion, double age, double resolution) const;
  pybind11::dict contacts() const;
  void checkpoint(const std::string& path) const;
  void set_velocity(const std::vector<std::int64_t>& ids,
                    const std::vector<std::array<double, 3>>& velocity);
  const Simulation& simulation() const { return session_->simulation(); }
  bool settled() const { return settled_; }

 private:
  friend class PyArrays;
  void refuse_open_views(const char* what) const;
  std::uint64_t steps_for(std::optional<std::uint64_t> steps,
                          std::optional<double> revolutions) const;
  std::unique_ptr<RunSession> session_;
  bool settled_ = false;
  int open_views_ = 0;  ///< array contexts open: stepping is refused
};

/// `with sim.arrays() as a:` (the Python side wraps it): zero-copy, read-only views of the
/// particle arrays while open; any use after the block raises.
class PyArrays {
 public:
  explicit PyArrays(PySimulation& sim);
  void enter();
  void exit();
  pybind11::array get(const std::string& name, pybind11::handle self) const;
  void check(const char* name) const;

 private:
  template <class T>
  static pybind11::array view(const std::vector<T>& v, int columns, pybind11::handle owner);
  enum class State { fresh, open, closed };
  PySimulation& sim_;
  State state_ = State::fresh;
};

void bind_simulation(pybind11::module_& m);

}  // namespace drumlab::python
