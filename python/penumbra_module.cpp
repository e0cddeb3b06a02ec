// The `penumbra` Python module: scenes, progressive rendering into NumPy arrays, the sample warps
// with their pdfs and chi-square tests, the samplers' point sets, convergence runs and closed forms.
#include <climits>
#include <new>
#include <utility>
#include <vector>

#include "core/math/cancellation.h"
#include "core/math/error.h"
#include "core/math/utf8.h"
#include "core/render/memory_estimate.h"
#include "python/arguments.h"
#include "python/bindings.h"
#include "python/text.h"

namespace penumbra::python {

PyObject* gSceneError = nullptr;

void throwSceneError(const std::string& what, const std::string& file, int line) {
  py::object type = py::reinterpret_borrow<py::object>(gSceneError);
  py::object error = type(text(what));
  error.attr("file") = file.empty() ? py::none() : py::object(pathText(file));
  error.attr("line") = line > 0 ? py::object(py::int_(line)) : py::none();
  // The message without the "file:line: " prefix that what() carries.
  std::string prefix =
      file.empty() ? "" : (line > 0 ? file + ":" + std::to_string(line) + ": " : file + ": ");
  error.attr("message") = text(what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what);
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
  const std::string name = argument;
  auto a = py::array::ensure(array);
  if (!a) {
    PyErr_Clear();
    throw py::type_error(name + ": expected an H x W x 3 float array");
  }
  if (a.ndim() != 3 || a.shape(2) != 3 || a.shape(0) < 1 || a.shape(1) < 1 || a.shape(0) > INT_MAX ||
      a.shape(1) > INT_MAX)
    throw py::value_error(name + ": expected an H x W x 3 float array with H, W >= 1");
  checkAllocation(uint64_t(a.shape(0)) * uint64_t(a.shape(1)) * 12, name + ": a float32 copy");
  py::array_t<float, py::array::c_style | py::array::forcecast> f;
  try {
    f = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
  } catch (const py::error_already_set&) {
  }
  if (!f) {
    PyErr_Clear();
    throw py::type_error(name + ": expected an H x W x 3 float array, got dtype " +
                         py::str(a.dtype()).cast<std::string>());
  }
  Image image(int(f.shape(1)), int(f.shape(0)));
  std::copy(f.data(), f.data() + image.rgb.size(), image.rgb.begin());
  return image;
}

namespace {

// C++ exceptions as Python ones; messages decoded with replacement (core quotes user input).
void translate(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const py::error_already_set&) {
    throw;
  } catch (const py::value_error& e) {  // ours, which may quote input that is not UTF-8
    PyErr_SetObject(PyExc_ValueError, text(e.what()).ptr());
  } catch (const py::type_error& e) {
    PyErr_SetObject(PyExc_TypeError, text(e.what()).ptr());
  } catch (const py::builtin_exception&) {
    throw;
  } catch (const OutOfMemoryError& e) {
    PyErr_SetObject(PyExc_MemoryError, text(e.what()).ptr());
  } catch (const Error& e) {
    try {
      throwSceneError(e.what(), e.file(), e.line());
    } catch (py::error_already_set& set) {
      set.restore();
    }
  } catch (const Cancelled&) {  // only when a signal handler raised, which is already set
    if (!PyErr_Occurred()) PyErr_SetNone(PyExc_KeyboardInterrupt);
  } catch (const std::bad_alloc&) {
    PyErr_SetString(PyExc_MemoryError, "out of memory");
  } catch (const std::exception& e) {
    if (invalidUtf8Offset(e.what()) == std::string::npos) throw;  // pybind11's own translation
    PyErr_SetObject(PyExc_RuntimeError, text(e.what()).ptr());
  }
}

}  // namespace

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

  py::register_exception_translator(&translate);

  bindScene(m);
  bindRender(m);
  bindWarp(m);
  bindAnalysis(m);
}
