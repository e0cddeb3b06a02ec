// The `penumbra` Python module: scenes, progressive rendering into NumPy arrays, the sample warps
// with their pdfs and chi-square tests, the samplers' point sets, convergence runs and closed forms.
#include <utility>
#include <vector>

#include "core/math/error.h"
#include "python/bindings.h"

namespace penumbra::python {

PyObject* gSceneError = nullptr;

void throwSceneError(const std::string& what, const std::string& file, int line) {
  py::object type = py::reinterpret_borrow<py::object>(gSceneError);
  py::object error = type(what);
  error.attr("file") = file.empty() ? py::none() : py::object(py::str(file));
  error.attr("line") = line > 0 ? py::object(py::int_(line)) : py::none();
  // The message without the "file:line: " prefix that what() carries.
  std::string prefix =
      file.empty() ? "" : (line > 0 ? file + ":" + std::to_string(line) + ": " : file + ": ");
  error.attr("message") = what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what;
  PyErr_SetObject(gSceneError, error.ptr());
  throw py::error_already_set();
}

py::array_t<float> imageToArray(Image&& image) {
  auto* pixels = new std::vector<float>(std::move(image.rgb));
  py::capsule owner(pixels, [](void* p) { delete static_cast<std::vector<float>*>(p); });
  const py::ssize_t h = image.height, w = image.width;
  return py::array_t<float>(
      {h, w, py::ssize_t(3)},
      {w * 3 * py::ssize_t(sizeof(float)), 3 * py::ssize_t(sizeof(float)), py::ssize_t(sizeof(float))},
      pixels->data(), owner);
}

Image arrayToImage(const py::handle& array, const char* argument) {
  auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(array);
  if (!a || a.ndim() != 3 || a.shape(2) != 3)
    throw py::value_error(std::string(argument) + ": expected an H x W x 3 float array");
  Image image(int(a.shape(1)), int(a.shape(0)));
  std::copy(a.data(), a.data() + image.rgb.size(), image.rgb.begin());
  return image;
}

}  // namespace penumbra::python

PYBIND11_MODULE(penumbra, m) {
  using namespace penumbra::python;
  m.doc() =
      "Penumbra from Python: load and edit scenes, render them into NumPy arrays, evaluate the sample "
      "warps and their pdfs, run chi-square tests and convergence measurements, and check renders "
      "against closed forms.";

  py::dict attributes;
  attributes["__doc__"] =
      "A scene that could not be loaded or built. A ValueError whose .file and .line (None when "
      "unknown) say where, and whose .message says what was expected.";
  gSceneError = PyErr_NewException("penumbra.SceneError", PyExc_ValueError, attributes.ptr());
  m.add_object("SceneError", py::handle(gSceneError));

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const penumbra::Error& e) {
      try {
        throwSceneError(e.what(), e.file(), e.line());
      } catch (py::error_already_set& set) {
        set.restore();
      }
    }
  });

  bindScene(m);
  bindRender(m);
  bindWarp(m);
  bindAnalysis(m);
}
