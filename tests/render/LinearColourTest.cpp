// Settings::linear through the Renderer: the frame holds its colour in linear light (Frame::linear,
// float32) and its colour image is that colour's display encoding. On the software reference that
// image is the 8-bit render's, byte for byte, wherever nothing blends (the same linear values, the
// same encoding); on GL within a level (llvmpipe's pow and the encoding's differ in the last bits).
// The background keeps its bytes; depth and ids are those of the 8-bit render; a translucent
// background is unpremultiplied in float before the encoding.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>

#include <gtest/gtest.h>

#include <frugal/Renderer.h>

#include "TestSupport.h"

namespace frugal {
namespace {

struct Pair {
    Frame plain, linear;
};

// The scene rendered twice on `backend`: 8-bit, then linear. Nothing when no GL runs here.
std::optional<Pair> renderBoth(BackendKind backend, const std::string& spec, Settings settings) {
    settings.backend = backend;
    settings.ids = true;
    Pair pair;
    for (bool linear : {false, true}) {
        Result<Scene> scene = loadScene(spec);
        EXPECT_TRUE(scene) << scene.error().message;
        if (!scene) return std::nullopt;
        settings.linear = linear;
        Result<Renderer> renderer = Renderer::create(std::move(*scene), settings);
        if (!renderer && renderer.error().kind == ErrorKind::BackendUnavailable) return std::nullopt;
        EXPECT_TRUE(renderer) << renderer.error().message;
        if (!renderer) return std::nullopt;
        Result<Frame> frame = renderer->render(Camera::automatic(), 0.0);
        EXPECT_TRUE(frame) << frame.error().message;
        if (!frame) return std::nullopt;
        (linear ? pair.linear : pair.plain) = std::move(*frame);
    }
    return pair;
}

// The largest channel difference between two colour images of one size, and how many pixels differ.
std::pair<int, std::size_t> colourDifference(const ColorImage& a, const ColorImage& b) {
    int worst = 0;
    std::size_t pixels = 0;
    for (std::size_t i = 0; i < a.rgba.size(); i += 4) {
        int largest = 0;
        for (std::size_t c = 0; c < 4; ++c)
            largest = std::max(largest, std::abs(int(a.rgba[i + c]) - int(b.rgba[i + c])));
        worst = std::max(worst, largest);
        pixels += largest > 0;
    }
    return {worst, pixels};
}

Settings small() {
    Settings s;
    s.width = 160;
    s.height = 120;
    return s;
}

TEST(LinearColourTest, TheSoftwareImageIsTheEightBitRenderByteForByte) {
    for (const char* spec : {"builtin:default", "builtin:materials", "builtin:cubes"}) {
        SCOPED_TRACE(spec);
        const std::optional<Pair> p = renderBoth(BackendKind::Software, spec, small());
        ASSERT_TRUE(p);
        EXPECT_TRUE(p->plain.linear.rgba.empty()) << "no linear colour unless asked for";
        ASSERT_EQ(p->linear.linear.rgba.size(), 160u * 120u * 4u);
        EXPECT_EQ(p->linear.linear.width, 160);
        EXPECT_EQ(p->linear.linear.height, 120);
        EXPECT_EQ(p->linear.color.rgba, p->plain.color.rgba);
        EXPECT_EQ(p->linear.depth.values, p->plain.depth.values);
        EXPECT_EQ(p->linear.ids.ids, p->plain.ids.ids);
        // Every value is the one the encoding maps to the image's byte.
        for (std::size_t i = 0; i < p->linear.linear.rgba.size(); ++i)
            ASSERT_EQ(i % 4 == 3 ? alphaLevel(p->linear.linear.rgba[i]) : displayLevel(p->linear.linear.rgba[i]),
                      p->linear.color.rgba[i])
                << "value " << i;
    }
}

TEST(LinearColourTest, GlIsTheEightBitRenderWithinALevel) {
    for (const char* spec : {"builtin:default", "builtin:materials"}) {
        SCOPED_TRACE(spec);
        const std::optional<Pair> p = renderBoth(BackendKind::Auto, spec, small());
        if (!p) FRUGAL_SKIP_IF_NO_GL("no GL backend");
        ASSERT_EQ(p->linear.linear.rgba.size(), 160u * 120u * 4u);
        const auto [worst, pixels] = colourDifference(p->linear.color, p->plain.color);
        EXPECT_LE(worst, 1);
        EXPECT_LE(pixels, 160u * 120u / 100u) << "at most 1 % of the pixels a level off";
        EXPECT_EQ(p->linear.ids.ids, p->plain.ids.ids);
        EXPECT_EQ(p->linear.depth.values, p->plain.depth.values);
    }
}

// Highlights keep their value above 1 in the linear colour (the 8-bit image clamps them).
TEST(LinearColourTest, BrightValuesAreNotClamped) {
    Settings s = small();
    s.environment = 4.0f;  // a bright sky: white surfaces well above 1
    const std::optional<Pair> p = renderBoth(BackendKind::Software, "builtin:materials", s);
    ASSERT_TRUE(p);
    float brightest = 0.0f;
    for (std::size_t i = 0; i < p->linear.linear.rgba.size(); i += 4)
        brightest = std::max(brightest, p->linear.linear.rgba[i]);
    EXPECT_GT(brightest, 1.5f);
}

// A translucent background: the colour image is straight alpha, as without linear, and the linear
// colour is unpremultiplied too (the background's pixels hold its linear value and alpha).
TEST(LinearColourTest, ATranslucentBackgroundKeepsItsBytes) {
    Settings s = small();
    s.background = {0.2f, 0.4f, 0.6f, 0.5f};
    const std::optional<Pair> p = renderBoth(BackendKind::Software, "builtin:default", s);
    ASSERT_TRUE(p);
    // The 8-bit render rounds premultiplied bytes and divides by a = 0.5, so its own error is up to
    // two levels; the linear one divides in float.
    const auto [worst, pixels] = colourDifference(p->linear.color, p->plain.color);
    EXPECT_LE(worst, 2) << pixels << " pixels differ";
    std::size_t background = 0;
    for (std::size_t i = 0; i < p->linear.ids.ids.size(); ++i) {
        if (p->linear.ids.ids[i] != 0) continue;
        ++background;
        EXPECT_NEAR(p->linear.linear.rgba[4 * i + 1], std::pow(0.4, 2.2), 1e-6) << i;
        EXPECT_EQ(p->linear.linear.rgba[4 * i + 3], 0.5f) << i;
        EXPECT_EQ(p->linear.color.rgba[4 * i + 3], 128) << i;  // 0.5 · 255 rounded to nearest even
        if (HasFailure()) break;
    }
    EXPECT_GT(background, 0u);
}

// The encoding itself: the 8-bit target's, at its ends and against the direct computation.
TEST(LinearColourTest, DisplayLevelEdges) {
    EXPECT_EQ(displayLevel(0.0f), 0);
    EXPECT_EQ(displayLevel(-1.0f), 0);
    EXPECT_EQ(displayLevel(std::numeric_limits<float>::quiet_NaN()), 0);
    EXPECT_EQ(displayLevel(1.0f), 255);
    EXPECT_EQ(displayLevel(1e30f), 255);
    EXPECT_EQ(displayLevel(std::numeric_limits<float>::infinity()), 255);
    EXPECT_EQ(displayLevel(0.5f), 186);  // 0.5^(1/2.2) = 0.7297 → 186.08
    EXPECT_EQ(alphaLevel(0.5f), 128);
    EXPECT_EQ(alphaLevel(-0.5f), 0);
    EXPECT_EQ(alphaLevel(2.0f), 255);
}

}  // namespace
}  // namespace frugal
