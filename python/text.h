// Strings across the boundary. Every string the module returns is text: UTF-8 from core decoded with
// replacement (U+FFFD) where it is not, paths as os.fsdecode() spells them. Every string argument is
// checked for NUL characters, which C++ would silently cut at.
#pragma once

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

namespace penumbra::python {

namespace py = pybind11;

// UTF-8 text as str; ill-formed bytes become U+FFFD.
py::str text(const std::string& s);
// A list of str, each as text().
py::list textList(const std::vector<std::string>& strings);
// A file system path as str (os.fsdecode: undecodable bytes as surrogate escapes, as os.listdir).
py::str pathText(const std::string& path);

// A path argument: str, bytes or os.PathLike, as the bytes the file system sees (os.fsencode).
// TypeError for anything else, ValueError for an empty path or one with a NUL character.
std::string pathArgument(const py::handle& path, const char* argument);
// A str argument as UTF-8: TypeError for another type, ValueError for a lone surrogate (not text)
// or a NUL character.
std::string textArgument(const py::handle& s, const std::string& argument);
// Raises ValueError "<argument>: contains a NUL character" when `s` has one.
void checkNoNul(const std::string& s, const std::string& argument);
// A message quoting user input, made valid UTF-8 (ill-formed bytes as \xNN), for pybind11's
// exceptions (which need UTF-8).
std::string quoted(const std::string& userText);

}  // namespace penumbra::python
