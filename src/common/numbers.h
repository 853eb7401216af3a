// Numbers as users type them, in decimal only: every number that enters the workbench (flags, the window's
// `--set` and scripts, environment variables) is read by these, so "0x10", "1e999", "nan", " 5" or "5 "
// are refused the same way everywhere.
#pragma once
#include <cstdint>
#include <optional>
#include <string_view>

namespace wb {

// A finite decimal number: an optional sign, digits with an optional fraction ("1", "-0.5", ".5", "2."), an
// optional exponent ("1e-3"). Nothing else: no hexadecimal, no inf or nan, no spaces. nullopt otherwise (also
// when it overflows to infinity).
std::optional<double> parseDecimal(std::string_view text);
// A non-negative decimal integer: digits only ("0", "42"), at most UINT64_MAX. nullopt otherwise.
std::optional<uint64_t> parseDecimalUnsigned(std::string_view text);

}  // namespace wb
