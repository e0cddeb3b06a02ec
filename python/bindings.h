// Shared pieces of the Python module: the scene object every binding file sees, the SceneError
// type, and the bind functions of each concept (scene, render, warp, analysis).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <string>

#include "core/image/image.h"
#include "core/scene/scene_builder.h"

namespace penumbra::python {

namespace py = pybind11;

// A loaded scene as Python holds it: the description (edited by Scene.set) and the built world.
// Calls that release the GIL work on a copy of `loaded` (shared pointers to the built world), so a
// set() from another thread never changes what they read.
struct PyScene {
  LoadedScene loaded;
};

// penumbra.SceneError, created at import (a ValueError subclass with .file, .line, .message).
extern PyObject* gSceneError;
// Raises SceneError for a penumbra::Error (file and line as attributes).
[[noreturn]] void throwSceneError(const std::string& what, const std::string& file, int line);

// An H x W x 3 float32 array that owns the image's pixels (moved, not copied).
py::array_t<float> imageToArray(Image&& image);
// The array (H x W x 3, any float dtype, H and W >= 1) as an Image; TypeError/ValueError naming
// `argument`, MemoryError when the copy does not fit.
Image arrayToImage(const py::handle& array, const char* argument);

void bindScene(py::module_& m);
void bindRender(py::module_& m);
void bindWarp(py::module_& m);
void bindAnalysis(py::module_& m);

}  // namespace penumbra::python
