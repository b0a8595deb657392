#pragma once
// drumlab.Scene (py_scene.cpp).
#include <string>
#include <vector>

#include <pybind11/pybind11.h>
#include <toml++/toml.h>

#include "engine/scene/scene_config.hpp"

namespace drumlab::python {

class PyScene {
 public:
  static PyScene load(const std::string& path);
  pybind11::object get(const std::string& key) const;
  void set(const std::string& key, const pybind11::object& value);
  void save(const std::string& path) const;
  std::vector<std::string> keys() const;
  std::string text() const;
  const SceneConfig& config() const { return config_; }
  const std::string& source() const { return source_; }

 private:
  static pybind11::object to_python(const toml::node& node);
  void check();  ///< parse_scene of the text: InputError (ValueError) for a bad scene
  toml::table table_;
  std::string source_;
  SceneConfig config_;
};

void bind_scene(pybind11::module_& m);

}  // namespace drumlab::python
