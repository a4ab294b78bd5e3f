#include "span/Engine.h"

#include <cassert>
#include <cmath>

namespace frugal::span {

std::string describeOverflow(std::uint8_t bits) {
    if (bits == 0) return "none";
    std::string text;
    const auto add = [&text](const char* name) { text += text.empty() ? name : std::string(", ") + name; };
    if (bits & kOverflowSlope) add("slope");
    if (bits & kOverflowAnchor) add("anchor");
    if (bits & kOverflowEndpoint) add("endpoint");
    if (bits & kOverflowOutput) add("output");
    return text;
}

std::optional<ChannelLine> lineFromSlope(int x0, double value, double slope, int width, std::uint8_t& overflow, int fracBits) {
    assert(width >= 1 && width <= kMaxWidth && x0 >= 0 && x0 <= kMaxColumn);
    assert(fracBits >= 0 && fracBits <= kSlopeFracBits);
    const std::optional<std::int64_t> a = toFixed(slope, slopeFormat(width, fracBits), Rounding::Nearest);
    const std::optional<std::int64_t> b = toFixed(value, anchorFormat(width, fracBits), Rounding::Nearest);
    if (!a) overflow |= kOverflowSlope;
    if (!b) overflow |= kOverflowAnchor;
    if (!a || !b) return std::nullopt;
    return ChannelLine{*a, *b, x0, width, fracBits};
}

std::optional<ChannelLine> lineThrough(int xl, double fl, int xr, double fr, int width, int anchorX, std::uint8_t& overflow,
                                       int fracBits) {
    assert(xl != xr || fl == fr);
    const double slope = xl == xr ? 0.0 : (fr - fl) / double(xr - xl);
    // B = f(X0) from the exact line (not from the rounded A), then rounded once.
    return lineFromSlope(anchorX, fl + slope * double(anchorX - xl), slope, width, overflow, fracBits);
}

std::optional<std::int64_t> multiply(const ChannelLine& line, int x, const EngineConfig& config, std::uint8_t& overflow) {
    assert(x >= 0 && x <= kMaxColumn + kEnginePixels && config.endFracBits <= line.fracBits);
    // |A| < 2^(28+16), |X − X0| < 2^17, |B| < 2^(28+16+16): the sum stays below 2^62.
    const std::int64_t exact = line.slopeRaw * std::int64_t(x - line.anchorX) + line.anchorRaw;
    const std::int64_t value = shiftRound(exact, line.fracBits - config.endFracBits, config.endRounding);
    if (!endpointFormat(line.width, config.endFracBits).fits(value)) {
        overflow |= kOverflowEndpoint;
        return std::nullopt;
    }
    return value;
}

void subdivide(std::int64_t left, std::int64_t right, int levels, Midpoint mode, std::span<std::int64_t> out) {
    assert(levels >= 0 && levels <= 16);
    const std::size_t n = std::size_t(1) << levels;
    assert(out.size() == n + 1);
    if (mode == Midpoint::Exact) {
        // The ends get `levels` more fraction bits; each halving then leaves an exact result (at level
        // l both operands are multiples of 2^(levels - l + 1)), which is what delaying the serial
        // data instead of shifting it achieves in the paper's interpolator.
        out[0] = left * std::int64_t(n);
        out[n] = right * std::int64_t(n);
    } else {
        out[0] = left;
        out[n] = right;
    }
    for (std::size_t step = n; step > 1; step /= 2) {  // one tree level per step: all its nodes at once
        const std::size_t half = step / 2;
        for (std::size_t a = 0; a < n; a += step) {
            const std::int64_t sum = out[a] + out[a + step];
            switch (mode) {
            case Midpoint::Exact:
                assert(sum % 2 == 0);
                out[a + half] = sum / 2;
                break;
            case Midpoint::TruncateEachLevel: out[a + half] = shiftRound(sum, 1, Rounding::Floor); break;
            case Midpoint::RoundEachLevel: out[a + half] = shiftRound(sum, 1, Rounding::Nearest); break;
            }
        }
    }
    if (mode != Midpoint::Exact)
        for (std::int64_t& v : out) v *= std::int64_t(n);  // the same fraction bits as Exact
}

namespace {

// Node [lo, lo + size) of the tree: paint, skip, or ask the children.
std::uint64_t paint(int lo, int size, int ml, int mr) {
    const int hi = lo + size - 1;
    if (hi < ml || lo > mr) return 0;
    if (lo >= ml && hi <= mr) return (size == 64 ? ~std::uint64_t(0) : ((std::uint64_t(1) << size) - 1)) << lo;
    return paint(lo, size / 2, ml, mr) | paint(lo + size / 2, size / 2, ml, mr);
}

}  // namespace

std::uint64_t edgePaintingTree(int ml, int mr) {
    if (ml > mr || mr < 0 || ml >= kEnginePixels) return 0;
    return paint(0, kEnginePixels, ml, mr);
}

bool lessLsbFirst(std::uint32_t newZ, std::uint32_t oldZ, int width) {
    assert(width >= 1 && width <= 32);
    BitSerialComparator comparator;
    for (int bit = 0; bit < width; ++bit) comparator.clock((newZ >> bit) & 1u, (oldZ >> bit) & 1u);
    return comparator.less();
}

bool interpolateEngine(int index, const ChannelLine& line, const EngineConfig& config,
                       std::array<std::int64_t, kEnginePixels>& values, std::uint8_t& overflow) {
    const int xl = kEnginePixels * index;
    const std::optional<std::int64_t> left = multiply(line, xl, config, overflow);
    const std::optional<std::int64_t> right = multiply(line, xl + kEnginePixels, config, overflow);
    if (!left || !right) return false;
    std::array<std::int64_t, kEnginePixels + 1> tree;
    subdivide(*left, *right, kTreeLevels, config.midpoint, tree);
    const int drop = config.endFracBits + kTreeLevels;
    for (int k = 0; k < kEnginePixels; ++k) values[std::size_t(k)] = shiftRound(tree[std::size_t(k)], drop, config.outRounding);
    return true;
}

namespace {

// A channel's 64 outputs, clamped; kOverflowOutput when a pixel inside `mask` left the range.
void channel(int index, const ChannelLine& line, const EngineConfig& config, std::uint64_t mask,
             std::array<std::uint32_t, kEnginePixels>& out, std::uint8_t& overflow) {
    std::array<std::int64_t, kEnginePixels> values{};
    if (!interpolateEngine(index, line, config, values, overflow)) return;  // outputs stay 0
    const std::int64_t top = outputFormat(line.width).maxRaw();
    for (int k = 0; k < kEnginePixels; ++k) {
        const std::int64_t v = values[std::size_t(k)];
        if ((v < 0 || v > top) && ((mask >> k) & 1u)) overflow |= kOverflowOutput;
        out[std::size_t(k)] = std::uint32_t(v < 0 ? 0 : v > top ? top : v);
    }
}

}  // namespace

EngineOutput runEngine(int index, const SpanCommand& command, std::span<const std::uint32_t, kEnginePixels> oldZ,
                       const EngineConfig& config) {
    assert(index >= 0 && index * kEnginePixels <= kMaxColumn);
    EngineOutput out;
    const int xl = kEnginePixels * index;
    // The control block clips the span to the engine: ML, MR in local pixels.
    out.mask = edgePaintingTree(command.xl - xl, command.xr - xl);
    // z first (its comparison needs the mask at the same time), then the colours (III.1).
    channel(index, command.z, config, out.mask, out.z, out.overflow);
    for (int k = 0; k < kEnginePixels; ++k)
        if (lessLsbFirst(out.z[std::size_t(k)], oldZ[std::size_t(k)], command.z.width)) out.zLess |= std::uint64_t(1) << k;
    out.writeEnable = out.mask & out.zLess;
    channel(index, command.r, config, out.mask, out.r, out.overflow);
    channel(index, command.g, config, out.mask, out.g, out.overflow);
    channel(index, command.b, config, out.mask, out.b, out.overflow);
    return out;
}

}  // namespace frugal::span
