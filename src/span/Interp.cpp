#include "span/Interp.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

namespace frugal::span {

namespace {

// Stores v clamped to [0, top]; flags the first column that needed it.
inline void store(std::int64_t v, std::int64_t top, int column, std::uint32_t& slot, FillResult& result) {
    if (v < 0 || v > top) {
        if (!(result.overflow & kOverflowOutput)) result.firstOverflowColumn = column;
        result.overflow |= kOverflowOutput;
        v = v < 0 ? 0 : top;
    }
    slot = std::uint32_t(v);
}

FillResult fillExact(const SpanInput& in, std::span<std::uint32_t> out) {
    FillResult result;
    const double top = double(outputFormat(in.width).maxRaw());
    for (int x = in.xBegin; x < in.xEnd; ++x) {
        const double v = std::floor(in.value + in.slope * double(x - in.xBegin) + 0.5);
        // Compared as a double first: an out-of-range double must not be converted to an integer.
        const std::int64_t clamped = !(v >= 0.0) ? -1 : v > top ? std::int64_t(top) + 1 : std::int64_t(v);
        store(clamped, std::int64_t(top), x, out[std::size_t(x - in.xBegin)], result);
    }
    return result;
}

FillResult fillEngineModel(const SpanInput& in, std::span<std::uint32_t> out, const EngineConfig& config) {
    FillResult result;
    std::uint8_t overflow = 0;
    const std::optional<ChannelLine> line = lineFromSlope(in.xBegin, in.value, in.slope, in.width, overflow, config.slopeFracBits);
    if (!line) {
        std::fill_n(out.begin(), in.xEnd - in.xBegin, 0u);
        result.overflow = overflow;
        return result;
    }
    const std::int64_t top = outputFormat(in.width).maxRaw();
    std::array<std::int64_t, kEnginePixels> values;
    for (int engine = in.xBegin / kEnginePixels; engine * kEnginePixels < in.xEnd; ++engine) {
        const int xl = engine * kEnginePixels;
        const int from = std::max(in.xBegin, xl), to = std::min(in.xEnd, xl + kEnginePixels);
        if (!interpolateEngine(engine, *line, config, values, overflow)) {
            std::fill_n(out.begin(), in.xEnd - in.xBegin, 0u);
            result.overflow = overflow;
            result.firstOverflowColumn = -1;
            return result;
        }
        for (int x = from; x < to; ++x)
            store(values[std::size_t(x - xl)], top, x, out[std::size_t(x - in.xBegin)], result);
    }
    result.overflow |= overflow;
    return result;
}

FillResult fillDda(const SpanInput& in, std::span<std::uint32_t> out, int accumulatorBits) {
    FillResult result;
    assert(accumulatorBits > in.width && accumulatorBits <= 62);
    const int f = accumulatorBits - in.width;
    // The register: unsigned, `width` integer bits, f fraction bits; the step: signed, same bits.
    const Format acc{in.width, f, false}, step{in.width, f, true};
    const std::optional<std::int64_t> start = toFixed(in.value, {in.width + 1, f, true}, Rounding::Nearest);
    const std::optional<std::int64_t> a = toFixed(in.slope, step, Rounding::Nearest);
    if (!start || !a) {
        std::fill_n(out.begin(), in.xEnd - in.xBegin, 0u);
        result.overflow = !a ? kOverflowSlope : kOverflowAnchor;
        return result;
    }
    const std::int64_t top = outputFormat(in.width).maxRaw();
    std::int64_t v = *start + (f > 0 ? std::int64_t(1) << (f - 1) : 0);
    for (int x = in.xBegin; x < in.xEnd; ++x) {
        // Outside the register's range the hardware would wrap; the model flags and clamps instead.
        store(acc.fits(v) ? (v >> f) : (v < 0 ? -1 : top + 1), top, x, out[std::size_t(x - in.xBegin)], result);
        v += *a;
    }
    return result;
}

}  // namespace

FillResult fillSpan(Interp mode, const SpanInput& input, std::span<std::uint32_t> out, const SpanOptions& options) {
    assert(input.xBegin >= 0 && input.xBegin <= input.xEnd && input.xEnd <= kMaxColumn + 1);
    assert(input.width >= 1 && input.width <= kMaxWidth);
    assert(out.size() >= std::size_t(input.xEnd - input.xBegin));
    switch (mode) {
    case Interp::Exact: return fillExact(input, out);
    case Interp::Span: return fillEngineModel(input, out, options.engine);
    case Interp::Dda: return fillDda(input, out, options.accumulatorBits);
    }
    return {};
}

}  // namespace frugal::span
