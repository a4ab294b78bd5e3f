// Helpers for the software backend's tests: the GL backend (EGL surfaceless, llvmpipe) as the
// reference, a pixel-by-pixel comparison of two read-backs, and the images written on failure
// (reference, actual, diff) into FRUGAL_TEST_OUTPUT_DIR/<name>/.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "TestSupport.h"
#include "gl/GlBackend.h"
#include "io/ImageIO.h"
#include "pipeline/Backend.h"
#include "software/SoftwareBackend.h"

namespace frugal::test {

// The reference: llvmpipe through EGL surfaceless. A failure (not a skip) when it cannot be made:
// these tests are labelled `gl` and the machines that run them have it.
inline std::unique_ptr<Backend> makeReference() {
    Result<std::unique_ptr<Backend>> backend = createGlBackend(BackendChoice::EglSurfaceless);
    if (!backend) {
        ADD_FAILURE() << backend.error().message;
        return nullptr;
    }
    return std::move(*backend);
}

// A fixture with both backends, made for each test: the reference and the software backend.
class ReferencePairTest : public ::testing::Test {
protected:
    void SetUp() override {
        reference = makeReference();
        ASSERT_NE(reference, nullptr);
        software = makeSoftwareBackend();
    }
    std::unique_ptr<Backend> reference, software;
};

struct Comparison {
    std::size_t pixels = 0;
    std::size_t covered = 0;       // pixels the reference drew (depth below the clear value or id ≠ 0)
    std::size_t coverage = 0;      // pixels drawn by one and not the other
    std::size_t depth = 0;         // depth values that differ
    std::uint32_t depthWorst = 0;  // largest difference in LSB
    std::size_t ids = 0;           // ids that differ
    std::size_t color = 0;         // pixels with any channel different
    int colorWorst = 0;            // largest channel difference
    bool sizeMismatch = false;

    double idAgreement() const { return pixels ? 1.0 - double(ids) / double(pixels) : 1.0; }
    std::string summary() const {
        std::ostringstream s;
        s << pixels << " pixels, " << covered << " covered: coverage differs at " << coverage << ", depth at " << depth
          << " (worst " << depthWorst << " LSB), ids at " << ids << ", colour at " << color << " (worst " << colorWorst
          << ")" << (sizeMismatch ? ", SIZES DIFFER" : "");
        return s.str();
    }
};

// The depth value of a target cleared to its far plane (frugal/Image.h), as read back.
inline std::uint32_t farValue(DepthFormat format) { return format == DepthFormat::D32F ? 0u : kDepthMax; }

// `drawn(i)`: whether pixel i was drawn, judged from depth against `clearDepth` (default: the far
// value of the reference's format; ids may be off). Depth differences are in LSB (D24) or ULP (D32F).
inline Comparison compareBuffers(const Buffers& reference, const Buffers& actual,
                                 std::optional<std::uint32_t> clearValue = std::nullopt) {
    Comparison c;
    const std::uint32_t clearDepth = clearValue.value_or(farValue(reference.depthFormat));
    if (reference.width != actual.width || reference.height != actual.height ||
        reference.depthFormat != actual.depthFormat || reference.rgba.size() != actual.rgba.size() ||
        reference.depth.size() != actual.depth.size() || reference.ids.size() != actual.ids.size()) {
        c.sizeMismatch = true;
        return c;
    }
    c.pixels = reference.pixelCount();
    for (std::size_t i = 0; i < c.pixels; ++i) {
        const bool a = reference.depth[i] != clearDepth || reference.ids[i] != 0;
        const bool b = actual.depth[i] != clearDepth || actual.ids[i] != 0;
        c.covered += a;
        c.coverage += a != b;
        if (reference.depth[i] != actual.depth[i]) {
            ++c.depth;
            const std::uint32_t d = reference.depth[i] > actual.depth[i] ? reference.depth[i] - actual.depth[i]
                                                                         : actual.depth[i] - reference.depth[i];
            c.depthWorst = std::max(c.depthWorst, d);
        }
        c.ids += reference.ids[i] != actual.ids[i];
        int worst = 0;
        for (int k = 0; k < 4; ++k)
            worst = std::max(worst, std::abs(int(reference.rgba[4 * i + k]) - int(actual.rgba[4 * i + k])));
        c.color += worst != 0;
        c.colorWorst = std::max(c.colorWorst, worst);
    }
    return c;
}

// reference.png, actual.png, ids of both, and diff.png: red = coverage differs, yellow = id differs,
// blue = depth differs, green shade = colour difference (×32), black = equal.
inline void saveImages(const std::string& name, const Buffers& reference, const Buffers& actual) {
    const std::filesystem::path dir = freshDir(name);
    (void)writeFileAtomic((dir / "reference.png").string(), encodeColorPng(reference));
    (void)writeFileAtomic((dir / "actual.png").string(), encodeColorPng(actual));
    (void)writeFileAtomic((dir / "reference-ids.png").string(), encodeIdPng(reference));
    (void)writeFileAtomic((dir / "actual-ids.png").string(), encodeIdPng(actual));
    if (reference.pixelCount() != actual.pixelCount()) return;
    Buffers diff;
    diff.width = reference.width;
    diff.height = reference.height;
    diff.rgba.assign(reference.pixelCount() * 4, 0);
    for (std::size_t i = 0; i < reference.pixelCount(); ++i) {
        std::uint8_t* p = &diff.rgba[4 * i];
        p[3] = 255;
        const std::uint32_t far = farValue(reference.depthFormat);
        const bool a = reference.depth[i] != far || reference.ids[i] != 0;
        const bool b = actual.depth[i] != far || actual.ids[i] != 0;
        int worst = 0;
        for (int k = 0; k < 4; ++k)
            worst = std::max(worst, std::abs(int(reference.rgba[4 * i + k]) - int(actual.rgba[4 * i + k])));
        if (a != b) {
            p[0] = 255;
        } else if (reference.ids[i] != actual.ids[i]) {
            p[0] = p[1] = 255;
        } else if (reference.depth[i] != actual.depth[i]) {
            p[2] = 255;
        } else if (worst != 0) {
            p[1] = std::uint8_t(std::min(255, 64 + 32 * worst));
        }
    }
    (void)writeFileAtomic((dir / "diff.png").string(), encodeColorPng(diff));
}

// The thresholds of the software reference: coverage and depth exact, ids ≥ 99.99 %, colour within
// 1 and different at all on at most 0.1 % of the covered pixels (the display encoding's power is
// computed exactly here and approximated by llvmpipe: software/Shading.h). Writes the images and
// fails with the numbers when they are not met.
inline void expectMatches(const std::string& name, const Buffers& reference, const Buffers& actual,
                          double idAgreement = 0.9999, int colorTolerance = 1, double colorDiffering = 0.001) {
    const Comparison c = compareBuffers(reference, actual);
    const bool ok = !c.sizeMismatch && c.coverage == 0 && c.depth == 0 && c.idAgreement() >= idAgreement &&
                    c.colorWorst <= colorTolerance && double(c.color) <= colorDiffering * double(c.covered);
    EXPECT_TRUE(ok) << name << ": " << c.summary() << "; images in " << (outputDir() / name).string();
    if (!ok) saveImages(name, reference, actual);
}

}  // namespace frugal::test
