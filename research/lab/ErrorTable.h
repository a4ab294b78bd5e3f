// Error tables of the span interpolators (paper 001, III.2: midpoint subdivision "without the
// truncation error of add-and-shift"), and the model's speed beside the paper's 59,000 spans/s.
//
// Each row: `spans` random spans of `length` pixels at `width` bits, every pixel compared with the
// exact line rounded to nearest (computed on integers, not in double). A span runs from column X_l
// (uniform in 0..4095, so it straddles 64-column engines anywhere) to X_l + length − 1; its end values
// are uniform in [0, 2^width − 1], and one span in four goes from 0 to the top or back (the steepest
// a channel allows over that length). Deterministic for a seed.
#pragma once

#include <cstdint>
#include <vector>

#include "renderer/Research.h"

namespace frugal::span {

enum class Method : std::uint8_t {
    Span,            // the paper's engine (Interp::Span)
    SpanTruncating,  // the same tree truncating at each level, as PIPE's add-and-shift-right does
    Dda,             // Interp::Dda
    Exact,           // Interp::Exact (double evaluation)
};
const char* methodName(Method method);  // "span", "span_trunc", "dda", "exact"

// The longest span of a table: a span starts anywhere in columns 0..4095.
constexpr int kMaxTableLength = kMaxColumn + 1 - 4096;

struct ErrorTableSettings {
    std::vector<int> lengths{8, 64, 512, 8192};  // pixels, 2..kMaxTableLength
    std::vector<int> widths{16, 24};             // bits, 1..kMaxWidth
    int spans = 2000;                            // per (width, length, method)
    std::uint64_t seed = 1;
    int accumulatorBits = 32;  // Dda register; > every width
    std::vector<Method> methods{Method::Span, Method::SpanTruncating, Method::Dda, Method::Exact};
};

struct ErrorRow {
    int width = 0, length = 0;
    Method method = Method::Span;
    std::int64_t worstLsb = 0;  // max |model − exact| over every pixel of every span
    double meanLsb = 0.0;       // mean |model − exact| over the pixels
    int spans = 0;
    std::int64_t pixels = 0;
    int overflowSpans = 0;  // spans whose fill reported overflow (none expected: inputs are legal)
};

// Rows ordered by width, then length, then method (as in settings).
std::vector<ErrorRow> errorTable(const ErrorTableSettings& settings);

// The paper's figure: one span per 17 µs at 10 MHz.
constexpr double kPaperSpansPerSecond = 1.0 / 17e-6;

// Spans per second of fillSpan in `method`, four channels per span (z 24 bits, R, G, B 16 bits) of
// `length` pixels; timed for at least `minSeconds`. A measurement, never asserted.
double fillSpansPerSecond(Method method, int length, int accumulatorBits, double minSeconds, std::uint64_t seed);
// Spans per second of the whole engine model (runEngine: multipliers, tree, EPT, comparator, WE for
// z, R, G, B) on spans inside one engine, as the paper's engine processes them.
double engineSpansPerSecond(double minSeconds, std::uint64_t seed);

}  // namespace frugal::span
