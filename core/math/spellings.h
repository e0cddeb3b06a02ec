// How a name is written in scene files and on the command line: the canonical spelling (what
// every writer outputs) followed by the aliases a reader also accepts. Compile-time data for the
// strategy and sampler tables.
#pragma once

#include <array>
#include <span>
#include <string>
#include <string_view>

namespace penumbra {

struct Spellings {
  std::array<std::string_view, 4> names{};  // canonical first; unused slots stay empty

  constexpr std::string_view canonical() const { return names[0]; }
  constexpr bool empty() const { return names[0].empty(); }
  constexpr bool accepts(std::string_view s) const {
    for (std::string_view n : names)
      if (!n.empty() && n == s) return true;
    return false;
  }
  // The used slots, for lookups that take a list of names.
  constexpr std::span<const std::string_view> list() const {
    size_t n = 0;
    while (n < names.size() && !names[n].empty()) ++n;
    return {names.data(), n};
  }
  // "a, b, c": every accepted spelling, for messages.
  std::string joined() const {
    std::string out;
    for (std::string_view n : list()) (out += out.empty() ? "" : ", ") += n;
    return out;
  }
};

}  // namespace penumbra
