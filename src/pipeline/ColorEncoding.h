// The display encoding of a linear colour channel as an 8-bit value, one function for the software
// reference's 8-bit targets and for the colour image a linear frame is read back with
// (frugal::displayLevel, frugal/Image.h).
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

namespace frugal {

// rgb^(1/2.2) as an 8-bit value, for a linear colour channel: the power in double rounded to float,
// then clamped to [0, 1] and rounded to the nearest of 255 steps as llvmpipe converts float colour to
// unorm8 (software/Shading.h, floatToUnorm8). Exact for every float (NaN and v ≤ 0 give 0):
// thresholds[b] is the least float whose byte is b or more, found once by bisection over float
// bits, and a table indexed by a value's upper 16 bits gives the byte at the start of its bucket,
// which one comparison corrects (no bucket spans more than one threshold).
class ColorEncoding {
public:
    static std::uint8_t encode(float v) {
        static const ColorEncoding encoding;
        return encoding.byte(v);
    }
    // The same, computed directly (slow): what encode() must equal, and what the tests compare.
    static std::uint8_t exact(float v) {
        if (!(v > 0.0f)) return 0;
        const float p = float(std::pow(double(v), double(1.0f / 2.2f)));
        if (p >= 1.0f) return 255;
        return std::uint8_t(std::nearbyint(p * 255.0f));
    }

private:
    ColorEncoding() {
        thresholds_[0] = 0.0f;
        for (int b = 1; b < 256; ++b) {
            std::uint32_t lo = 0, hi = 0x3F800000u;  // exact(+0) = 0 < b <= exact(1.0f) = 255
            while (hi - lo > 1) {
                const std::uint32_t mid = lo + (hi - lo) / 2;
                (exact(std::bit_cast<float>(mid)) >= b ? hi : lo) = mid;
            }
            thresholds_[std::size_t(b)] = std::bit_cast<float>(hi);
        }
        for (std::uint32_t bucket = 0; bucket < buckets_.size(); ++bucket)
            buckets_[bucket] = exact(std::bit_cast<float>(bucket << 16));
    }
    std::uint8_t byte(float v) const {
        if (!(v > 0.0f)) return 0;
        if (v >= 1.0f) return 255;
        std::uint8_t b = buckets_[std::bit_cast<std::uint32_t>(v) >> 16];
        if (b < 255 && v >= thresholds_[std::size_t(b) + 1]) ++b;
        return b;
    }
    std::array<float, 256> thresholds_{};
    std::array<std::uint8_t, 0x3F80 + 1> buckets_{};  // the positive floats below 1.0, by upper bits
};

}  // namespace frugal
