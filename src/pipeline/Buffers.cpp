#include "pipeline/Buffers.h"

#include <cmath>

#include "pipeline/ColorEncoding.h"

namespace frugal {

std::uint8_t displayLevel(float x) { return ColorEncoding::encode(x); }

std::uint8_t alphaLevel(float a) {
    if (!(a > 0.0f)) return 0;
    if (a >= 1.0f) return 255;
    return std::uint8_t(std::nearbyint(a * 255.0f));
}

void encodeLinear(Buffers& out) {
    const std::size_t values = out.linear.size();
    out.rgba.resize(values);
    for (std::size_t i = 0; i < values; i += 4) {
        for (std::size_t c = 0; c < 3; ++c) out.rgba[i + c] = displayLevel(out.linear[i + c]);
        out.rgba[i + 3] = alphaLevel(out.linear[i + 3]);
    }
}

}  // namespace frugal
