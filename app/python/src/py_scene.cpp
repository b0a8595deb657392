// drumlab.Scene: a scene's TOML, read and written by dotted key, checked by the engine's loader
// (parse_scene) after every change: a bad key or value raises ValueError with the loader's line,
// the line the CLI prints after "drumlab: error: ".
#include "app/python/src/py_scene.hpp"

#include <fstream>
#include <iterator>
#include <sstream>

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "engine/io/atomic_file.hpp"
#include "engine/scene/scene_keys.hpp"
#include "engine/scene/scene_writer.hpp"

namespace drumlab::python {
namespace py = pybind11;

PyScene PyScene::load(const std::string& path) {
  PyScene s;
  s.source_ = path;
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("{}: cannot read the scene file", path));
  const std::string original((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
  // Checked as the file is first, so that an error names the file's own line (as the CLI's).
  s.config_ = parse_scene(original, path);
  s.table_ = toml::parse(original, path);
  // A packing file named relative to the scene stays found wherever the scene is saved.
  if (auto* file = s.table_["fill"]["file"].as_string()) {
    const std::filesystem::path csv = file->get();
    if (csv.is_relative()) {
      *file = std::filesystem::absolute(std::filesystem::path(path).parent_path() / csv).string();
    }
  }
  return s;
}

std::string PyScene::text() const {
  std::ostringstream out;
  out << table_ << '\n';
  return with_shortest_floats(out.str());
}

void PyScene::check() {
  config_ = parse_scene(text(), source_);
}

py::object PyScene::get(const std::string& key) const {
  const toml::node* node = find_scene_key(table_, key);
  if (node == nullptr) throw py::key_error(fmt::format("{}: no key '{}'", source_, key));
  return to_python(*node);
}

py::object PyScene::to_python(const toml::node& node) {
  if (const auto* v = node.as_floating_point()) return py::float_(v->get());
  if (const auto* v = node.as_integer()) return py::int_(v->get());
  if (const auto* v = node.as_boolean()) return py::bool_(v->get());
  if (const auto* v = node.as_string()) return py::str(v->get());
  if (const auto* a = node.as_array()) {
    py::list out;
    for (const toml::node& e : *a) out.append(to_python(e));
    return out;
  }
  py::dict out;
  for (const auto& [k, v] : *node.as_table()) out[py::str(std::string(k.str()))] = to_python(v);
  return out;
}

void PyScene::set(const std::string& key, const py::object& value) {
  const toml::table before = table_;
  const std::string context = fmt::format("{}: {}", source_, key);
  try {
    if (py::isinstance<py::bool_>(value)) {
      set_scene_key(table_, key, value.cast<bool>() ? "true" : "false", context);
    } else if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value) ||
               py::isinstance<py::str>(value)) {
      set_scene_key(table_, key, py::str(value).cast<std::string>(), context);
    } else if (py::isinstance<py::sequence>(value)) {  // a vector: gravity = [0, -9.81, 0]
      toml::array a;
      for (const py::handle e : value.cast<py::sequence>()) a.push_back(e.cast<double>());
      const auto dot = key.rfind('.');
      toml::table* table = &table_;
      if (dot != std::string::npos) {
        toml::node* parent = find_scene_key(table_, key.substr(0, dot));
        if (parent == nullptr || !parent->is_table()) {
          throw InputError(
              fmt::format("{}: '{}' is not a table in the scene", context, key.substr(0, dot)));
        }
        table = parent->as_table();
      }
      table->insert_or_assign(dot == std::string::npos ? key : key.substr(dot + 1), a);
    } else {
      throw InputError(
          fmt::format("{}: a number, a string, true/false or a list of numbers", context));
    }
    check();
  } catch (...) {
    table_ = before;  // the scene stays as it was
    throw;
  }
}

void PyScene::save(const std::string& path) const {
  write_file_atomically(path, [&](std::ostream& out) { out << text(); });
}

std::vector<std::string> PyScene::keys() const {
  std::vector<std::string> out;
  const auto walk = [&](const auto& self, const toml::table& t, const std::string& prefix) -> void {
    for (const auto& [k, v] : t) {
      const std::string name = prefix + std::string(k.str());
      if (v.is_table()) {
        self(self, *v.as_table(), name + ".");
      } else {
        out.push_back(name);
      }
    }
  };
  walk(walk, table_, "");
  return out;
}

void bind_scene(py::module_& m) {
  py::class_<PyScene>(m, "Scene", R"(A scene (TOML), read and written by dotted key.

Scene.load(path) reads and checks it as `drumlab run` does; scene["liquid.surface_tension"] =
0.05 sets a key (typed as the existing value; tables created where missing) and checks the whole
scene again: a bad key or value raises ValueError with the line the CLI prints, and the scene
keeps its old value.)")
      .def_static("load", &PyScene::load, py::arg("path"), "Reads and checks a scene file.")
      .def("__getitem__", &PyScene::get, py::arg("key"))
      .def("__setitem__", &PyScene::set, py::arg("key"), py::arg("value"))
      .def("get", &PyScene::get, py::arg("key"), "The value at a dotted key (KeyError if none).")
      .def("set", &PyScene::set, py::arg("key"), py::arg("value"), "Sets a dotted key.")
      .def("keys", &PyScene::keys, "Every dotted key of the scene, in file order.")
      .def("save", &PyScene::save, py::arg("path"), "Writes the scene (TOML), atomically.")
      .def("text", &PyScene::text, "The scene as TOML text.")
      .def_property_readonly("name", [](const PyScene& s) { return s.config().name; })
      .def_property_readonly("source", &PyScene::source)
      .def("__repr__", [](const PyScene& s) {
        return fmt::format("<drumlab.Scene '{}' from {}>", s.config().name, s.source());
      });
}

}  // namespace drumlab::python
