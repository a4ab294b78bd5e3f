// Fig. 11 of paper 001 (section IV): engine (XL, XR) = (0, 64), one span (Xl, Xr) = (2, 9) with
// z 10H -> 3FFH, red 0 -> 7, green 7 -> 0, blue 3 -> 0. The paper prints (text of section IV; the
// figure itself is a waveform plot): z 010, 0A0, 12F, ..., 3FF; red 0, 2, 2, ..., 7; green 7, 6, 5,
// ..., 0; blue 3, 3, 2, ..., 0 — the values at X = 2, 3, 4 and 9.
//
// The exact line gives z(3) = 159.857 and z(4) = 303.714: rounding gives 160, 304 and truncation
// 159, 303, so no single rounding of the exact line prints both 0A0 and 12F. The scheme that prints
// every value (red's second value aside, below) is the engine of span/Engine.h:
//   A = 1007/7 and B = f(0) = 16 − 2A = −271.714 with >= 5 fraction bits (we use 16);
//   the multipliers round f(0) = −271.714 -> −272 and f(64) = 8935.143 -> 8935 (to nearest);
//   the tree subdivides exactly: f(x) = −272 + 9207·x/64, 6 fraction bits;
//   each pixel rounds to nearest: z(2..9) = 15.72, 159.58, 303.44, ... -> 010 0A0 12F 1BF 24F 2DF 36F 3FF.
// The same scheme gives blue 3 3 2 2 1 1 1 0 (ends 3.857 -> 4, −23.57 -> −24), green 7 .. 0, red 0 .. 7.
// Truncating anywhere — the multiplier outputs, each tree level (PIPE's add-and-shift), or the
// output — contradicts at least one printed value (fig11Schemes() lists them with their mismatches).
// Red's second value reads "2" in the text; with red 0 -> 7 over 7 pixels (slope exactly 1) every
// scheme gives 1 there, as the brief's "red 0 -> 7" does: we count it as doubtful, not as a mismatch.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "renderer/Research.h"

namespace frugal::span {

constexpr int kFig11Xl = 2, kFig11Xr = 9;

struct Fig11Printed {
    int x;
    int value;
    bool doubtful;  // red at X = 3: the text prints 2, a slope-1 ramp has 1 (an OCR/print slip)
};

struct Fig11Channel {
    const char* name;  // "z", "red", "green", "blue"
    int width;         // 24 or 16
    int from, to;      // f(Xl), f(Xr)
    std::vector<Fig11Printed> printed;
    std::array<std::int64_t, kFig11Xr - kFig11Xl + 1> values{};  // the scheme's values at X = 2..9
    int mismatches = 0;                                          // printed values (not doubtful) the scheme misses
    int doubtfulMismatches = 0;                                  // doubtful printed values it misses
};

// A way of computing the figure: the engine with some rounding (config), or the exact line (no
// engine) with one rounding.
struct Fig11Scheme {
    std::string name;
    bool exactLine = false;
    Rounding lineRounding = Rounding::Nearest;  // exactLine only
    EngineConfig config{};                      // the engine's
};

struct Fig11Result {
    Fig11Scheme scheme;
    std::array<Fig11Channel, 4> channels;     // z, red, green, blue
    std::uint64_t mask = 0, writeEnable = 0;  // engine schemes: EPT mask and WE (old z = all ones)
    std::uint8_t overflow = 0;
    int mismatches = 0, doubtfulMismatches = 0;  // over the channels
};

// The engine's scheme first (span/Engine.h defaults), then the natural alternatives it was chosen from.
std::vector<Fig11Scheme> fig11Schemes();
Fig11Result runFig11(const Fig11Scheme& scheme);
// "010 0A0 12F ..." (upper-case hex, 3 digits for z, 1 for colours as the figure prints them).
std::string fig11Hex(const Fig11Channel& channel);

}  // namespace frugal::span
