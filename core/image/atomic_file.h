// Atomic file replacement: write everything to a temporary file in the target's directory, flush and
// fsync it, then rename() it onto the target. Readers (the viewer, scripts polling an output file) see
// either the old file or the complete new one, never a partial write; on any failure the temporary is
// removed, the old file is untouched, and an Error naming the path and strerror is thrown.
#pragma once

#include <cstddef>
#include <cstdio>
#include <functional>
#include <string>

namespace penumbra {

// Unique temp name next to `path`: path + ".tmp-<pid>-<counter>".
std::string atomicTempPath(const std::string& path);

// Checks, without touching an existing file, that `path` can be written atomically: it has no NUL byte,
// its directory
// exists and a file can be created in it (a probe temporary is created and removed), and an existing
// `path` is a regular file that is not read-only (it is refused, as cp refuses without -f, rather
// than replaced). Throws Error naming the path and the reason. Commands call it before long work.
void checkOutputPath(const std::string& path);

// Removes temporaries of `path` (path + ".tmp-<pid>-<n>") left by processes that no longer exist,
// e.g. killed during a write. Those of live processes are left alone. Returns how many it removed.
int removeStaleTemporaries(const std::string& path);

// Checks `path` (checkOutputPath), removes its stale temporaries, then calls `write(tempPath)`, which must
// create and fully write the file at tempPath (by any means, e.g. a third-party library that only takes a
// filename) and throw on failure. Then fsyncs the temp file and renames it onto `path`. If `write` throws,
// the temp file is removed and the exception rethrown.
void writeFileAtomically(const std::string& path,
                         const std::function<void(const std::string& tempPath)>& write);

// Convenience: atomically replace `path` with the given bytes.
void writeBytesAtomically(const std::string& path, const void* data, std::size_t size);

// Convenience for stdio writers: `write(FILE*)` writes into an open temp file; checks ferror/fflush.
void writeStdioAtomically(const std::string& path, const std::function<void(std::FILE*)>& write);

}  // namespace penumbra
