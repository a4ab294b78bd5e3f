// Fixed-point vocabulary of the span engine model (paper 001: Bang, Bae, Kyung, "A Graphics
// Accelerator for Hidden Surface Removal and Color Shading", KAIST 1990; see span/Engine.h).
//
// A value is an integer `raw` read as raw / 2^fracBits. A Format names its integer bits and fraction
// bits explicitly, and whether it carries a two's-complement sign bit on top of them:
//   unsigned: raw in [0, 2^(intBits+fracBits) - 1]                     (intBits+fracBits bits)
//   signed:   raw in [-2^(intBits+fracBits), 2^(intBits+fracBits) - 1]  (1+intBits+fracBits bits)
// Nothing here wraps: a value that does not fit is reported (std::nullopt, or an Overflow flag), so
// a model that overflows says so instead of printing a plausible wrong number.
//
// Rounding: Floor is what dropping low bits of a two's-complement word does (an arithmetic shift,
// toward -inf); Nearest is round half up, floor(v + 1/2): the hardware's "add half an LSB, then drop
// the bits". Both are defined for negative values the same way (no round-toward-zero anywhere).
#pragma once

#include <cassert>
#include <cmath>
#include <cstdint>
#include <optional>

namespace frugal::span {

enum class Rounding : std::uint8_t { Floor, Nearest };

struct Format {
    int intBits = 0;   // integer bits (magnitude; the sign bit, if any, is extra)
    int fracBits = 0;  // fraction bits
    bool isSigned = false;

    int totalBits() const { return intBits + fracBits + (isSigned ? 1 : 0); }
    std::int64_t maxRaw() const { return (std::int64_t(1) << (intBits + fracBits)) - 1; }
    std::int64_t minRaw() const { return isSigned ? -(std::int64_t(1) << (intBits + fracBits)) : 0; }
    bool fits(std::int64_t raw) const { return raw >= minRaw() && raw <= maxRaw(); }
    double toDouble(std::int64_t raw) const { return std::ldexp(double(raw), -fracBits); }
};

// Formats are limited so that every product the model forms fits an int64 (see Engine.h).
constexpr int kMaxFormatBits = 62;

// raw >> drop with the given rounding (drop >= 0); exact two's-complement arithmetic, no overflow for
// |raw| < 2^62.
inline std::int64_t shiftRound(std::int64_t raw, int drop, Rounding rounding) {
    assert(drop >= 0 && drop < 62);
    if (drop == 0) return raw;
    if (rounding == Rounding::Nearest) raw += std::int64_t(1) << (drop - 1);
    return raw >> drop;  // arithmetic shift: floor (C++20 defines >> on negative values)
}

// `value` in `format`, rounded; nothing when it is not finite or does not fit.
inline std::optional<std::int64_t> toFixed(double value, Format format, Rounding rounding) {
    assert(format.intBits + format.fracBits <= kMaxFormatBits);
    if (!std::isfinite(value)) return std::nullopt;
    const double scaled = std::ldexp(value, format.fracBits);
    const double r = rounding == Rounding::Nearest ? std::floor(scaled + 0.5) : std::floor(scaled);
    // Compare as doubles first: converting an out-of-range double to int64 is undefined.
    if (r < double(format.minRaw()) || r > double(format.maxRaw())) return std::nullopt;
    return std::int64_t(r);
}

// floor(num / den) and round-half-up(num / den) for den > 0, exact on integers.
inline std::int64_t floorDiv(std::int64_t num, std::int64_t den) {
    assert(den > 0);
    std::int64_t q = num / den;
    if ((num % den != 0) && (num < 0)) --q;
    return q;
}
inline std::int64_t roundDiv(std::int64_t num, std::int64_t den) { return floorDiv(2 * num + den, 2 * den); }

}  // namespace frugal::span
