#include "lab/ErrorTable.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <chrono>
#include <cstdlib>
#include <random>

namespace frugal::span {

const char* methodName(Method method) {
    switch (method) {
        case Method::Span:
            return "span";
        case Method::SpanTruncating:
            return "span_trunc";
        case Method::Dda:
            return "dda";
        case Method::Exact:
            return "exact";
    }
    return "?";
}

namespace {

struct RandomSpan {
    int xl = 0;
    std::int64_t from = 0, to = 0;
};

RandomSpan randomSpan(std::mt19937_64& rng, int width, int index) {
    const std::int64_t top = (std::int64_t(1) << width) - 1;
    RandomSpan s;
    s.xl = int(rng() % 4096);
    if (index % 4 == 3) {  // the steepest ramp: the whole range over the span
        const bool up = (rng() & 1) != 0;
        s.from = up ? 0 : top;
        s.to = up ? top : 0;
    } else {
        s.from = std::int64_t(rng() % std::uint64_t(top + 1));
        s.to = std::int64_t(rng() % std::uint64_t(top + 1));
    }
    return s;
}

Interp interpOf(Method method) {
    switch (method) {
        case Method::Span:
        case Method::SpanTruncating:
            return Interp::Span;
        case Method::Dda:
            return Interp::Dda;
        case Method::Exact:
            return Interp::Exact;
    }
    return Interp::Exact;
}

SpanOptions optionsOf(Method method, int accumulatorBits) {
    SpanOptions options;
    options.accumulatorBits = accumulatorBits;
    if (method == Method::SpanTruncating) options.engine.midpoint = Midpoint::TruncateEachLevel;
    return options;
}

SpanInput inputOf(const RandomSpan& s, int length, int width) {
    return {s.xl, s.xl + length, double(s.from), double(s.to - s.from) / double(length - 1), width};
}

}  // namespace

std::vector<ErrorRow> errorTable(const ErrorTableSettings& settings) {
    std::vector<ErrorRow> rows;
    int longest = 0;
    for (int length : settings.lengths) longest = std::max(longest, length);
    std::vector<std::uint32_t> out(std::size_t(std::max(longest, 1)));
    for (int width : settings.widths)
        for (int length : settings.lengths) {
            assert(width >= 1 && width <= kMaxWidth && length >= 2 && length <= kMaxTableLength);
            for (Method method : settings.methods) {
                ErrorRow row;
                row.width = width;
                row.length = length;
                row.method = method;
                row.spans = settings.spans;
                // The same spans for every method of a (width, length).
                std::mt19937_64 rng(settings.seed * 0x9E3779B97F4A7C15ull + std::uint64_t(width) * 65537u +
                                    std::uint64_t(length));
                const SpanOptions options = optionsOf(method, settings.accumulatorBits);
                double sum = 0.0;
                for (int i = 0; i < settings.spans; ++i) {
                    const RandomSpan s = randomSpan(rng, width, i);
                    const FillResult result = fillSpan(interpOf(method), inputOf(s, length, width), out, options);
                    if (!result.ok()) ++row.overflowSpans;
                    const std::int64_t d = length - 1;
                    for (int k = 0; k < length; ++k) {
                        // The exact line at pixel k, rounded half up on integers.
                        const std::int64_t exact = roundDiv(s.from * d + (s.to - s.from) * k, d);
                        const std::int64_t error = std::llabs(std::int64_t(out[std::size_t(k)]) - exact);
                        row.worstLsb = std::max(row.worstLsb, error);
                        sum += double(error);
                    }
                    row.pixels += length;
                }
                row.meanLsb = row.pixels ? sum / double(row.pixels) : 0.0;
                rows.push_back(row);
            }
        }
    return rows;
}

namespace {

using Clock = std::chrono::steady_clock;

// Runs `batch` (which processes `perBatch` spans) until `minSeconds` have passed; spans per second.
template <class Batch>
double timeSpans(Batch&& batch, int perBatch, double minSeconds) {
    batch();  // warm-up
    std::int64_t spans = 0;
    const auto start = Clock::now();
    double seconds = 0.0;
    do {
        batch();
        spans += perBatch;
        seconds = std::chrono::duration<double>(Clock::now() - start).count();
    } while (seconds < minSeconds);
    return double(spans) / seconds;
}

}  // namespace

double fillSpansPerSecond(Method method, int length, int accumulatorBits, double minSeconds, std::uint64_t seed) {
    constexpr int kBatch = 256;
    std::mt19937_64 rng(seed);
    std::vector<std::array<SpanInput, 4>> inputs;
    for (int i = 0; i < kBatch; ++i) {
        std::array<SpanInput, 4> span;
        for (int c = 0; c < 4; ++c) {
            const int width = c == 0 ? 24 : 16;
            RandomSpan s = randomSpan(rng, width, i);
            if (c > 0) s.xl = span[0].xBegin;  // one span: the same columns for every channel
            span[std::size_t(c)] = inputOf(s, length, width);
        }
        inputs.push_back(span);
    }
    std::vector<std::uint32_t> out(static_cast<std::size_t>(length));
    const SpanOptions options = optionsOf(method, accumulatorBits);
    volatile std::uint32_t sink = 0;
    return timeSpans(
        [&] {
            for (const auto& span : inputs)
                for (const SpanInput& in : span) {
                    fillSpan(interpOf(method), in, out, options);
                    sink = sink + out[std::size_t(length - 1)];
                }
        },
        kBatch, minSeconds);
}

double engineSpansPerSecond(double minSeconds, std::uint64_t seed) {
    constexpr int kBatch = 256;
    std::mt19937_64 rng(seed);
    std::vector<SpanCommand> commands;
    for (int i = 0; i < kBatch; ++i) {
        SpanCommand c;
        c.xl = int(rng() % 56);
        c.xr = c.xl + 1 + int(rng() % 8);  // short spans inside engine 0, as the paper's 10×10 polygons
        std::uint8_t overflow = 0;
        ChannelLine* lines[4] = {&c.z, &c.r, &c.g, &c.b};
        for (int ch = 0; ch < 4; ++ch) {
            const int width = ch == 0 ? 24 : 16;
            const double top = double((std::int64_t(1) << width) - 1);
            const double from = double(rng() % std::uint64_t(top + 1)), to = double(rng() % std::uint64_t(top + 1));
            if (const std::optional<ChannelLine> line = lineThrough(c.xl, from, c.xr, to, width, 0, overflow))
                *lines[ch] = *line;
        }
        commands.push_back(c);
    }
    std::array<std::uint32_t, kEnginePixels> oldZ;
    for (std::uint32_t& z : oldZ) z = std::uint32_t(rng() & 0xFFFFFFu);
    volatile std::uint64_t sink = 0;
    return timeSpans(
        [&] {
            for (const SpanCommand& c : commands) sink = sink ^ runEngine(0, c, oldZ).writeEnable;
        },
        kBatch, minSeconds);
}

}  // namespace frugal::span
