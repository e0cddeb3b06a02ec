// Reading an input file whole, refusing what is not a regular file (a directory, /dev/zero, a FIFO)
// and anything larger than a cap, before reading a byte: a mesh path pointing at /dev/zero must not
// read gigabytes before failing.
#pragma once

#include <cstdint>
#include <string>

namespace penumbra {

// Throws Error unless `path` is free of NUL bytes: the system would take it only up to the first one,
// i.e. another file. `what` names the file in the message ("scene file", "output image").
void checkNoNulInPath(const std::string& path, const std::string& what);

// Throws Error (checkNoNulInPath, then Error(path, 0, ...)) unless `path` names a regular file (after
// symlinks) of at most `maxBytes`; `what` names it in messages ("scene file", "mesh file").
void checkRegularFile(const std::string& path, uint64_t maxBytes, const std::string& what);

// checkRegularFile, then the whole file; reads at most maxBytes even if the file grows meanwhile.
std::string readRegularFile(const std::string& path, uint64_t maxBytes, const std::string& what);

}  // namespace penumbra
