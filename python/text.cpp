#include "python/text.h"

#include "core/math/utf8.h"

namespace penumbra::python {

py::str text(const std::string& s) {
  PyObject* o = PyUnicode_DecodeUTF8(s.data(), py::ssize_t(s.size()), "replace");
  if (!o) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(o);
}

py::list textList(const std::vector<std::string>& strings) {
  py::list out;
  for (const std::string& s : strings) out.append(text(s));
  return out;
}

py::str pathText(const std::string& path) {
  PyObject* o = PyUnicode_DecodeFSDefaultAndSize(path.data(), py::ssize_t(path.size()));
  if (!o) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(o);
}

std::string pathArgument(const py::handle& path, const char* argument) {
  PyObject* fspath = PyOS_FSPath(path.ptr());  // str or bytes, from os.PathLike too
  if (!fspath) {
    PyErr_Clear();
    throw py::type_error(std::string(argument) + ": expected a str, bytes or os.PathLike path, got " +
                         py::str(py::type::handle_of(path).attr("__name__")).cast<std::string>());
  }
  py::object p = py::reinterpret_steal<py::object>(fspath);
  if (PyUnicode_Check(p.ptr())) {
    PyObject* encoded = PyUnicode_EncodeFSDefault(p.ptr());  // surrogate escapes back to their bytes
    if (!encoded) throw py::error_already_set();
    p = py::reinterpret_steal<py::object>(encoded);
  }
  std::string bytes(PyBytes_AS_STRING(p.ptr()), size_t(PyBytes_GET_SIZE(p.ptr())));
  if (bytes.empty()) throw py::value_error(std::string(argument) + ": expected a path, got an empty one");
  checkNoNul(bytes, argument);
  return bytes;
}

std::string textArgument(const py::handle& s, const std::string& argument) {
  if (!PyUnicode_Check(s.ptr()))
    throw py::type_error(argument + ": expected a str, got " +
                         py::str(py::type::handle_of(s).attr("__name__")).cast<std::string>());
  Py_ssize_t size = 0;
  const char* utf8 = PyUnicode_AsUTF8AndSize(s.ptr(), &size);
  if (!utf8) {
    PyErr_Clear();
    throw py::value_error(argument + ": not valid text (a lone surrogate cannot be UTF-8)");
  }
  std::string out(utf8, size_t(size));
  checkNoNul(out, argument);
  return out;
}

void checkNoNul(const std::string& s, const std::string& argument) {
  if (s.find('\0') != std::string::npos) throw py::value_error(argument + ": contains a NUL character");
}

std::string quoted(const std::string& userText) {
  return escapeInvalidUtf8(userText);
}

}  // namespace penumbra::python
