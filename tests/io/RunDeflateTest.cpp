// The run-length deflate (io/RunDeflate.h) decoded by zlib, a strict, independent decoder (it
// checks the Adler-32 and refuses incomplete or oversubscribed codes): every byte back, for every
// pixel size, across block boundaries, runs longer than a match, data with no runs (stored
// blocks) and the empty stream; and PNGs at every level decoded to the pixels they were made of.
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <zlib.h>

#include <frugal/Files.h>
#include <frugal/Renderer.h>

#include "io/ImageIO.h"
#include "io/RunDeflate.h"

namespace frugal {
namespace {

std::vector<std::uint8_t> compressed(const std::vector<std::uint8_t>& data, std::size_t step) {
    std::vector<std::uint8_t> out(runDeflateBound(data.size()));
    out.resize(runDeflateZlib(data, step, out.data()));
    return out;
}

// zlib's inflate of the stream; fails the test when zlib refuses it or it does not end there.
std::vector<std::uint8_t> inflated(const std::vector<std::uint8_t>& stream, std::size_t size) {
    std::vector<std::uint8_t> out(size + 1);
    uLongf got = uLongf(out.size());
    const int z = uncompress(out.data(), &got, stream.data(), uLong(stream.size()));
    EXPECT_EQ(z, Z_OK) << zError(z);
    out.resize(got);
    return out;
}

void expectRoundTrip(const std::vector<std::uint8_t>& data, std::size_t step) {
    const std::vector<std::uint8_t> stream = compressed(data, step);
    EXPECT_LE(stream.size(), runDeflateBound(data.size()));
    EXPECT_EQ(inflated(stream, data.size()), data) << "step " << step << ", " << data.size() << " bytes";
}

TEST(RunDeflateTest, EveryByteComesBackForEveryPixelSize) {
    std::mt19937 random(7);
    for (const std::size_t step : {1, 2, 3, 4, 6, 8}) {
        // Runs of every length around the match limits (3, 258, 259, 516), pixels that repeat,
        // and noise between them; 1.5 MB, so several blocks of 256 KiB.
        std::vector<std::uint8_t> data;
        while (data.size() < (std::size_t(3) << 19)) {
            const std::size_t run = std::size_t(random() % 600);
            const std::uint8_t value = std::uint8_t(random() % 4);
            data.insert(data.end(), run, value);
            for (int k = int(random() % 40); k > 0; --k) data.push_back(std::uint8_t(random()));
            std::vector<std::uint8_t> pixel(step);
            for (std::uint8_t& b : pixel) b = std::uint8_t(random());
            for (int k = int(random() % 80); k > 0; --k) data.insert(data.end(), pixel.begin(), pixel.end());
        }
        expectRoundTrip(data, step);
    }
}

TEST(RunDeflateTest, EdgesDecodeToo) {
    expectRoundTrip({}, 4);
    expectRoundTrip({42}, 4);
    expectRoundTrip({1, 2, 3}, 1);
    expectRoundTrip(std::vector<std::uint8_t>(259, 0), 1);                   // one byte, then a run of 258
    expectRoundTrip(std::vector<std::uint8_t>(std::size_t(1) << 20, 0), 4);  // runs across block ends
    std::vector<std::uint8_t> noise(300000);
    std::mt19937 random(3);
    for (std::uint8_t& b : noise) b = std::uint8_t(random());
    const std::vector<std::uint8_t> stream = compressed(noise, 4);
    EXPECT_LT(stream.size(), noise.size() + noise.size() / 1000 + 64) << "noise is stored, not inflated";
    EXPECT_EQ(inflated(stream, noise.size()), noise);
}

TEST(RunDeflateTest, RunsCompress) {
    // A frame of background with a few different rows: most of it is runs.
    std::vector<std::uint8_t> data(std::size_t(1920) * 4 * 64, 0);
    for (std::size_t i = 0; i < data.size(); i += 997) data[i] = std::uint8_t(i);
    EXPECT_LT(compressed(data, 4).size(), data.size() / 20);
}

Frame testFrame(int w, int h) {
    Frame frame;
    frame.color = {w, h, {}};
    frame.depth = {w, h, {}, DepthFormat::D24, 0.1f, 100.0f, true};
    frame.ids = {w, h, {}};
    std::mt19937 random(11);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            // Flat regions, a gradient and noise: what renders are made of.
            const bool inside = (x - w / 2) * (x - w / 2) + (y - h / 2) * (y - h / 2) < w * h / 8;
            const std::uint8_t noise = std::uint8_t(random() % 3);
            frame.color.rgba.insert(frame.color.rgba.end(),
                                    {std::uint8_t(inside ? x + noise : 30), std::uint8_t(inside ? y : 33),
                                     std::uint8_t(inside ? 200 : 38), 255});
            frame.depth.values.push_back(inside ? std::uint32_t(x * 1000 + y * 3 + noise) : kDepthMax);
            frame.ids.ids.push_back(inside ? std::uint32_t(1 + x / 7 + (y / 5) * 1000) : 0u);
        }
    return frame;
}

TEST(RunDeflateTest, PngsAtEveryLevelDecodeToTheirPixels) {
    const Frame frame = testFrame(67, 41);  // odd sizes: rows that are not a multiple of anything
    const auto decoded = [](const Result<Bytes>& png) {
        EXPECT_TRUE(png) << (png ? "" : png.error().message);
        Result<DecodedImage> image = decodePng(*png, "test");
        EXPECT_TRUE(image) << (image ? "" : image.error().message);
        return *image;
    };
    const DecodedImage color = decoded(encodeColorPng(frame.color, PngOptions::atLevel(6)));
    const DecodedImage depth = decoded(encodeDepthPng(frame.depth, PngOptions::atLevel(6)));
    const DecodedImage ids = decoded(encodeIdPng(frame.ids, PngOptions::atLevel(6)));
    for (int level = kAutoPngLevel; level <= kMaxPngLevel; ++level) {
        EXPECT_EQ(decoded(encodeColorPng(frame.color, PngOptions::atLevel(level))).pixels8, color.pixels8) << level;
        EXPECT_EQ(decoded(encodeDepthPng(frame.depth, PngOptions::atLevel(level))).pixels16, depth.pixels16) << level;
        EXPECT_EQ(decoded(encodeIdPng(frame.ids, PngOptions::atLevel(level))).pixels8, ids.pixels8) << level;
        for (const PngFilter filter : {PngFilter::None, PngFilter::Sub, PngFilter::Up, PngFilter::Paeth}) {
            PngOptions options = PngOptions::atLevel(level);
            options.filter = filter;
            EXPECT_EQ(decoded(encodeColorPng(frame.color, options)).pixels8, color.pixels8) << level;
            EXPECT_EQ(decoded(encodeDepthPng(frame.depth, options)).pixels16, depth.pixels16) << level;
        }
    }
    // Top row first, as the files hold it: the frame's last row (bottom-up) is the image's first.
    EXPECT_EQ(color.pixels8[0], frame.color.rgba[std::size_t(40) * 67 * 4]);
}

TEST(RunDeflateTest, LevelsOutOfRangeAreRefused) {
    const Frame frame = testFrame(4, 4);
    EXPECT_EQ(encodeColorPng(frame.color, PngOptions::atLevel(13)).error().message,
              "PNG encoder: the level must be 0 to 12 (or -1: auto), got 13");
    EXPECT_EQ(encodeIdPng(frame.ids, PngOptions::atLevel(-2)).error().message,
              "PNG encoder: the level must be 0 to 12 (or -1: auto), got -2");
}

}  // namespace
}  // namespace frugal
