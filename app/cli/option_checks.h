// Strict CLI11 validators for numbers whose plain conversions let bad text through: CLI11 reads "-1"
// into an unsigned option as its two's complement, saturates out-of-range integers, and NaN passes
// PositiveNumber (every comparison with NaN is false).
#pragma once

#include <CLI/CLI.hpp>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>

#include "core/math/argument_checks.h"

namespace penumbra::cli {

// A decimal integer in [0, max]: digits only (no sign, no exponent).
inline CLI::Validator unsignedInteger(uint64_t max = UINT64_MAX) {
  return CLI::Validator(
      [max](std::string& text) -> std::string {
        uint64_t v = 0;
        auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (text.empty() || end != text.data() + text.size() ||
            text.find_first_not_of("0123456789") != std::string::npos)
          return "expected a non-negative integer, got '" + text + "'";
        if (ec == std::errc::result_out_of_range || v > max)
          return "'" + text + "' is out of range (at most " + std::to_string(max) + ")";
        return {};
      },
      "UINT");
}

// --seed of every command: any 64-bit unsigned integer, nothing out of range clamped into it.
inline CLI::Option* addSeedOption(CLI::App& cmd, uint64_t& seed, const std::string& help) {
  return cmd.add_option("--seed", seed, help)->check(unsignedInteger())->type_name("UINT");
}
// The same where leaving it out means "the scene's seed".
inline CLI::Option* addSeedOption(CLI::App& cmd, std::optional<uint64_t>& seed, const std::string& help) {
  return cmd
      .add_option_function<std::string>(
          "--seed", [&seed](const std::string& text) { seed = std::stoull(text); }, help)
      ->check(unsignedInteger())
      ->type_name("UINT");
}

// A finite number > 0 (rejects nan, inf and anything that is not entirely a number).
inline CLI::Validator finitePositiveNumber() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size() || !isFinitePositive(v))
          return std::string(kExpectedFinitePositive) + ", got '" + text + "'";
        return {};
      },
      "POSITIVE");
}

}  // namespace penumbra::cli
