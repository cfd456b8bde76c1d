// A loaded, validated scene as the Python object rheodda.Scene.
#pragma once

#include <pybind11/pybind11.h>
#include <rheodda/scene/scene.hpp>

#include <string>

namespace rheodda::python {

struct Scene {
  scene::SceneDescription description;
  std::string text;  ///< the YAML text it was read from (echoed by run(), hashed in checkpoints)
};

/// The scene's unit labels as a dict: length, force, time, stress (scene_bindings.cpp).
pybind11::dict units_dict(const scene::Units& u);

}  // namespace rheodda::python
