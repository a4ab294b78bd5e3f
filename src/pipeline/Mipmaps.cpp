#include "pipeline/Mipmaps.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace frugal {

namespace {

// The sRGB curve (IEC 61966-2-1) both ways, in double.
double srgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

std::uint8_t toByte(double unit) { return std::uint8_t(std::clamp(std::floor(unit * 255.0 + 0.5), 0.0, 255.0)); }

// The texels of the level above that texel i of a level `to` wide covers, `from` wide, and their
// weights (the overlap of [i·from/to, (i+1)·from/to) with each texel, over its length).
struct Taps {
    int first = 0, count = 0;
    std::array<double, 3> weight{};
};

Taps tapsOf(int i, int from, int to) {
    Taps taps;
    if (from == to) {  // an axis already 1 wide
        taps.first = i;
        taps.count = 1;
        taps.weight[0] = 1.0;
        return taps;
    }
    // In units of 1/to of a source texel, the destination texel spans [i·from, (i + 1)·from).
    const long long begin = (long long)i * from, end = begin + from;
    taps.first = int(begin / to);
    for (int k = taps.first; (long long)k * to < end; ++k) {
        const long long lo = std::max(begin, (long long)k * to), hi = std::min(end, (long long)(k + 1) * to);
        taps.weight[std::size_t(taps.count++)] = double(hi - lo) / double(from);
    }
    return taps;
}

}  // namespace

int mipLevelCount(int width, int height) {
    int levels = 1;
    for (int size = std::max(width, height); size > 1; size /= 2) ++levels;
    return levels;
}

std::vector<MipLevel> mipLevels(const Texture& texture) {
    // Channels as values to average: the sRGB curve decoded for an sRGB texture's rgb.
    std::array<double, 256> decoded{}, plain{};
    for (int b = 0; b < 256; ++b) {
        plain[std::size_t(b)] = b / 255.0;
        decoded[std::size_t(b)] = texture.srgb ? srgbToLinear(b / 255.0) : b / 255.0;
    }
    // sRGB encoding and rounding in one search: the byte b whose encoded value is nearest is the
    // number of midpoints (b + 0.5) / 255, decoded to linear, at or below v.
    std::array<double, 255> midpoints{};
    for (int b = 0; b < 255; ++b) midpoints[std::size_t(b)] = srgbToLinear((b + 0.5) / 255.0);
    const auto encode = [&](double v, int channel) {
        if (!texture.srgb || channel == 3) return toByte(v);
        return std::uint8_t(std::upper_bound(midpoints.begin(), midpoints.end(), v) - midpoints.begin());
    };

    std::vector<MipLevel> levels;
    const int count = mipLevelCount(texture.width, texture.height);
    levels.reserve(std::size_t(count - 1));
    const std::uint8_t* above = texture.rgba.data();
    int aboveWidth = texture.width, aboveHeight = texture.height;
    for (int level = 1; level < count; ++level) {
        MipLevel out;
        out.width = std::max(1, aboveWidth / 2);
        out.height = std::max(1, aboveHeight / 2);
        out.rgba.resize(std::size_t(out.width) * std::size_t(out.height) * 4);
        std::vector<Taps> xTaps(std::size_t(out.width));
        for (int x = 0; x < out.width; ++x) xTaps[std::size_t(x)] = tapsOf(x, aboveWidth, out.width);
        std::vector<double> sums(std::size_t(out.width) * 4);
        for (int y = 0; y < out.height; ++y) {
            std::fill(sums.begin(), sums.end(), 0.0);
            const Taps yTaps = tapsOf(y, aboveHeight, out.height);
            for (int j = 0; j < yTaps.count; ++j) {
                const std::uint8_t* src = above + std::size_t(yTaps.first + j) * std::size_t(aboveWidth) * 4;
                for (int x = 0; x < out.width; ++x) {
                    const Taps& taps = xTaps[std::size_t(x)];
                    for (int c = 0; c < 4; ++c) {
                        const auto& table = c < 3 ? decoded : plain;
                        double v = 0.0;
                        for (int k = 0; k < taps.count; ++k)
                            v += taps.weight[std::size_t(k)] *
                                 table[src[std::size_t(taps.first + k) * 4 + std::size_t(c)]];
                        sums[std::size_t(x) * 4 + std::size_t(c)] += yTaps.weight[std::size_t(j)] * v;
                    }
                }
            }
            std::uint8_t* dst = out.rgba.data() + std::size_t(y) * std::size_t(out.width) * 4;
            for (int x = 0; x < out.width; ++x)
                for (int c = 0; c < 4; ++c)
                    dst[std::size_t(x) * 4 + std::size_t(c)] = encode(sums[std::size_t(x) * 4 + std::size_t(c)], c);
        }
        levels.push_back(std::move(out));
        above = levels.back().rgba.data();
        aboveWidth = levels.back().width;
        aboveHeight = levels.back().height;
    }
    return levels;
}

}  // namespace frugal
