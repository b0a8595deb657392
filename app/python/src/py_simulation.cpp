// drumlab.Simulation: a RunSession (engine/session/run_session.hpp) driven from Python: the same
// fill, settling and steps as `drumlab run`, so the same bits. The GIL is released while the
// engine steps; between chunks of steps the signal handlers run (Ctrl-C stops the run cleanly
// between two steps) and the callback, if any, sees the simulation.
#include "app/python/src/py_simulation.hpp"

#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "engine/analysis/agglomerates.hpp"
#include "engine/analysis/drum_observables.hpp"
#include "engine/analysis/flow_regime.hpp"
#include "engine/contact/bond.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/threads.hpp"

namespace drumlab::python {
namespace py = pybind11;

PySimulation::PySimulation(const PyScene& scene, const std::string& method, int threads,
                           double dt_factor) {
  if (threads < 0) throw InputError("threads: must be >= 0 (0: the OpenMP default)");
  if (threads > 0) set_thread_count(threads);
  SessionOptions o;
  o.scene_file = scene.source();
  o.method = method;
  o.dt_factor = dt_factor;
  o.steps = 0;  // the run's length is run()'s
  py::gil_scoped_release release;
  session_ = std::make_unique<RunSession>(scene.config(), o);
}

void PySimulation::refuse_open_views(const char* what) const {
  if (open_views_ > 0) {
    throw std::runtime_error(fmt::format(
        "{}: the particle arrays are open (leave the `with sim.arrays()` block first: stepping "
        "moves and re-orders them)",
        what));
  }
}

/// Steps in chunks (each <= the scene's diagnostics_every), the GIL released; between chunks the
/// signal handlers run: a KeyboardInterrupt stops the phase there and is raised after it.
template <class Phase>
std::uint64_t stepped(Phase&& phase) {
  bool interrupted = false;
  std::uint64_t done = 0;
  {
    py::gil_scoped_release release;
    done = phase([&](std::uint64_t, std::uint64_t) {
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) {
        interrupted = true;
        return false;
      }
      return true;
    });
  }
  if (interrupted) throw py::error_already_set();
  return done;
}

void PySimulation::settle() {
  refuse_open_views("settle");
  if (settled_) throw std::runtime_error("settle: the bed has settled already");
  stepped([&](const SessionProgress& p) {
    session_->settle(p);
    return std::uint64_t{0};
  });
  settled_ = true;
}

std::uint64_t PySimulation::steps_for(std::optional<std::uint64_t> steps,
                                      std::optional<double> revolutions) const {
  if (steps && revolutions) throw InputError("run: give steps or revolutions, not both");
  if (steps) return *steps;
  const Simulation& sim = session_->simulation();
  if (revolutions) {
    if (!(*revolutions >= 0.0) || sim.drum_omega() == 0.0) {
      throw InputError("run: revolutions must be >= 0, in a turning drum");
    }
    return static_cast<std::uint64_t>(std::llround(*revolutions * 2.0 * std::numbers::pi /
                                                   std::abs(sim.drum_omega()) / sim.dt()));
  }
  SessionOptions o = session_->options();
  o.steps.reset();
  return session_plan(session_->scene(), o, sim.dt(), true).turn_steps;
}

std::uint64_t PySimulation::run(std::optional<std::uint64_t> steps,
                                std::optional<double> revolutions, const py::object& callback,
                                std::uint64_t every) {
  refuse_open_views("run");
  if (!settled_) settle();  // as `drumlab run`: the bed settles with the drum at rest first
  const std::uint64_t n = steps_for(steps, revolutions);
  if (!callback.is_none() && every == 0) throw InputError("run: every must be > 0");
  const std::uint64_t chunk = callback.is_none() ? n : every;
  std::uint64_t done = 0;
  while (done < n) {
    const std::uint64_t k = std::min(chunk, n - done);
    const std::uint64_t did =
        stepped([&](const SessionProgress& p) { return session_->advance(k, p); });
    done += did;
    if (!callback.is_none()) {
      const py::object go = callback(py::cast(this, py::return_value_policy::reference));
      if (!go.is_none() && !go.cast<bool>()) break;  // the callback asked to stop
      refuse_open_views("run (after the callback)");
    }
  }
  return done;
}

py::dict PySimulation::observables() const {
  const DrumObservables o = measure_drum(session_->simulation());
  py::dict d;
  d["angle_fit_deg"] =
      o.surface_found ? o.angle_of_repose_deg : std::numeric_limits<double>::quiet_NaN();
  d["angle_com_deg"] = o.com_angle_deg;
  d["flowing_layer"] = o.flowing_layer_thickness;
  d["bed_depth"] = o.bed_depth;
  d["surface_curvature"] = o.surface_curvature;
  d["relative_speed"] = o.relative_speed;
  d["airborne_fraction"] = o.airborne_fraction;
  d["upper_fraction"] = o.upper_fraction;
  d["com_offset"] = o.com_offset;
  d["wall_speed"] = o.wall_speed;
  d["field"] = o.field;
  d["mean_kinetic_energy"] = o.mean_kinetic_energy;
  return d;
}

py::dict PySimulation::agglomerates(const std::string& criterion, double age,
                                    double resolution) const {
  const Simulation& sim = session_->simulation();
  GranuleCriterion c;
  const auto method = parse_granule_method(criterion);
  if (!method) {
    throw InputError(
        fmt::format("criterion: '{}' is not one of {}", criterion, granule_method_choices()));
  }
  c.method = *method;
  c.age = age;
  c.resolution = resolution;
  std::vector<Bond> bonds;
  const AgglomerateFrame f =
      find_agglomerates(agglomerate_input(sim, bonds), granule_options(sim.scene().drum.omega, c));
  py::dict d;
  d["criterion"] = f.stats.criterion;
  d["count"] = f.stats.count;
  d["mean_size"] = f.stats.mean_size;
  d["largest"] = f.stats.largest;
  d["d10"] = f.stats.d10;
  d["d50"] = f.stats.d50;
  d["d90"] = f.stats.d90;
  d["bonds"] = f.stats.bonds;
  py::array_t<std::uint32_t> label(static_cast<py::ssize_t>(f.label.size()));
  std::copy(f.label.begin(), f.label.end(), label.mutable_data());
  d["label"] = label;
  py::list sizes;
  for (const Agglomerate& a : f.agglomerates) sizes.append(a.primaries);
  d["sizes"] = sizes;
  return d;
}

py::dict PySimulation::contacts() const {
  const Simulation& sim = session_->simulation();
  std::vector<ContactForce> forces;
  sim.contact_forces(forces);
  std::vector<Bond> bonds;
  sim.bonds(bonds);
  const auto n = static_cast<py::ssize_t>(forces.size());
  py::array_t<std::int64_t> pairs({n, py::ssize_t{2}});
  py::array_t<double> force({n, py::ssize_t{3}});
  auto pr = pairs.mutable_unchecked<2>();
  auto fr = force.mutable_unchecked<2>();
  const Particles& p = sim.particles();
  for (py::ssize_t k = 0; k < n; ++k) {
    const ContactForce& c = forces[static_cast<std::size_t>(k)];
    pr(k, 0) = p.id[c.i];
    pr(k, 1) = p.id[c.j];
    for (int a = 0; a < 3; ++a) fr(k, a) = c.force[a];
  }
  const auto m = static_cast<py::ssize_t>(bonds.size());
  py::array_t<std::int64_t> bond_pairs({m, py::ssize_t{2}});
  py::array_t<double> volume(m), age(m);
  auto br = bond_pairs.mutable_unchecked<2>();
  for (py::ssize_t k = 0; k < m; ++k) {
    const Bond& b = bonds[static_cast<std::size_t>(k)];
    br(k, 0) = p.id[b.i];
    br(k, 1) = p.id[b.j];
    volume.mutable_at(k) = b.volume;
    age.mutable_at(k) = b.age;
  }
  py::dict d;
  d["pairs"] = pairs;
  d["force"] = force;
  d["bond_pairs"] = bond_pairs;
  d["bridge_volume"] = volume;
  d["bond_age"] = age;
  return d;
}

void PySimulation::checkpoint(const std::string& path) const {
  const Simulation& sim = session_->simulation();
  write_checkpoint(path, sim.state(), sim.scene().name);
}

void PySimulation::set_velocity(const std::vector<std::int64_t>& ids,
                                const std::vector<std::array<double, 3>>& velocity) {
  refuse_open_views("set_velocity");
  if (ids.size() != velocity.size()) {
    throw InputError("set_velocity: as many velocities as ids");
  }
  Particles& p = session_->simulation().local_particles();  // between steps
  std::vector<std::size_t> slot(p.size(), p.size());
  for (std::size_t i = 0; i < p.size(); ++i) slot[p.id[i]] = i;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    if (ids[k] < 0 || static_cast<std::size_t>(ids[k]) >= p.size()) {
      throw InputError(fmt::format("set_velocity: no particle with id {}", ids[k]));
    }
    const Vec3 v(velocity[k][0], velocity[k][1], velocity[k][2]);
    if (!v.allFinite()) throw InputError(fmt::format("set_velocity: id {}: not finite", ids[k]));
  }
  for (std::size_t k = 0; k < ids.size(); ++k) {
    p.velocity[slot[static_cast<std::size_t>(ids[k])]] =
        Vec3(velocity[k][0], velocity[k][1], velocity[k][2]);
  }
}

PyArrays::PyArrays(PySimulation& sim) : sim_(sim) {}

void PyArrays::enter() {
  if (state_ != State::fresh) throw std::runtime_error("arrays: a context is entered once");
  state_ = State::open;
  ++sim_.open_views_;
}

void PyArrays::exit() {
  if (state_ == State::open) --sim_.open_views_;
  state_ = State::closed;
}

void PyArrays::check(const char* name) const {
  if (state_ != State::open) {
    throw std::runtime_error(fmt::format(
        "arrays.{}: used outside its `with sim.arrays()` block (the memory may have moved)", name));
  }
}

template <class T>
py::array PyArrays::view(const std::vector<T>& v, int columns, py::handle owner) {
  const auto n = static_cast<py::ssize_t>(v.size());
  py::array a;
  if constexpr (std::is_same_v<T, Vec3>) {
    a = py::array(py::dtype::of<double>(), {n, py::ssize_t{3}},
                  {static_cast<py::ssize_t>(sizeof(Vec3)), py::ssize_t{sizeof(double)}},
                  v.empty() ? nullptr : v.front().data(), owner);
  } else {
    (void)columns;
    a = py::array(py::dtype::of<T>(), {n}, {static_cast<py::ssize_t>(sizeof(T))}, v.data(), owner);
  }
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

py::array PyArrays::get(const std::string& name, py::handle self) const {
  check(name.c_str());
  const Particles& p = sim_.session_->simulation().particles();
  if (name == "position") return view(p.position, 3, self);
  if (name == "velocity") return view(p.velocity, 3, self);
  if (name == "omega") return view(p.omega, 3, self);
  if (name == "force") return view(p.force, 3, self);
  if (name == "radius") return view(p.radius, 1, self);
  if (name == "mass") return view(p.mass, 1, self);
  if (name == "id") return view(p.id, 1, self);
  if (name == "size_class") return view(p.size_class, 1, self);
  if (name == "film") {
    const std::vector<double>* film = p.find_array(kLiquidFilmArray);
    if (film == nullptr) throw py::attribute_error("arrays.film: the scene has no liquid films");
    return view(*film, 1, self);
  }
  throw py::attribute_error(fmt::format("arrays: no array '{}'", name));
}

void bind_simulation(py::module_& m) {
  py::class_<PySimulation>(m, "_Simulation")
      .def(py::init<const PyScene&, const std::string&, int, double>(), py::arg("scene"),
           py::arg("method") = "", py::arg("threads") = 0, py::arg("dt_factor") = 0.0)
      .def("settle", &PySimulation::settle)
      .def("run", &PySimulation::run, py::arg("steps") = py::none(),
           py::arg("revolutions") = py::none(), py::arg("callback") = py::none(),
           py::arg("every") = 100)
      .def("observables", &PySimulation::observables)
      .def("agglomerates", &PySimulation::agglomerates, py::arg("criterion") = "age",
           py::arg("age") = -1.0, py::arg("resolution") = 1.0)
      .def("contacts", &PySimulation::contacts)
      .def("checkpoint", &PySimulation::checkpoint, py::arg("path"))
      .def("set_velocity", &PySimulation::set_velocity, py::arg("ids"), py::arg("velocity"))
      .def("diagnostics",
           [](const PySimulation& s) {
             const Diagnostics d = s.simulation().diagnostics();
             py::dict out;
             out["kinetic_energy"] = d.kinetic_energy;
             out["rotational_energy"] = d.rotational_energy;
             out["potential_energy"] = d.potential_energy;
             out["elastic_energy"] = d.elastic_energy;
             out["max_overlap_ratio"] = d.max_overlap_ratio;
             out["contacts"] = d.contacts;
             out["wall_contacts"] = d.wall_contacts;
             out["bridges"] = d.bridges;
             out["liquid_volume"] = d.liquid_volume;
             return out;
           })
      .def_property_readonly("time", [](const PySimulation& s) { return s.simulation().time(); })
      .def_property_readonly("dt", [](const PySimulation& s) { return s.simulation().dt(); })
      .def_property_readonly("steps", [](const PySimulation& s) { return s.simulation().steps(); })
      .def_property_readonly("revolutions",
                             [](const PySimulation& s) {
                               return s.simulation().drum_angle() / (2.0 * std::numbers::pi);
                             })
      .def_property_readonly(
          "n", [](const PySimulation& s) { return s.simulation().particles().size(); })
      .def_property_readonly(
          "method", [](const PySimulation& s) { return s.simulation().scene().search_method; })
      .def_property_readonly("settled", &PySimulation::settled)
      .def(
          "_arrays", [](PySimulation& s) { return std::make_unique<PyArrays>(s); },
          py::keep_alive<0, 1>());
  py::class_<PyArrays>(m, "_Arrays")
      .def("_enter", &PyArrays::enter)
      .def("_exit", &PyArrays::exit)
      .def("_get", [](py::object self, const std::string& name) {
        return self.cast<const PyArrays&>().get(name, self);
      });
}

}  // namespace drumlab::python
