// The compiled part of the Python module `drumlab` (the package in app/python/drumlab wraps it):
// Scene, Simulation, the array context, and the readers of checkpoints and HDF5 series. The
// engine's InputError (a bad scene, key, value or file: the CLI's one line) is ValueError.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "app/python/src/py_scene.hpp"
#include "app/python/src/py_simulation.hpp"
#include "engine/contact/law_probe.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/io/h5_series.hpp"
#include "engine/io/paraview/frame_datasets.hpp"
#include "engine/io/paraview/xml_writer.hpp"

namespace py = pybind11;
using namespace drumlab;

namespace {

py::array_t<double> vectors(const std::vector<Vec3>& v) {
  py::array_t<double> a({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
  auto r = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < v.size(); ++i) {
    for (int k = 0; k < 3; ++k) r(static_cast<py::ssize_t>(i), k) = v[i][k];
  }
  return a;
}

template <class T>
py::array_t<T> values(const std::vector<T>& v) {
  py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

py::dict read_checkpoint_arrays(const std::string& path) {
  const Checkpoint c = read_checkpoint(path);
  const SimulationState& s = c.state;
  py::dict d;
  d["scene"] = c.scene_name;
  d["time"] = s.time;
  d["steps"] = s.steps;
  d["position"] = vectors(s.particles.position);
  d["velocity"] = vectors(s.particles.velocity);
  d["omega"] = vectors(s.particles.omega);
  d["radius"] = values(s.particles.radius);
  d["id"] = values(s.particles.id);
  d["size_class"] = values(s.particles.size_class);
  return d;
}

py::list read_series_frames(const std::string& path) {
  const SeriesInfo info = read_series_info(path);
  py::list frames;
  for (std::size_t k = 0; k < info.frames; ++k) {
    const SeriesFrame f = read_series_frame(path, k);
    py::dict d;
    d["time"] = f.time;
    d["step"] = f.step;
    d["position"] = vectors(f.position);
    d["velocity"] = vectors(f.velocity);
    d["omega"] = vectors(f.omega);
    d["radius"] = values(f.radius);
    d["id"] = values(f.id);
    d["size_class"] = values(f.size_class);
    if (f.has_bonds) {
      d["mass"] = values(f.mass);
      d["film"] = values(f.film);
      d["agglomerate_id"] = values(f.agglomerate_id);
      py::array_t<std::int64_t> pairs({static_cast<py::ssize_t>(f.bonds.size()), py::ssize_t{2}});
      auto r = pairs.mutable_unchecked<2>();
      for (std::size_t b = 0; b < f.bonds.size(); ++b) {
        r(static_cast<py::ssize_t>(b), 0) = f.id[f.bonds[b].i];
        r(static_cast<py::ssize_t>(b), 1) = f.id[f.bonds[b].j];
      }
      d["bond_pairs"] = pairs;
    }
    frames.append(d);
  }
  return frames;
}

}  // namespace

PYBIND11_MODULE(_drumlab, m) {
  m.doc() = "drumlab's engine from Python (the package `drumlab` wraps this module).";
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  python::bind_scene(m);
  python::bind_simulation(m);
  m.def("read_checkpoint", &read_checkpoint_arrays, py::arg("path"),
        "A checkpoint's particle arrays (copies) and its scene name, time and steps.");
  m.def("read_series", &read_series_frames, py::arg("path"),
        "The frames of an HDF5 time series (run --h5): a list of dicts of numpy arrays.");
  m.def(
      "law_curve",
      [](const python::PyScene& scene, int class_a, int class_b, bool wall, double overlap,
         double start_gap, double end_gap, std::size_t steps) {
        if (class_a < 0 || class_a > 255 || class_b < 0 || class_b > 255) {
          throw InputError("law_curve: class indices are 0..255");
        }
        LawProbeOptions o;
        o.class_a = static_cast<std::uint8_t>(class_a);
        o.class_b = static_cast<std::uint8_t>(class_b);
        o.wall = wall;
        o.overlap = overlap;
        o.start_gap = start_gap;
        o.end_gap = end_gap;
        o.steps = steps;
        const LawCurve c = probe_law(scene.config(), o);
        const auto n = static_cast<py::ssize_t>(c.samples.size());
        py::array_t<double> gap(n), force(n), volume(n);
        py::array_t<bool> retreat(n);
        for (py::ssize_t k = 0; k < n; ++k) {
          const LawSample& s = c.samples[static_cast<std::size_t>(k)];
          gap.mutable_at(k) = s.gap;
          force.mutable_at(k) = s.normal_force;
          volume.mutable_at(k) = s.bridge_volume;
          retreat.mutable_at(k) = s.retreat;
        }
        py::dict d;
        d["label"] = c.label;
        d["gap"] = gap;
        d["normal_force"] = force;
        d["bridge_volume"] = volume;
        d["retreat"] = retreat;
        d["rupture_gap"] = c.rupture_gap;
        d["predicted_rupture"] = c.predicted_rupture;
        return d;
      },
      py::arg("scene"), py::arg("class_a") = 0, py::arg("class_b") = 0, py::arg("wall") = false,
      py::arg("overlap") = -1.0, py::arg("start_gap") = -1.0, py::arg("end_gap") = -1.0,
      py::arg("steps") = 400,
      "`drumlab law`: the normal force of the scene's contact law between two particles of "
      "classes a and b (or a and the wall) on approach and retreat, read from the engine's own "
      "code path; a dict of numpy arrays (gap, normal_force, bridge_volume, retreat) and the "
      "rupture gap against the law's prediction.");
  m.def(
      "_write_vtu",
      [](const python::PySimulation& s, const std::string& path) {
        paraview::write_xml_file(paraview::particles(s.simulation()), path);
      },
      py::arg("sim"), py::arg("path"));
}
