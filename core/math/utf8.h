// UTF-8 checks for text that reaches users and other programs: scene files and --set values (which
// Python returns as str, and which error messages quote).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace penumbra {

// Offset of the first byte that does not begin a well-formed UTF-8 sequence (overlong forms,
// surrogates and code points above U+10FFFF are ill-formed), or std::string_view::npos.
size_t invalidUtf8Offset(std::string_view text);

// `text` with every byte of an ill-formed sequence written as \xNN and NUL as \x00: valid UTF-8
// without control NULs, for messages that quote user input.
std::string escapeInvalidUtf8(std::string_view text);

}  // namespace penumbra
