#include "lab/Fig11.h"

#include <cstdio>

namespace frugal::span {

namespace {

std::array<Fig11Channel, 4> printedChannels() {
    return {{
        {"z", 24, 0x010, 0x3FF, {{2, 0x010, false}, {3, 0x0A0, false}, {4, 0x12F, false}, {9, 0x3FF, false}}, {}, 0, 0},
        {"red", 16, 0, 7, {{2, 0, false}, {3, 2, true}, {4, 2, false}, {9, 7, false}}, {}, 0, 0},
        {"green", 16, 7, 0, {{2, 7, false}, {3, 6, false}, {4, 5, false}, {9, 0, false}}, {}, 0, 0},
        {"blue", 16, 3, 0, {{2, 3, false}, {3, 3, false}, {4, 2, false}, {9, 0, false}}, {}, 0, 0},
    }};
}

EngineConfig withEnds(Rounding ends, Midpoint midpoint, Rounding out, int endFracBits = 0,
                      int slopeFracBits = kSlopeFracBits) {
    EngineConfig c;
    c.endRounding = ends;
    c.midpoint = midpoint;
    c.outRounding = out;
    c.endFracBits = endFracBits;
    c.slopeFracBits = slopeFracBits;
    return c;
}

}  // namespace

std::vector<Fig11Scheme> fig11Schemes() {
    using R = Rounding;
    using M = Midpoint;
    std::vector<Fig11Scheme> s;
    s.push_back({"engine: ends rounded, exact tree, output rounded (the model)", false, R::Nearest, {}});
    s.push_back({"engine as above, A and B with 5 fraction bits", false, R::Nearest,
                 withEnds(R::Nearest, M::Exact, R::Nearest, 0, 5)});
    s.push_back({"engine as above, A and B with 4 fraction bits", false, R::Nearest,
                 withEnds(R::Nearest, M::Exact, R::Nearest, 0, 4)});
    s.push_back({"exact line, rounded", true, R::Nearest, {}});
    s.push_back({"exact line, truncated", true, R::Floor, {}});
    s.push_back({"engine: ends keep 16 fraction bits, exact tree, output rounded", false, R::Nearest,
                 withEnds(R::Nearest, M::Exact, R::Nearest, kSlopeFracBits)});
    s.push_back({"engine: ends keep 16 fraction bits, exact tree, output truncated", false, R::Nearest,
                 withEnds(R::Nearest, M::Exact, R::Floor, kSlopeFracBits)});
    s.push_back({"engine: ends rounded, exact tree, output truncated", false, R::Nearest,
                 withEnds(R::Nearest, M::Exact, R::Floor)});
    s.push_back({"engine: ends truncated, exact tree, output rounded", false, R::Nearest,
                 withEnds(R::Floor, M::Exact, R::Nearest)});
    s.push_back({"engine: ends truncated, exact tree, output truncated", false, R::Nearest,
                 withEnds(R::Floor, M::Exact, R::Floor)});
    s.push_back({"engine: ends rounded, each level truncated (PIPE add-and-shift)", false, R::Nearest,
                 withEnds(R::Nearest, M::TruncateEachLevel, R::Nearest)});
    s.push_back({"engine: ends truncated, each level truncated", false, R::Nearest,
                 withEnds(R::Floor, M::TruncateEachLevel, R::Floor)});
    s.push_back({"engine: ends rounded, each level rounded", false, R::Nearest,
                 withEnds(R::Nearest, M::RoundEachLevel, R::Nearest)});
    return s;
}

Fig11Result runFig11(const Fig11Scheme& scheme) {
    Fig11Result result;
    result.scheme = scheme;
    result.channels = printedChannels();
    constexpr int kPixels = kFig11Xr - kFig11Xl + 1;
    if (scheme.exactLine) {
        for (Fig11Channel& ch : result.channels)
            for (int i = 0; i < kPixels; ++i) {
                // f(x) = from + (to − from)·(x − Xl)/(Xr − Xl), rounded exactly on integers.
                const std::int64_t num = std::int64_t(ch.from) * (kPixels - 1) + std::int64_t(ch.to - ch.from) * i;
                ch.values[std::size_t(i)] =
                    scheme.lineRounding == Rounding::Nearest ? roundDiv(num, kPixels - 1) : floorDiv(num, kPixels - 1);
            }
    } else {
        // The paper's span command: A and the intercept B = f(0) (anchor column 0), engine 0.
        SpanCommand command{kFig11Xl, kFig11Xr, {}, {}, {}, {}};
        ChannelLine* lines[4] = {&command.z, &command.r, &command.g, &command.b};
        for (std::size_t c = 0; c < 4; ++c) {
            const Fig11Channel& ch = result.channels[c];
            const std::optional<ChannelLine> line = lineThrough(kFig11Xl, ch.from, kFig11Xr, ch.to, ch.width, 0,
                                                                result.overflow, scheme.config.slopeFracBits);
            if (line) *lines[c] = *line;
        }
        std::array<std::uint32_t, kEnginePixels> oldZ;
        oldZ.fill(0xFFFFFFu);  // a cleared 24-bit z-buffer: every pixel of the span is nearer
        const EngineOutput out = runEngine(0, command, oldZ, scheme.config);
        result.mask = out.mask;
        result.writeEnable = out.writeEnable;
        result.overflow |= out.overflow;
        // The values before the output clamp, so that a scheme that leaves the range shows it (−1).
        for (std::size_t c = 0; c < 4; ++c) {
            std::array<std::int64_t, kEnginePixels> values{};
            std::uint8_t ignored = 0;
            interpolateEngine(0, *lines[c], scheme.config, values, ignored);
            for (int i = 0; i < kPixels; ++i)
                result.channels[c].values[std::size_t(i)] = values[std::size_t(kFig11Xl + i)];
        }
    }
    for (Fig11Channel& ch : result.channels) {
        for (const Fig11Printed& p : ch.printed)
            if (ch.values[std::size_t(p.x - kFig11Xl)] != p.value)
                ++(p.doubtful ? ch.doubtfulMismatches : ch.mismatches);
        result.mismatches += ch.mismatches;
        result.doubtfulMismatches += ch.doubtfulMismatches;
    }
    return result;
}

std::string fig11Hex(const Fig11Channel& channel) {
    std::string text;
    for (std::int64_t v : channel.values) {
        char buf[24];
        if (v < 0)
            std::snprintf(buf, sizeof buf, "-%llX", static_cast<unsigned long long>(-v));
        else
            std::snprintf(buf, sizeof buf, channel.width == 24 ? "%03llX" : "%llX", static_cast<unsigned long long>(v));
        text += (text.empty() ? "" : " ") + std::string(buf);
    }
    return text;
}

}  // namespace frugal::span
