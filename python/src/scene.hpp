// A loaded, validated scene as the Python object rheodda.Scene.
#pragma once

#include <rheodda/scene/scene.hpp>

#include <string>

namespace rheodda::python {

struct Scene {
  scene::SceneDescription description;
  std::string text;  ///< the YAML text it was read from (echoed by run(), hashed in checkpoints)
};

}  // namespace rheodda::python
