// The per-scanline-span API the software rasterizer can call (one channel at a time): fill the
// integer values of a span's pixels by exact evaluation, by the paper-001 span engine model
// (span/Engine.h), or by a DDA. Allocation-free: the caller owns the output array.
//
// What it takes:
//  - columns xBegin .. xEnd - 1 (xEnd exclusive; 0 <= xBegin <= xEnd <= kMaxColumn + 1);
//  - `value`: the plane's value at column xBegin, in output LSBs (e.g. depth · (2^24 − 1));
//  - `slope`: d value / d column, LSBs per pixel;
//  - `width`: output bits, 1..28 (z 24, colour 16 in the paper).
// What it returns: out[k] = the value of column xBegin + k, for k < xEnd − xBegin (out must be at
// least that long), unsigned `width`-bit integers; and a FillResult with the overflow bits
// (span/Engine.h OverflowBits) and the first column whose value left [0, 2^width − 1]. Such a value
// is clamped into the range in `out`, never wrapped; when the slope or an endpoint cannot be
// represented (Span, Dda) the whole span is filled with 0 and flagged.
//
// The modes:
//  - Exact: round-half-up of value + slope·(x − xBegin) in double (the reference).
//  - Span:  the engine of paper 001: A and value rounded to 16 fraction bits, the L/R multipliers
//           evaluate f(XL_i) and f(XR_i) of every 64-column engine the span touches (XL_i = 64·i,
//           absolute columns) rounded to integers, the binary tree subdivides exactly, each pixel
//           rounds to nearest. Its error against Exact is at most 1 LSB (two halves of rounding and
//           the 2^-16 slope quantisation times < 2^17 columns, which stays below 1/2).
//  - Dda:   add-and-shift in an `accumulatorBits` register (default 32) holding `width` integer bits
//           and F = accumulatorBits − width fraction bits: acc = round(value·2^F) + 2^(F−1) (so the
//           shift rounds), step = round(slope·2^F), out = acc >> F, acc += step per pixel. Its error
//           grows with the span length by up to 2^-(F+1) LSB per pixel (the slope's rounding).
#pragma once

#include <cstdint>
#include <span>

#include <frugal/Settings.h>

#include "span/Engine.h"

namespace frugal::span {

using Interp = frugal::DepthInterp;  // frugal/Settings.h: its names are toString's

struct SpanInput {
    int xBegin = 0;
    int xEnd = 0;  // exclusive
    double value = 0.0;
    double slope = 0.0;
    int width = 16;
};

struct SpanOptions {
    int accumulatorBits = 32;  // Dda: register width, > width and <= 62
    EngineConfig engine{};     // Span: the engine's rounding (the defaults are the paper's engine)
};

struct FillResult {
    std::uint8_t overflow = kOverflowNone;
    int firstOverflowColumn = -1;  // first column clamped (kOverflowOutput), else -1
    bool ok() const { return overflow == kOverflowNone; }
};

FillResult fillSpan(Interp mode, const SpanInput& input, std::span<std::uint32_t> out, const SpanOptions& options = {});

}  // namespace frugal::span
