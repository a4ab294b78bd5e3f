// Bit-level model of the shading engine of paper 001 (Bang, Bae, Kyung, "A Graphics Accelerator for
// Hidden Surface Removal and Color Shading", KAIST 1990; the model is described block by block in
// docs/span/README.md), one block per class or function so that each can be tested alone. Section
// and figure numbers are the paper's.
//
// Conventions
//  - Pixel columns are integers >= 0; a value belongs to the column (no half-pixel offsets here: the
//    caller evaluates its plane at whatever point it calls the column's sample).
//  - Engine i owns columns XL_i = 64·i .. XL_i + 63; XR_i = XL_i + 64 is the right end the R-multiplier
//    evaluates (III.1: "XR_i = XL_i + 64"); it is the next engine's first column, never written here.
//  - A span command covers columns X_l .. X_r, both inclusive (Fig. 11: (Xl, Xr) = (2, 9) is 8 pixels).
//  - Channels are unsigned integers of `width` bits: z 24 bits, R, G, B 16 bits each (III.2). Smaller
//    z is nearer: write-enable = mask AND (new z < old z) (II.1, III.3).
//
// Number formats (all explicit, see span/Fixed.h; nothing wraps, overflow is flagged):
//  - slope A:      signed, `width` integer bits, kSlopeFracBits (16) fraction bits. |A| < 2^width
//                  LSB per pixel: a channel may cross its whole range within one pixel, not more.
//  - anchor B:     f at the anchor column X0 (the paper's intercept B = f(0) when X0 = 0): signed,
//                  width + 16 integer bits (room for f(0) = f(X_l) - A·X_l at any column < 2^16),
//                  kSlopeFracBits fraction bits.
//  - endpoints:    f(XL_i), f(XR_i) from the multipliers, rounded to integers (EngineConfig): signed,
//                  width + 7 integer bits, so a legal span (values in range, |A| < 2^width) always fits
//                  64 columns beyond either end.
//  - interpolator: the endpoints with 6 more fraction bits (one per tree level; 2^6 = 64 pixels).
//  - outputs:      unsigned, `width` bits, rounded to nearest (half up) from the interpolator.
//
// The rounding order is what reproduces Fig. 11 (see span/Fig11.h): the two multipliers round
// f(XL), f(XR) to integers, the binary tree subdivides them exactly (III.2: the serial interpolator
// delays data instead of shifting right, so no level truncates), and each pixel's value is rounded to
// nearest as it leaves the tree. Truncating at the multipliers, at the tree levels or at the output
// each contradicts a printed value.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "span/Fixed.h"

namespace frugal::span {

constexpr int kEnginePixels = 64;   // III.1: each shading engine owns 64 pixels of a scanline
constexpr int kTreeLevels = 6;      // log2(64): levels of the midpoint-subdivision tree
constexpr int kSlopeFracBits = 16;  // fraction bits of A and B (Fig. 11 needs >= 5, see Fig11.h)
constexpr int kMaxWidth = 28;       // channel widths 1..28 keep every product inside int64
constexpr int kMaxColumn = 65535;   // columns 0..65535 (the paper's multiplier: 11 stages, 1024 columns)

// What overflowed, as bits: several may be set. A set bit means the value that left its format was
// clamped (outputs) or not computed (slope, anchor, endpoints), never wrapped.
enum OverflowBits : std::uint8_t {
    kOverflowNone = 0,
    kOverflowSlope = 1,     // A does not fit the slope format (|A| >= 2^width, or not finite)
    kOverflowAnchor = 2,    // B does not fit the anchor format
    kOverflowEndpoint = 4,  // f(XL) or f(XR) does not fit the endpoint format
    kOverflowOutput = 8,    // a pixel inside the span left [0, 2^width - 1] (clamped in the output)
};
// "slope, output" for the set bits; "none" for 0.
std::string describeOverflow(std::uint8_t bits);

inline Format slopeFormat(int width, int fracBits = kSlopeFracBits) { return {width, fracBits, true}; }
inline Format anchorFormat(int width, int fracBits = kSlopeFracBits) { return {width + 16, fracBits, true}; }
inline Format endpointFormat(int width, int fracBits = 0) { return {width + 7, fracBits, true}; }
inline Format outputFormat(int width) { return {width, 0, false}; }

// How the engine rounds (the defaults are the paper's engine as Fig. 11 shows it; the other settings
// exist to show which schemes Fig. 11 rules out).
enum class Midpoint : std::uint8_t {
    Exact,              // III.2: every level keeps its extra bit (the serial interpolator's delays)
    TruncateEachLevel,  // PIPE's add-and-shift-right: each level floors (a + b) / 2
    RoundEachLevel,     // each level rounds (a + b) / 2 half up
};
struct EngineConfig {
    int slopeFracBits = kSlopeFracBits;     // fraction bits of A and B
    int endFracBits = 0;                    // fraction bits the multipliers keep in f(XL), f(XR)
    Rounding endRounding = Rounding::Nearest;
    Midpoint midpoint = Midpoint::Exact;
    Rounding outRounding = Rounding::Nearest;
};

// One channel of a span command, f(X) = A·(X − X0) + B, A and B as raw fixed-point values with
// `fracBits` fraction bits (III.1: the scanline processor sends the slope A and the intercept B; the
// paper anchors at X0 = 0, so B = f(0); the rasterizer API anchors at the span's first column).
struct ChannelLine {
    std::int64_t slopeRaw = 0;
    std::int64_t anchorRaw = 0;
    int anchorX = 0;
    int width = 16;
    int fracBits = kSlopeFracBits;
};

// The scanline processor's side (III.1, Fig. 4): the line through (xl, fl) and (xr, fr), A and B
// rounded to nearest with `fracBits` fraction bits, anchored at `anchorX`. xl != xr unless fl == fr.
// Nothing, with the overflow bit in `overflow`, when A or B does not fit its format.
std::optional<ChannelLine> lineThrough(int xl, double fl, int xr, double fr, int width, int anchorX, std::uint8_t& overflow,
                                       int fracBits = kSlopeFracBits);
// The same from f(x0) and the slope as doubles.
std::optional<ChannelLine> lineFromSlope(int x0, double value, double slope, int width, std::uint8_t& overflow,
                                         int fracBits = kSlopeFracBits);

// III.2, Fig. 7 — the L- and R-multipliers: f(X) = A·(X − X0) + B, the exact product rounded to the
// endpoint format (config.endFracBits fraction bits, config.endRounding). Nothing (and
// kOverflowEndpoint) when it does not fit.
std::optional<std::int64_t> multiply(const ChannelLine& line, int x, const EngineConfig& config, std::uint8_t& overflow);
// Clock cycles of one serial multiplication (III.2: (11 + n)·T_c for an n-bit f(X)).
inline int multiplierCycles(int width) { return 11 + width; }

// III.2, Fig. 8 — the midpoint-subdivision (binary tree) interpolator for 2^levels + 1 nodes. Input:
// f(0) and f(2^levels) as raw values with `inFrac` fraction bits. Output: node k in out[k], with
// inFrac + levels fraction bits (Exact keeps the bit each halving makes; the other modes drop it at
// every level, so their values are multiples of 2^levels). Level 1 computes f(mid) = (f(0) + f(end)) / 2,
// level 2 the quarter points from those, and so on (the paper's 9-pixel example is levels = 3).
// out.size() must be 2^levels + 1.
void subdivide(std::int64_t left, std::int64_t right, int levels, Midpoint mode, std::span<std::int64_t> out);

// III.3 — the Edge Painting Tree: the mask of an engine's pixels inside the span, bit k for local
// pixel k (0..63), from the local ends ML, MR (inclusive; the control block clips X_l, X_r to the
// engine). A binary tree over the 64 pixels: a node whose range lies wholly inside [ML, MR] paints
// all its leaves, one wholly outside paints none, a node the edge cuts asks its two children.
// Empty when ML > MR.
std::uint64_t edgePaintingTree(int ml, int mr);

// III.3, Fig. 10 — the bit-serial z comparator of one pixel, fed LSB first. The flag starts at 0;
// a bit where the new z is 0 and the old 1 sets it, a bit where the new z is 1 and the old 0 clears
// it, equal bits keep it. After the MSB the flag is (new z < old z): the most significant differing
// bit decides, and it is the last one to touch the flag. (The paper's text says the flag keeps its
// value when NZ_i >= OZ_i; read literally that gives new = 2, old = 1 -> "less", see the test.)
class BitSerialComparator {
public:
    void clock(bool newBit, bool oldBit) {
        if (!newBit && oldBit) flag_ = true;
        else if (newBit && !oldBit) flag_ = false;
    }
    bool less() const { return flag_; }

private:
    bool flag_ = false;
};
// `width` clocks of the comparator, LSB first.
bool lessLsbFirst(std::uint32_t newZ, std::uint32_t oldZ, int width);

// III.1, Fig. 6 — one shading engine. A span command: columns xl..xr (inclusive), one line per channel.
struct SpanCommand {
    int xl = 0, xr = 0;
    ChannelLine z, r, g, b;
};

struct EngineOutput {
    std::array<std::uint32_t, kEnginePixels> z{}, r{}, g{}, b{};  // all 64 pixels, clamped to the channel's range
    std::uint64_t mask = 0;         // EPT: pixels inside [xl, xr]
    std::uint64_t zLess = 0;        // comparator: new z < old z
    std::uint64_t writeEnable = 0;  // mask AND zLess (the 'WE signal storage' register)
    std::uint8_t overflow = 0;      // OverflowBits, any channel; outputs count only inside the mask
};

// Engine `index` (XL = 64·index) on one span: the multipliers evaluate each channel at XL and XR, the
// tree interpolates the 64 pixels, the EPT masks, the comparator compares z with `oldZ`.
EngineOutput runEngine(int index, const SpanCommand& command, std::span<const std::uint32_t, kEnginePixels> oldZ,
                       const EngineConfig& config = {});

// One channel of one engine: the 64 interpolated values (before clamping, as signed integers) and
// the overflow bits of the multipliers; the building block of runEngine and of the span API.
// Returns false (no values) when an endpoint overflowed.
bool interpolateEngine(int index, const ChannelLine& line, const EngineConfig& config,
                       std::array<std::int64_t, kEnginePixels>& values, std::uint8_t& overflow);

}  // namespace frugal::span
