// The GL backend on every context kind this build has (EGL surfaceless, EGL device with the software
// device allowed, OSMesa): known colours, depths and ids at known pixels, culling, the id pass against
// the indexed pass, clears, copies, read-back scaling, repeatability, and EGL vs OSMesa identity.
//
// Meshes are built here in clip space (identity matrices) unless a test says otherwise. Target
// 64×48: NDC (x, y) lands at window ((x+1)·32, (y+1)·24); rows are bottom-up.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <vector>

#include "ShadingReference.h"
#include "TestSupport.h"
#include "gl/GlBackend.h"
#include "gl/GlContext.h"
#include "io/ImageIO.h"

namespace frugal {
namespace {

constexpr int kWidth = 64;
constexpr int kHeight = 48;
const glm::vec4 kBackground{0.2f, 0.4f, 0.6f, 1.0f};  // exact in 8 bits: 51, 102, 153

// A backend of `kind`, or nullptr with the reason added as a test failure: every kind this build
// has must work on the machines the tests run on.
std::unique_ptr<Backend> makeBackend(ContextKind kind) {
    Result<std::unique_ptr<GlContext>> context = createContext(kind);
    if (!context) {
        ADD_FAILURE() << context.error().message;
        return nullptr;
    }
    Result<std::unique_ptr<Backend>> backend = makeGlBackend(std::move(*context));
    if (!backend) {
        ADD_FAILURE() << backend.error().message;
        return nullptr;
    }
    return std::move(*backend);
}

std::uint8_t unorm8(float v) { return std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

std::uint32_t depth24(float windowZ) { return std::uint32_t(std::lround(double(windowZ) * kDepthMax)); }

std::size_t at(const Buffers& b, int x, int y) { return std::size_t(y) * std::size_t(b.width) + std::size_t(x); }

// Colour at (x, y) equals `expected` within `tolerance` per channel (GL's float→8-bit rounding).
::testing::AssertionResult colorIs(const Buffers& b, int x, int y, glm::vec4 expected, int tolerance = 1) {
    const std::uint8_t* p = &b.rgba[at(b, x, y) * 4];
    for (int c = 0; c < 4; ++c) {
        const int want = unorm8(expected[c]);
        if (std::abs(int(p[c]) - want) > tolerance)
            return ::testing::AssertionFailure()
                   << "pixel (" << x << ", " << y << ") is " << int(p[0]) << " " << int(p[1]) << " " << int(p[2]) << " "
                   << int(p[3]) << ", expected " << int(unorm8(expected[0])) << " " << int(unorm8(expected[1])) << " "
                   << int(unorm8(expected[2])) << " " << int(unorm8(expected[3])) << " (±" << tolerance << ")";
    }
    return ::testing::AssertionSuccess();
}

// Two triangles, both at NDC z = 0.5 (window z 0.75), normal +z:
//   triangle 0 (source 7): counter-clockwise (front), left half, centroid at window (16, 17.6);
//   triangle 1 (source 3): clockwise (back), right half, centroid at window (48, 17.6).
Mesh frontAndBack() {
    Mesh m;
    m.positions = {{-0.9f, -0.8f, 0.5f}, {-0.1f, -0.8f, 0.5f}, {-0.5f, 0.8f, 0.5f},
                   {0.1f, -0.8f, 0.5f},  {0.5f, 0.8f, 0.5f},   {0.9f, -0.8f, 0.5f}};
    m.normals.assign(6, glm::vec3(0.0f, 0.0f, 1.0f));
    m.indices = {0, 1, 2, 3, 4, 5};
    m.triangleSource = {7, 3};
    return m;
}
constexpr int kFrontX = 16, kBackX = 48, kCentroidY = 17;
const std::uint32_t kTriangleDepth = depth24(0.75f);

// The eye at (0, 0, 2) looking down −z, with an identity view-projection (the view translates by
// −2, the projection back by +2): clip coordinates are the positions themselves. The light shines
// straight along −z, onto the front faces; flipped back faces get the environment alone.
FrameParams simpleFrame(bool writeIds = true) {
    FrameParams frame;
    frame.view = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -2.0f));
    frame.projection = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 2.0f));
    frame.lighting.toLight = glm::vec3(0.0f, 0.0f, 1.0f);
    frame.writeIds = writeIds;
    return frame;
}

// What simpleFrame shows at pixel (x, y) of a width × height target, of a surface at NDC depth z with
// normal n and material (base, metallic, roughness): the shading model computed in double
// (ShadingReference.h), encoded for display.
glm::vec4 shadedAt(int x, int y, float z, glm::vec3 n, const test::ShadedMaterial& material, double alpha = 1.0,
                   int width = kWidth, int height = kHeight) {
    const glm::dvec3 p((x + 0.5) / width * 2.0 - 1.0, (y + 0.5) / height * 2.0 - 1.0, double(z));
    const glm::dvec3 v = glm::normalize(glm::dvec3(0.0, 0.0, 2.0) - p);
    const glm::dvec3 rgb =
        test::displayedRgb(test::referenceShade(material, glm::dvec3(n), v, simpleFrame().lighting));
    return {float(rgb.r), float(rgb.g), float(rgb.b), float(alpha)};
}
glm::vec4 shadedAt(int x, int y, float z, glm::vec3 n, glm::vec4 base, double metallic = 1.0, double roughness = 1.0,
                   int width = kWidth, int height = kHeight) {
    return shadedAt(x, y, z, n, {glm::dvec3(base), metallic, roughness}, base.a, width, height);
}
const glm::vec4 kFactor{1.0f, 0.5f, 0.25f, 1.0f};

std::vector<IndexRange> all(const Mesh& m) { return {IndexRange{0, std::uint32_t(m.triangleCount())}}; }

// `quad` with `texture`, unlit (so a pixel is its texel), on a fresh target.
Buffers drawUnlitTextured(Backend& backend, const Mesh& quad, const Texture& texture, bool writeIds) {
    const MeshHandle mesh = backend.uploadMesh(quad);
    const TextureHandle handle = backend.uploadTexture(texture);
    EXPECT_NE(mesh, kNoHandle);
    EXPECT_NE(handle, kNoHandle);
    const TargetHandle target = backend.createTarget(kWidth, kHeight);
    backend.beginFrame(target, simpleFrame(writeIds));
    DrawParams params;
    params.mesh = mesh;
    params.texture = handle;
    params.unlit = true;
    backend.draw(params, all(quad));
    Buffers out = backend.readBack(target);
    backend.destroyTarget(target);
    return out;
}

// Begins a simple frame on `target` and draws the frontAndBack() mesh uploaded as `mesh`, ids from 100.
void drawFrontAndBack(Backend& backend, TargetHandle target, MeshHandle mesh, bool writeIds, bool doubleSided = true) {
    backend.beginFrame(target, simpleFrame(writeIds));
    DrawParams params;
    params.mesh = mesh;
    params.baseColorFactor = kFactor;
    params.doubleSided = doubleSided;
    params.firstId = 100;
    backend.draw(params, all(frontAndBack()));
}

Buffers drawTwoTriangles(Backend& backend, bool doubleSided, bool writeIds) {
    const MeshHandle handle = backend.uploadMesh(frontAndBack());
    EXPECT_NE(handle, kNoHandle);
    const TargetHandle target = backend.createTarget(kWidth, kHeight);
    EXPECT_NE(target, kNoHandle);
    backend.clear(target, Rect{0, 0, kWidth, kHeight}, kBackground, 1.0f);
    drawFrontAndBack(backend, target, handle, writeIds, doubleSided);
    Buffers out = backend.readBack(target);
    backend.destroyTarget(target);
    return out;
}

// A denser scene for comparisons: overlapping triangles at many depths through a perspective camera,
// with vertex colours, a linearly filtered repeating texture, two instances (one double-sided), and
// ranges given out of order. Deterministic (a fixed LCG).
struct Lcg {
    std::uint32_t state = 12345u;
    float next() {  // [0, 1)
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) / float(1u << 24);
    }
    float in(float lo, float hi) { return lo + (hi - lo) * next(); }
};

Mesh randomMesh(int triangles) {
    Lcg rng;
    Mesh m;
    for (int t = 0; t < triangles; ++t) {
        const glm::vec3 centre{rng.in(-1, 1), rng.in(-1, 1), rng.in(-1, 1)};
        for (int k = 0; k < 3; ++k) {
            m.positions.push_back(centre + glm::vec3(rng.in(-0.9f, 0.9f), rng.in(-0.9f, 0.9f), rng.in(-0.3f, 0.3f)));
            m.normals.push_back(glm::normalize(glm::vec3(rng.in(-1, 1), rng.in(-1, 1), rng.in(0.2f, 1))));
            m.colors.push_back({rng.in(0.2f, 1), rng.in(0.2f, 1), rng.in(0.2f, 1), 1.0f});
            m.uvs.push_back({rng.in(-0.5f, 1.5f), rng.in(-0.5f, 1.5f)});
            m.indices.push_back(std::uint32_t(3 * t + k));
        }
        m.triangleSource.push_back(std::uint32_t(triangles - 1 - t));
    }
    return m;
}

Texture checkerTexture() {
    Texture tex;
    tex.width = 4;
    tex.height = 4;
    tex.filter = Filter::Linear;
    tex.wrapS = Wrap::Repeat;
    tex.wrapT = Wrap::MirroredRepeat;
    for (int i = 0; i < 16; ++i) {
        const bool dark = ((i % 4) + (i / 4)) % 2 == 0;
        tex.rgba.insert(tex.rgba.end(),
                        {std::uint8_t(dark ? 60 : 250), std::uint8_t(dark ? 90 : 240), std::uint8_t(i * 16), 255});
    }
    return tex;
}

Buffers renderDenseScene(Backend& backend, bool writeIds) {
    const Mesh mesh = randomMesh(60);
    const MeshHandle handle = backend.uploadMesh(mesh);
    const TextureHandle texture = backend.uploadTexture(checkerTexture());
    EXPECT_NE(handle, kNoHandle);
    EXPECT_NE(texture, kNoHandle);
    const TargetHandle target = backend.createTarget(kWidth, kHeight);
    backend.clear(target, Rect{0, 0, kWidth, kHeight}, kBackground, 1.0f);
    FrameParams frame;
    frame.view = glm::lookAt(glm::vec3(0.3f, 0.4f, 2.6f), glm::vec3(0.0f), glm::vec3(0, 1, 0));
    frame.projection = glm::perspective(0.9f, float(kWidth) / kHeight, 0.5f, 10.0f);
    frame.writeIds = writeIds;
    backend.beginFrame(target, frame);
    DrawParams params;
    params.mesh = handle;
    params.texture = texture;
    params.firstId = 1;
    params.model = glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(0, 1, 0));
    const IndexRange ranges[] = {{0, 20}, {30, 30}, {20, 10}};
    backend.draw(params, ranges);
    params.doubleSided = true;
    params.texture = kNoHandle;
    params.baseColorFactor = {0.8f, 1.0f, 0.6f, 1.0f};
    params.firstId = 1000;
    params.model = glm::translate(glm::scale(glm::mat4(1.0f), glm::vec3(0.7f)), glm::vec3(0.4f, -0.2f, 0.5f));
    backend.draw(params, all(mesh));
    Buffers out = backend.readBack(target);
    backend.destroyTarget(target);
    return out;
}

// Saves colour and id images of both when they differ, for a look at the failure.
::testing::AssertionResult identical(const Buffers& a, const Buffers& b, const std::string& name,
                                     bool compareIds = true) {
    const bool same = a.width == b.width && a.height == b.height && a.rgba == b.rgba && a.depth == b.depth &&
                      (!compareIds || a.ids == b.ids);
    if (same) return ::testing::AssertionSuccess();
    const std::filesystem::path dir = test::freshDir(name);
    (void)writeFileAtomic((dir / "a.png").string(), encodeColorPng(a));
    (void)writeFileAtomic((dir / "b.png").string(), encodeColorPng(b));
    (void)writeFileAtomic((dir / "a-ids.png").string(), encodeIdPng(a));
    (void)writeFileAtomic((dir / "b-ids.png").string(), encodeIdPng(b));
    std::size_t colour = 0, depth = 0, ids = 0;
    for (std::size_t i = 0; i < std::min(a.pixelCount(), b.pixelCount()); ++i) {
        colour += std::equal(&a.rgba[4 * i], &a.rgba[4 * i + 4], &b.rgba[4 * i]) ? 0 : 1;
        depth += a.depth[i] != b.depth[i];
        ids += a.ids[i] != b.ids[i];
    }
    return ::testing::AssertionFailure() << name << ": " << colour << " colour, " << depth << " depth, " << ids
                                         << " id pixels differ; images in " << dir;
}

class GlBackendGLTest : public ::testing::TestWithParam<ContextKind> {
protected:
    void SetUp() override {
        backend_ = makeBackend(GetParam());
        if (!backend_) GTEST_SKIP() << "no backend (reported as a failure above)";
    }
    std::unique_ptr<Backend> backend_;
};

TEST_P(GlBackendGLTest, NameAndRenderer) {
    EXPECT_EQ(backend_->name(), contextKindName(GetParam()));
    const std::string renderer = backend_->renderer();
    EXPECT_NE(renderer.find("; "), std::string::npos) << renderer;
    EXPECT_NE(renderer.find("Core Profile"), std::string::npos) << renderer;
    EXPECT_GE(backend_->maxTargetSize(), 4096);
}

TEST_P(GlBackendGLTest, DrawsKnownColourDepthAndIds) {
    const Buffers b = drawTwoTriangles(*backend_, /*doubleSided=*/false, /*writeIds=*/true);
    ASSERT_EQ(b.width, kWidth);
    ASSERT_EQ(b.height, kHeight);
    EXPECT_TRUE(colorIs(b, kFrontX, kCentroidY, shadedAt(kFrontX, kCentroidY, 0.5f, {0, 0, 1}, kFactor)));
    EXPECT_NEAR(double(b.depth[at(b, kFrontX, kCentroidY)]), double(kTriangleDepth), 1.0);
    EXPECT_EQ(b.ids[at(b, kFrontX, kCentroidY)], 107u);
    // Back face culled: background colour, far depth, id 0.
    EXPECT_TRUE(colorIs(b, kBackX, kCentroidY, kBackground, 0));
    EXPECT_EQ(b.depth[at(b, kBackX, kCentroidY)], kDepthMax);
    EXPECT_EQ(b.ids[at(b, kBackX, kCentroidY)], 0u);
    // Outside both triangles.
    for (auto [x, y] : {std::pair{0, 0}, std::pair{63, 47}, std::pair{32, 20}, std::pair{16, 45}}) {
        EXPECT_TRUE(colorIs(b, x, y, kBackground, 0));
        EXPECT_EQ(b.depth[at(b, x, y)], kDepthMax) << x << ", " << y;
        EXPECT_EQ(b.ids[at(b, x, y)], 0u) << x << ", " << y;
    }
    // Every pixel is either the triangle (id 107, its depth) or background: nothing in between.
    std::size_t covered = 0;
    for (std::size_t i = 0; i < b.pixelCount(); ++i) {
        if (b.ids[i] == 0) {
            EXPECT_EQ(b.depth[i], kDepthMax) << "pixel " << i;
        } else {
            EXPECT_EQ(b.ids[i], 107u) << "pixel " << i;
            ++covered;
        }
    }
    // Area 0.8 × 1.6 / 2 NDC² = 0.64 of 4 → 16 % of 3072 pixels ≈ 491.
    EXPECT_NEAR(double(covered), 491.5, 20.0);
}

TEST_P(GlBackendGLTest, DoubleSidedDrawsBackFacesWithFlippedNormal) {
    const Buffers b = drawTwoTriangles(*backend_, /*doubleSided=*/true, /*writeIds=*/true);
    EXPECT_TRUE(colorIs(b, kFrontX, kCentroidY, shadedAt(kFrontX, kCentroidY, 0.5f, {0, 0, 1}, kFactor)));
    // The back face's normal is negated, so the light is behind it: the environment only.
    EXPECT_TRUE(colorIs(b, kBackX, kCentroidY, shadedAt(kBackX, kCentroidY, 0.5f, {0, 0, -1}, kFactor)));
    EXPECT_NEAR(double(b.depth[at(b, kBackX, kCentroidY)]), double(kTriangleDepth), 1.0);
    EXPECT_EQ(b.ids[at(b, kBackX, kCentroidY)], 103u);
    EXPECT_EQ(b.ids[at(b, kFrontX, kCentroidY)], 107u);
}

TEST_P(GlBackendGLTest, WithoutIdsLeavesIdsZeroAndGivesTheSameColourAndDepth) {
    for (bool doubleSided : {false, true}) {
        const Buffers with = drawTwoTriangles(*backend_, doubleSided, true);
        const Buffers without = drawTwoTriangles(*backend_, doubleSided, false);
        EXPECT_TRUE(identical(with, without, "ids-vs-none-simple", /*compareIds=*/false));
        EXPECT_TRUE(std::all_of(without.ids.begin(), without.ids.end(), [](std::uint32_t id) { return id == 0; }));
    }
    const Buffers with = renderDenseScene(*backend_, true);
    const Buffers without = renderDenseScene(*backend_, false);
    EXPECT_TRUE(identical(with, without, "ids-vs-none-dense", /*compareIds=*/false));
    EXPECT_TRUE(std::all_of(without.ids.begin(), without.ids.end(), [](std::uint32_t id) { return id == 0; }));
    // The id pass itself: background exactly where nothing was drawn, valid ids elsewhere.
    std::size_t drawn = 0;
    for (std::size_t i = 0; i < with.pixelCount(); ++i) {
        const std::uint32_t id = with.ids[i];
        EXPECT_EQ(id == 0, with.depth[i] == kDepthMax) << "pixel " << i;
        if (id == 0) continue;
        ++drawn;
        EXPECT_TRUE((id >= 1 && id <= 60) || (id >= 1000 && id < 1060)) << "pixel " << i << " id " << id;
    }
    EXPECT_GT(drawn, with.pixelCount() / 2) << "the dense scene should cover most of the target";
}

TEST_P(GlBackendGLTest, RangesSelectTrianglesInBothPaths) {
    Mesh mesh = frontAndBack();
    std::swap(mesh.indices[3], mesh.indices[4]);  // make triangle 1 front-facing too
    const MeshHandle handle = backend_->uploadMesh(mesh);
    const TargetHandle target = backend_->createTarget(kWidth, kHeight);
    for (bool writeIds : {true, false}) {
        backend_->clear(target, Rect{0, 0, kWidth, kHeight}, kBackground, 1.0f);
        backend_->beginFrame(target, simpleFrame(writeIds));
        DrawParams params;
        params.mesh = handle;
        params.firstId = 100;
        const IndexRange second[] = {{1, 1}, {2, 0}};
        backend_->draw(params, second);
        const Buffers b = backend_->readBack(target);
        EXPECT_TRUE(colorIs(b, kFrontX, kCentroidY, kBackground, 0)) << "writeIds " << writeIds;
        EXPECT_TRUE(colorIs(b, kBackX, kCentroidY, shadedAt(kBackX, kCentroidY, 0.5f, {0, 0, 1}, glm::vec4(1.0f))))
            << "writeIds " << writeIds;
        EXPECT_EQ(b.ids[at(b, kBackX, kCentroidY)], writeIds ? 103u : 0u);
    }
    backend_->destroyTarget(target);
}

// Many short ranges are drawn from one streamed index buffer (gl/GlDraw.cpp): the same triangles in
// the same order as drawing them range by range, so the same colour and depth, ties included; and the
// mesh's own index buffer is back in its VAO afterwards.
TEST_P(GlBackendGLTest, ManyShortRangesDrawTheSameAsOneRangeAtATime) {
    const Mesh mesh = randomMesh(400);
    const MeshHandle handle = backend_->uploadMesh(mesh);
    const TargetHandle target = backend_->createTarget(kWidth, kHeight);
    FrameParams frame;
    frame.view = glm::lookAt(glm::vec3(0.3f, 0.4f, 2.6f), glm::vec3(0.0f), glm::vec3(0, 1, 0));
    frame.projection = glm::perspective(0.9f, float(kWidth) / kHeight, 0.5f, 10.0f);
    frame.writeIds = false;
    DrawParams params;
    params.mesh = handle;
    params.doubleSided = true;
    // Every other run of 1–3 triangles: 100+ ranges, far more than the gathering threshold.
    std::vector<IndexRange> ranges;
    for (std::uint32_t t = 0, k = 0; t < 400; t += 2 + k % 3, ++k) ranges.push_back({t, 1 + k % 3});
    ASSERT_GE(ranges.size(), 100u);

    const auto render = [&](bool gathered) {
        backend_->clear(target, Rect{0, 0, kWidth, kHeight}, kBackground, 1.0f);
        backend_->beginFrame(target, frame);
        if (gathered) {
            backend_->draw(params, ranges);
        } else {
            for (const IndexRange& range : ranges) backend_->draw(params, std::span<const IndexRange>(&range, 1));
        }
        return backend_->readBack(target);
    };
    const Buffers gathered = render(true);
    const Buffers separate = render(false);
    EXPECT_TRUE(identical(gathered, separate, "gathered-vs-separate", /*compareIds=*/false));
    // After the gathered draw the mesh draws whole from its own index buffer again.
    const auto thenWhole = [&](bool gather) {
        render(gather);
        backend_->draw(params, all(mesh));
        return backend_->readBack(target);
    };
    EXPECT_TRUE(identical(thenWhole(true), thenWhole(false), "whole-after-gathered", /*compareIds=*/false));
    backend_->destroyTarget(target);
}

// Three full-screen-ish triangles at NDC depths `zs`, red, green and blue (sources 0, 1, 2).
Mesh threeLayers(const std::array<float, 3>& zs) {
    Mesh m;
    for (int t = 0; t < 3; ++t) {
        const float z = zs[std::size_t(t)];
        m.positions.insert(m.positions.end(), {{-3.0f, -3.0f, z}, {3.0f, -3.0f, z}, {0.0f, 3.0f, z}});
        m.colors.insert(m.colors.end(), 3, glm::vec4(t == 0, t == 1, t == 2, 1.0f));
        m.indices.insert(m.indices.end(), {std::uint32_t(3 * t), std::uint32_t(3 * t + 1), std::uint32_t(3 * t + 2)});
        m.triangleSource.push_back(std::uint32_t(t));
    }
    m.normals.assign(9, glm::vec3(0, 0, 1));
    return m;
}

// A cleared target with a frame begun, for unlit draws (a pixel is its colour).
TargetHandle startFrame(Backend& backend) {
    const TargetHandle target = backend.createTarget(kWidth, kHeight);
    backend.clear(target, Rect{0, 0, kWidth, kHeight}, kBackground, 1.0f);
    backend.beginFrame(target, simpleFrame());
    return target;
}

TEST_P(GlBackendGLTest, DepthTestKeepsTheNearerAndTheFirstOnTies) {
    // Two full-screen-ish triangles: source 0 at NDC z 0.5, source 1 at z -0.5 (nearer), then a
    // third at exactly the nearer one's depth, drawn last: GL_LESS keeps the earlier one.
    const Mesh m = threeLayers({0.5f, -0.5f, -0.5f});
    const MeshHandle handle = backend_->uploadMesh(m);
    const TargetHandle target = startFrame(*backend_);
    DrawParams params;
    params.mesh = handle;
    params.unlit = true;
    backend_->draw(params, all(m));
    const Buffers b = backend_->readBack(target);
    EXPECT_TRUE(colorIs(b, 32, 24, {0, 1, 0, 1}, 0));
    EXPECT_EQ(b.ids[at(b, 32, 24)], 2u);  // firstId 1 + source 1
    EXPECT_NEAR(double(b.depth[at(b, 32, 24)]), double(depth24(0.25f)), 1.0);
    backend_->destroyTarget(target);
}

TEST_P(GlBackendGLTest, DepthOffDrawsInOrderAndWritesNoDepth) {
    // The three triangles of the test above with DepthMode::Off: the last drawn (source 2) keeps
    // the pixel whatever its depth, and the depth buffer keeps its clear value. A depth-tested draw
    // after it tests again (the state is per draw): the nearer triangles pass the cleared depth.
    const Mesh m = threeLayers({-0.5f, 0.5f, 0.9f});  // the last one drawn is the farthest
    const MeshHandle handle = backend_->uploadMesh(m);
    const TargetHandle target = startFrame(*backend_);
    DrawParams params;
    params.mesh = handle;
    params.unlit = true;
    params.depth = DepthMode::Off;
    backend_->draw(params, all(m));
    Buffers b = backend_->readBack(target);
    EXPECT_TRUE(colorIs(b, 32, 24, {0, 0, 1, 1}, 0));
    EXPECT_EQ(b.ids[at(b, 32, 24)], 3u);
    EXPECT_EQ(b.depth[at(b, 32, 24)], 0xFFFFFFu);
    params.depth = DepthMode::Test;
    backend_->draw(params, {{IndexRange{1, 1}}});  // source 1, z 0.5: passes the cleared depth
    b = backend_->readBack(target);
    EXPECT_TRUE(colorIs(b, 32, 24, {0, 1, 0, 1}, 0));
    EXPECT_NEAR(double(b.depth[at(b, 32, 24)]), double(depth24(0.75f)), 1.0);
    backend_->destroyTarget(target);
}

TEST_P(GlBackendGLTest, StateChangesCountWhatTheCacheLetsThrough) {
    const MeshHandle handle = backend_->uploadMesh(frontAndBack());
    const TargetHandle target = backend_->createTarget(kWidth, kHeight);
    drawFrontAndBack(*backend_, target, handle, true);
    const StateChanges first = backend_->stateChanges();
    DrawParams params;
    params.mesh = handle;
    params.baseColorFactor = kFactor;
    params.doubleSided = true;
    params.firstId = 100;
    backend_->draw(params, all(frontAndBack()));  // the same draw again: nothing to change
    StateChanges now = backend_->stateChanges();
    EXPECT_EQ(now.draws, first.draws + 1);
    EXPECT_EQ(now.meshes, first.meshes);
    EXPECT_EQ(now.programs, first.programs);
    EXPECT_EQ(now.toggles, first.toggles);
    EXPECT_EQ(now.uniforms, first.uniforms);
    params.firstId = 200;  // one uniform
    params.depth = DepthMode::Off;  // one toggle
    backend_->draw(params, all(frontAndBack()));
    const StateChanges last = backend_->stateChanges();
    EXPECT_EQ(last.draws, now.draws + 1);
    EXPECT_EQ(last.uniforms, now.uniforms + 1);
    EXPECT_EQ(last.toggles, now.toggles + 1);
    EXPECT_EQ(last.meshes, now.meshes);
    backend_->finish();
    backend_->destroyTarget(target);
}

TEST_P(GlBackendGLTest, InstancedDrawsEqualOneDrawPerInstance) {
    // Three instances of the two-triangle mesh, each with its own transform and first id,
    // overlapping so that the order shows: one drawInstances against three draws, with and without
    // ids, bit for bit, and one draw call against three. The material is the draw's.
    const MeshHandle handle = backend_->uploadMesh(frontAndBack());
    const TargetHandle target = backend_->createTarget(kWidth, kHeight);
    const InstanceParams instances[3] = {
        {glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 0.1f)), 100},
        {glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, 0.1f, -0.2f)), 200},
        {glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(0, 0, 1)), 300}};
    DrawParams params;
    params.mesh = handle;
    params.doubleSided = true;
    params.baseColorFactor = glm::vec4(0.2f, 0.6f, 0.9f, 0.5f);
    params.metallic = 0.3f;
    params.roughness = 0.4f;
    for (const bool ids : {true, false}) {
        SCOPED_TRACE(ids ? "with ids" : "without ids");
        backend_->clear(target, Rect{0, 0, kWidth, kHeight}, kBackground, 1.0f);
        backend_->beginFrame(target, simpleFrame(ids));
        for (const InstanceParams& instance : instances) {
            DrawParams one = params;
            one.model = instance.model;
            one.firstId = instance.firstId;
            backend_->draw(one, all(frontAndBack()));
        }
        const Buffers separate = backend_->readBack(target);
        backend_->clear(target, Rect{0, 0, kWidth, kHeight}, kBackground, 1.0f);
        backend_->beginFrame(target, simpleFrame(ids));
        const StateChanges before = backend_->stateChanges();
        backend_->drawInstances(params, instances, IndexRange{0, 2});
        EXPECT_EQ(backend_->stateChanges().draws, before.draws + 1);
        const Buffers batched = backend_->readBack(target);
        EXPECT_EQ(batched.rgba, separate.rgba);
        EXPECT_EQ(batched.depth, separate.depth);
        EXPECT_EQ(batched.ids, separate.ids);
        if (ids) {
            EXPECT_NE(std::count(batched.ids.begin(), batched.ids.end(), 300u + 7u), 0);  // the last instance shows
        }
    }
    backend_->destroyTarget(target);
}

TEST_P(GlBackendGLTest, TextureRowsAndNearestFilter) {
    // A 2×2 texture on a quad covering the target, nearest filter: the first stored row is v = 0,
    // which the quad maps to the bottom of the window.
    Texture tex;
    tex.width = 2;
    tex.height = 2;
    tex.filter = Filter::Nearest;
    tex.rgba = {255, 0, 0,   255, 0,   255, 0,   255,   // row 0: red, green
                0,   0, 255, 255, 255, 255, 255, 255};  // row 1: blue, white
    Mesh quad;
    quad.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    quad.normals.assign(4, glm::vec3(0, 0, 1));
    quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    quad.triangleSource = {0, 1};
    const Buffers b = drawUnlitTextured(*backend_, quad, tex, true);
    EXPECT_TRUE(colorIs(b, 10, 10, {1, 0, 0, 1}, 0));  // bottom left: row 0, texel 0
    EXPECT_TRUE(colorIs(b, 50, 10, {0, 1, 0, 1}, 0));
    EXPECT_TRUE(colorIs(b, 10, 40, {0, 0, 1, 1}, 0));
    EXPECT_TRUE(colorIs(b, 50, 40, {1, 1, 1, 1}, 0));

    Texture bad = tex;
    bad.rgba.pop_back();
    EXPECT_EQ(backend_->uploadTexture(bad), kNoHandle);
}

TEST_P(GlBackendGLTest, ClearsASubRectangle) {
    const TargetHandle target = backend_->createTarget(kWidth, kHeight);
    ASSERT_NE(target, kNoHandle);
    // A fresh target is cleared: transparent black, far, id 0.
    Buffers b = backend_->readBack(target);
    EXPECT_TRUE(colorIs(b, 5, 5, {0, 0, 0, 0}, 0));
    EXPECT_EQ(b.depth[at(b, 5, 5)], kDepthMax);

    // Draw the front triangle so ids are non-zero, then clear a rectangle across it.
    const Mesh mesh = frontAndBack();
    const MeshHandle handle = backend_->uploadMesh(mesh);
    backend_->clear(target, Rect{0, 0, kWidth, kHeight}, kBackground, 1.0f);
    backend_->beginFrame(target, simpleFrame());
    DrawParams params;
    params.mesh = handle;
    params.firstId = 100;
    backend_->draw(params, all(mesh));
    const Rect rect{10, 12, 8, 6};  // covers (16, 17), the front triangle's centroid
    const glm::vec4 red{1, 0, 0, 1};
    backend_->clear(target, rect, red, 0.25f);
    b = backend_->readBack(target);
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const bool inside = x >= rect.x && x < rect.x + rect.width && y >= rect.y && y < rect.y + rect.height;
            if (inside) {
                ASSERT_TRUE(colorIs(b, x, y, red, 0));
                ASSERT_EQ(b.ids[at(b, x, y)], 0u) << x << ", " << y;
                ASSERT_NEAR(double(b.depth[at(b, x, y)]), double(depth24(0.25f)), 1.0) << x << ", " << y;
            }
        }
    }
    // Just outside the rectangle the triangle is still there.
    EXPECT_EQ(b.ids[at(b, 16, rect.y + rect.height)], 107u);
    EXPECT_EQ(b.ids[at(b, rect.x - 1, 10)], 107u);
    // Drawing continues into the same frame after a clear.
    backend_->draw(params, all(mesh));
    b = backend_->readBack(target);
    EXPECT_EQ(b.ids[at(b, kFrontX, kCentroidY)], 0u) << "the cleared depth 0.25 is nearer than 0.75";
    EXPECT_TRUE(colorIs(b, kFrontX, kCentroidY, red, 0));
    backend_->destroyTarget(target);
}

TEST_P(GlBackendGLTest, CopiesARectanglePerAttachment) {
    const Mesh mesh = frontAndBack();
    const MeshHandle handle = backend_->uploadMesh(mesh);
    const TargetHandle source = backend_->createTarget(kWidth, kHeight);
    backend_->clear(source, Rect{0, 0, kWidth, kHeight}, kBackground, 1.0f);
    backend_->beginFrame(source, simpleFrame());
    DrawParams params;
    params.mesh = handle;
    params.firstId = 100;
    params.doubleSided = true;
    backend_->draw(params, all(mesh));
    const Buffers src = backend_->readBack(source);

    const TargetHandle dest = backend_->createTarget(kWidth, kHeight);
    const glm::vec4 destColor{0, 0, 1, 1};
    const Rect rect{12, 10, 40, 12};  // both centroids, part of each triangle and background
    struct Case {
        bool color, depth, ids;
    } cases[] = {{true, false, false}, {false, true, false}, {false, false, true}, {true, true, true}};
    for (const Case& c : cases) {
        backend_->clear(dest, Rect{0, 0, kWidth, kHeight}, destColor, 0.5f);
        const Buffers before = backend_->readBack(dest);
        backend_->copy(source, dest, rect, c.color, c.depth, c.ids);
        const Buffers b = backend_->readBack(dest);
        int changedColor = 0, changedDepth = 0, changedIds = 0;
        for (int y = 0; y < kHeight; ++y) {
            for (int x = 0; x < kWidth; ++x) {
                const std::size_t i = at(b, x, y);
                const bool inside = x >= rect.x && x < rect.x + rect.width && y >= rect.y && y < rect.y + rect.height;
                const Buffers& colorFrom = inside && c.color ? src : before;
                const Buffers& depthFrom = inside && c.depth ? src : before;
                const Buffers& idsFrom = inside && c.ids ? src : before;
                ASSERT_TRUE(std::equal(&b.rgba[4 * i], &b.rgba[4 * i + 4], &colorFrom.rgba[4 * i]))
                    << "colour at " << x << ", " << y << " (copy " << c.color << c.depth << c.ids << ")";
                ASSERT_EQ(b.depth[i], depthFrom.depth[i])
                    << x << ", " << y << " (copy " << c.color << c.depth << c.ids << ")";
                ASSERT_EQ(b.ids[i], idsFrom.ids[i])
                    << x << ", " << y << " (copy " << c.color << c.depth << c.ids << ")";
                changedColor += !std::equal(&b.rgba[4 * i], &b.rgba[4 * i + 4], &before.rgba[4 * i]);
                changedDepth += b.depth[i] != before.depth[i];
                changedIds += b.ids[i] != before.ids[i];
            }
        }
        // The copy must have done something where asked (the source differs inside the rectangle).
        EXPECT_EQ(changedColor > 0, c.color);
        EXPECT_EQ(changedDepth > 0, c.depth);
        EXPECT_EQ(changedIds > 0, c.ids);
    }
    // A frame drawn after copies still goes to its target with ids.
    backend_->clear(source, Rect{0, 0, kWidth, kHeight}, kBackground, 1.0f);
    backend_->beginFrame(source, simpleFrame());
    backend_->draw(params, all(mesh));
    EXPECT_TRUE(identical(backend_->readBack(source), src, "draw-after-copy"));
    backend_->destroyTarget(source);
    backend_->destroyTarget(dest);
}

TEST_P(GlBackendGLTest, DepthReadBackIsTheStored24BitValue) {
    const TargetHandle target = backend_->createTarget(4, 4);
    const auto cleared = [&](float depth) {
        backend_->clear(target, Rect{0, 0, 4, 4}, kBackground, depth);
        return backend_->readBack(target).depth[5];
    };
    EXPECT_EQ(cleared(1.0f), 0xFFFFFFu);
    EXPECT_EQ(cleared(0.0f), 0u);
    // 0.5 · 0xFFFFFF = 8388607.5: llvmpipe rounds the tie up (documented in GlBackend.cpp).
    EXPECT_EQ(cleared(0.5f), 0x800000u);
    EXPECT_EQ(cleared(0.25f), depth24(0.25f));
    EXPECT_EQ(cleared(2.0f), 0xFFFFFFu) << "clamped to [0, 1]";
    backend_->destroyTarget(target);
}

TEST_P(GlBackendGLTest, TwoRendersAreIdentical) {
    const Buffers a = renderDenseScene(*backend_, true);
    const Buffers b = renderDenseScene(*backend_, true);
    EXPECT_TRUE(identical(a, b, std::string("repeat-") + contextKindName(GetParam())));
}

TEST_P(GlBackendGLTest, OneByOneTarget) {
    const TargetHandle target = backend_->createTarget(1, 1);
    ASSERT_NE(target, kNoHandle);
    Mesh big;
    big.positions = {{-3, -3, 0}, {3, -3, 0}, {0, 3, 0}};
    big.normals.assign(3, glm::vec3(0, 0, 1));
    big.indices = {0, 1, 2};
    big.triangleSource = {4};
    const MeshHandle mesh = backend_->uploadMesh(big);
    backend_->clear(target, Rect{0, 0, 1, 1}, kBackground, 1.0f);
    backend_->beginFrame(target, simpleFrame());
    DrawParams params;
    params.mesh = mesh;
    params.firstId = 10;
    backend_->draw(params, all(big));
    const Buffers b = backend_->readBack(target);
    ASSERT_EQ(b.pixelCount(), 1u);
    EXPECT_EQ(b.ids[0], 14u);
    EXPECT_TRUE(colorIs(b, 0, 0, shadedAt(0, 0, 0.0f, {0, 0, 1}, glm::vec4(1.0f), 1.0, 1.0, 1, 1)));
    EXPECT_NEAR(double(b.depth[0]), double(depth24(0.5f)), 1.0);
    backend_->destroyTarget(target);
}

TEST_P(GlBackendGLTest, BadSizesAndBadMeshesGiveNoHandle) {
    const int max = backend_->maxTargetSize();
    for (auto [w, h] : {std::pair{0, 0}, std::pair{0, 10}, std::pair{10, 0}, std::pair{-1, 5}, std::pair{max + 1, 1},
                        std::pair{1, max + 1}})
        EXPECT_EQ(backend_->createTarget(w, h), kNoHandle) << w << "×" << h;
    // Still usable afterwards.
    const TargetHandle ok = backend_->createTarget(2, 2);
    EXPECT_NE(ok, kNoHandle);
    backend_->destroyTarget(ok);

    Mesh outOfRange = frontAndBack();
    outOfRange.indices[4] = 6;
    EXPECT_EQ(backend_->uploadMesh(outOfRange), kNoHandle);
    Mesh notTriangles = frontAndBack();
    notTriangles.indices.pop_back();
    EXPECT_EQ(backend_->uploadMesh(notTriangles), kNoHandle);
    Mesh shortNormals = frontAndBack();
    shortNormals.normals.pop_back();
    EXPECT_EQ(backend_->uploadMesh(shortNormals), kNoHandle);
    Mesh shortSources = frontAndBack();
    shortSources.triangleSource.pop_back();
    EXPECT_EQ(backend_->uploadMesh(shortSources), kNoHandle);
}

TEST_P(GlBackendGLTest, MeshWithoutNormalsOrSourcesUsesDefaults) {
    // No normals: +z; no triangleSource: triangle t has source t.
    Mesh mesh = frontAndBack();
    mesh.normals.clear();
    mesh.triangleSource.clear();
    const Buffers reference = drawTwoTriangles(*backend_, true, true);
    const MeshHandle handle = backend_->uploadMesh(mesh);
    ASSERT_NE(handle, kNoHandle);
    const TargetHandle target = backend_->createTarget(kWidth, kHeight);
    backend_->clear(target, Rect{0, 0, kWidth, kHeight}, kBackground, 1.0f);
    backend_->beginFrame(target, simpleFrame());
    DrawParams params;
    params.mesh = handle;
    params.baseColorFactor = kFactor;
    params.doubleSided = true;
    params.firstId = 100;
    backend_->draw(params, all(mesh));
    const Buffers b = backend_->readBack(target);
    EXPECT_TRUE(identical(b, reference, "default-normals", /*compareIds=*/false));
    EXPECT_EQ(b.ids[at(b, kFrontX, kCentroidY)], 100u);
    EXPECT_EQ(b.ids[at(b, kBackX, kCentroidY)], 101u);
    backend_->destroyTarget(target);
}

// --- The id attachment's contract (Backend.h): clear sets ids to 0, and a frame without ids leaves
// them as cleared. The backend skips clearing ids it knows to be 0 (GlBackend.cpp); these would fail
// if it lost track.

bool allIdsZero(const Buffers& b) {
    return std::all_of(b.ids.begin(), b.ids.end(), [](std::uint32_t id) { return id == 0; });
}

TEST_P(GlBackendGLTest, ClearAfterAFrameWithIdsZeroesThemForAFrameWithout) {
    const MeshHandle mesh = backend_->uploadMesh(frontAndBack());
    const TargetHandle target = backend_->createTarget(kWidth, kHeight);
    const Rect whole{0, 0, kWidth, kHeight};
    EXPECT_TRUE(allIdsZero(backend_->readBack(target))) << "a new target";

    backend_->clear(target, whole, kBackground, 1.0f);
    drawFrontAndBack(*backend_, target, mesh, true);
    const Buffers withIds = backend_->readBack(target);
    ASSERT_EQ(withIds.ids[at(withIds, kFrontX, kCentroidY)], 107u);

    // Frames alternate with and without ids: ids are exactly the drawn ones, or all 0.
    for (int frame = 0; frame < 6; ++frame) {
        const bool writeIds = frame % 3 == 2;
        backend_->clear(target, whole, kBackground, 1.0f);
        drawFrontAndBack(*backend_, target, mesh, writeIds);
        const Buffers b = backend_->readBack(target);
        EXPECT_TRUE(identical(b, withIds, "alternating-ids-" + std::to_string(frame), /*compareIds=*/writeIds));
        if (!writeIds) {
            EXPECT_TRUE(allIdsZero(b)) << "frame " << frame;
        }
    }
    backend_->destroyTarget(target);
}

TEST_P(GlBackendGLTest, PartialClearsOfIdsClearTheRectangleOnly) {
    const MeshHandle mesh = backend_->uploadMesh(frontAndBack());
    const TargetHandle target = backend_->createTarget(kWidth, kHeight);
    const Rect whole{0, 0, kWidth, kHeight};
    backend_->clear(target, whole, kBackground, 1.0f);
    drawFrontAndBack(*backend_, target, mesh, true);
    const Buffers drawn = backend_->readBack(target);

    // A rectangle over part of both triangles and background, cleared, then drawn again without
    // ids: inside, the ids are 0 (the triangles come back in colour); outside, the first frame's.
    const Rect rect{10, 12, 44, 6};
    backend_->clear(target, rect, kBackground, 1.0f);
    drawFrontAndBack(*backend_, target, mesh, false);
    Buffers b = backend_->readBack(target);
    EXPECT_TRUE(identical(b, drawn, "partial-clear-colour", /*compareIds=*/false));
    int kept = 0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const bool inside = x >= rect.x && x < rect.x + rect.width && y >= rect.y && y < rect.y + rect.height;
            const std::uint32_t want = inside ? 0u : drawn.ids[at(drawn, x, y)];
            ASSERT_EQ(b.ids[at(b, x, y)], want) << x << ", " << y;
            kept += !inside && want != 0;
        }
    }
    EXPECT_GT(kept, 100) << "ids outside the rectangle must survive";

    // Two partial clears that together cover the target are not one whole clear: ids still cleared.
    backend_->clear(target, Rect{0, 0, kWidth, kHeight / 2}, kBackground, 1.0f);
    backend_->clear(target, Rect{0, kHeight / 2, kWidth, kHeight - kHeight / 2}, kBackground, 1.0f);
    EXPECT_TRUE(allIdsZero(backend_->readBack(target)));
    drawFrontAndBack(*backend_, target, mesh, false);
    EXPECT_TRUE(allIdsZero(backend_->readBack(target)));
    backend_->destroyTarget(target);
}

TEST_P(GlBackendGLTest, IdsCopiedIntoATargetAreClearedLikeDrawnOnes) {
    const MeshHandle mesh = backend_->uploadMesh(frontAndBack());
    const Rect whole{0, 0, kWidth, kHeight};
    const TargetHandle source = backend_->createTarget(kWidth, kHeight);
    backend_->clear(source, whole, kBackground, 1.0f);
    drawFrontAndBack(*backend_, source, mesh, true);
    const Buffers src = backend_->readBack(source);

    // Only ids arrive in `dest` (a new target), through a copy: no draw with ids ever went there.
    const TargetHandle dest = backend_->createTarget(kWidth, kHeight);
    backend_->copy(source, dest, whole, /*color=*/false, /*depth=*/false, /*ids=*/true);
    ASSERT_EQ(backend_->readBack(dest).ids, src.ids);

    const Rect rect{12, 10, 40, 12};
    backend_->clear(dest, rect, kBackground, 1.0f);
    Buffers b = backend_->readBack(dest);
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const bool inside = x >= rect.x && x < rect.x + rect.width && y >= rect.y && y < rect.y + rect.height;
            ASSERT_EQ(b.ids[at(b, x, y)], inside ? 0u : src.ids[at(src, x, y)]) << x << ", " << y;
        }
    }
    backend_->clear(dest, whole, kBackground, 1.0f);
    drawFrontAndBack(*backend_, dest, mesh, false);
    b = backend_->readBack(dest);
    EXPECT_TRUE(allIdsZero(b));
    EXPECT_TRUE(identical(b, src, "copied-ids-then-cleared", /*compareIds=*/false));

    // Colour and depth copied from a target with ids bring no ids along.
    backend_->clear(dest, whole, kBackground, 1.0f);
    backend_->copy(source, dest, whole, /*color=*/true, /*depth=*/true, /*ids=*/false);
    EXPECT_TRUE(allIdsZero(backend_->readBack(dest)));
    backend_->destroyTarget(source);
    backend_->destroyTarget(dest);
}

// --- Program variants (texture, vertex colours, ids): uniforms are per program, so each variant
// must get the current values even when another variant was given them last.

TEST_P(GlBackendGLTest, EachProgramVariantGetsTheCurrentUniforms) {
    Mesh plain = randomMesh(40);
    plain.colors.clear();
    const Mesh colored = randomMesh(40);
    const Texture texture = checkerTexture();
    FrameParams frameA;
    frameA.view = glm::lookAt(glm::vec3(0.3f, 0.4f, 2.6f), glm::vec3(0.0f), glm::vec3(0, 1, 0));
    frameA.projection = glm::perspective(0.9f, float(kWidth) / kHeight, 0.5f, 10.0f);
    FrameParams frameB = frameA;
    frameB.lighting.toLight = glm::normalize(glm::vec3(-0.5f, 0.2f, 1.0f));
    frameB.lighting.environment = 0.2f;
    frameB.lighting.light = 2.5f;
    frameB.view = glm::lookAt(glm::vec3(-0.5f, 0.1f, 2.4f), glm::vec3(0.0f), glm::vec3(0, 1, 0));
    const glm::mat4 modelA = glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(0, 1, 0));
    const glm::mat4 modelB = glm::rotate(glm::mat4(1.0f), -0.7f, glm::vec3(1, 0, 0));

    // Every variant: textured or not, coloured or not, with and without ids, lit or unlit.
    struct Draw {
        bool textured, coloured, ids, unlit;
    };
    std::vector<Draw> variants;
    for (int v = 0; v < 16; ++v) variants.push_back({(v & 1) != 0, (v & 2) != 0, (v & 4) != 0, (v & 8) != 0});

    // One frame with the given variant, model, factor and frame parameters.
    struct Handles {
        MeshHandle plain, colored;
        TextureHandle texture;
        TargetHandle target;
    };
    const auto upload = [&](Backend& backend) {
        return Handles{backend.uploadMesh(plain), backend.uploadMesh(colored), backend.uploadTexture(texture),
                       backend.createTarget(kWidth, kHeight)};
    };
    const auto render = [&](Backend& backend, const Handles& h, const Draw& d, const FrameParams& base,
                            const glm::mat4& model, const glm::vec4& factor, std::uint32_t firstId) {
        backend.clear(h.target, Rect{0, 0, kWidth, kHeight}, kBackground, 1.0f);
        FrameParams frame = base;
        frame.writeIds = d.ids;
        backend.beginFrame(h.target, frame);
        DrawParams params;
        params.mesh = d.coloured ? h.colored : h.plain;
        params.texture = d.textured ? h.texture : kNoHandle;
        params.model = model;
        params.baseColorFactor = factor;
        params.metallic = factor.r;
        params.roughness = factor.g;
        params.unlit = d.unlit;
        params.firstId = firstId;
        backend.draw(params, all(plain));
        return backend.readBack(h.target);
    };

    // The test's backend draws every variant with (A, factor A, id 1) first, then with (B, factor B,
    // id 500), each after another variant had B; a fresh backend per variant draws its B frame alone.
    const Handles h = upload(*backend_);
    const glm::vec4 factorA{1.0f, 0.9f, 0.8f, 1.0f}, factorB{0.5f, 0.7f, 1.0f, 1.0f};
    for (const Draw& d : variants) render(*backend_, h, d, frameA, modelA, factorA, 1);
    std::vector<Buffers> afterOthers;
    for (const Draw& d : variants) afterOthers.push_back(render(*backend_, h, d, frameB, modelB, factorB, 500));
    for (std::size_t i = 0; i < variants.size(); ++i) {
        const Draw& d = variants[i];
        const std::string name =
            std::string("variant-") + (d.textured ? "t" : "") + (d.coloured ? "c" : "") + (d.ids ? "i" : "") +
            (d.unlit ? "u" : "");
        std::unique_ptr<Backend> fresh = makeBackend(GetParam());
        ASSERT_NE(fresh, nullptr);
        const Buffers alone = render(*fresh, upload(*fresh), d, frameB, modelB, factorB, 500);
        EXPECT_GT(std::count_if(alone.depth.begin(), alone.depth.end(), [](std::uint32_t z) { return z != kDepthMax; }),
                  kWidth * kHeight / 4)
            << name;
        EXPECT_TRUE(identical(afterOthers[i], alone, name));
    }
}

// A 1×1 texture of `rgba`, uploaded.
TextureHandle uploadTexel(Backend& backend, std::vector<std::uint8_t> rgba, bool srgb) {
    Texture t;
    t.width = t.height = 1;
    t.rgba = std::move(rgba);
    t.srgb = srgb;
    const TextureHandle handle = backend.uploadTexture(t);
    EXPECT_NE(handle, kNoHandle);
    return handle;
}

// Each map scales what glTF says it scales, read from a 1×1 texture (so every pixel samples the one
// texel): metallic × blue and roughness × green, the environment's light × the occlusion's red at
// its strength, emission × the emissive map's decoded rgb.
TEST_P(GlBackendGLTest, MapsScaleTheFactorsAsGltfReadsThem) {
    Backend* backend = backend_.get();
    const auto texel = [&](std::uint8_t r, std::uint8_t g, std::uint8_t b, bool srgb) {
        return uploadTexel(*backend, {r, g, b, 255}, srgb);
    };
    const TextureHandle mr = texel(0, 64, 191, false), occlusion = texel(0, 0, 0, false),
                        emissive = texel(255, 0, 0, true);
    const Mesh quad = frontAndBack();
    const MeshHandle mesh = backend->uploadMesh(quad);
    const TargetHandle target = backend->createTarget(kWidth, kHeight);
    const auto drawn = [&](const DrawParams& material) {
        backend->clear(target, Rect{0, 0, kWidth, kHeight}, glm::vec4(0.0f), 1.0f);
        backend->beginFrame(target, simpleFrame(false));
        DrawParams params = material;
        params.mesh = mesh;
        params.baseColorFactor = kFactor;
        backend->draw(params, all(quad));
        return backend->readBack(target);
    };
    const double unorm = 1.0 / 255.0;
    test::ShadedMaterial expected{glm::dvec3(kFactor), 191 * unorm, 64 * unorm};
    DrawParams params;
    params.metallicRoughnessTexture = mr;
    EXPECT_TRUE(colorIs(drawn(params), kFrontX, kCentroidY, shadedAt(kFrontX, kCentroidY, 0.5f, {0, 0, 1}, expected)));

    params = {};
    params.metallic = 0.25f;
    params.roughness = 0.5f;
    params.occlusionTexture = occlusion;
    for (const float strength : {0.0f, 0.5f, 1.0f}) {
        params.occlusionStrength = strength;
        expected = {glm::dvec3(kFactor), 0.25, 0.5, glm::dvec3(0.0), 1.0 - double(strength)};
        const glm::vec4 want = shadedAt(kFrontX, kCentroidY, 0.5f, {0, 0, 1}, expected);
        EXPECT_TRUE(colorIs(drawn(params), kFrontX, kCentroidY, want)) << "occlusion strength " << strength;
    }

    params = {};
    params.emissive = {0.5f, 0.5f, 0.5f};
    params.emissiveTexture = emissive;
    expected = {glm::dvec3(kFactor), 1.0, 1.0, glm::dvec3(0.5, 0.0, 0.0)};
    EXPECT_TRUE(colorIs(drawn(params), kFrontX, kCentroidY, shadedAt(kFrontX, kCentroidY, 0.5f, {0, 0, 1}, expected)));
    params.unlit = true;  // unlit ignores the maps: the base colour as it is
    EXPECT_TRUE(colorIs(drawn(params), kFrontX, kCentroidY,
                        glm::vec4(glm::vec3(test::displayedRgb(glm::dvec3(kFactor))), 1.0f)));
    backend->destroyTarget(target);
}

// A normal map's texel is a normal in the basis (tangent, bitangent = cross(normal, tangent) · w,
// normal): here tangent +x, so bitangent +y for w = 1 and −y for w = −1; its x and y scaled.
TEST_P(GlBackendGLTest, NormalMapsTurnTheNormalInTheTangentBasis) {
    Backend* backend = backend_.get();
    Texture t;
    t.width = t.height = 1;
    t.rgba = {255, 64, 160, 255};  // (1, −0.498, 0.255) after · 2 − 1
    t.srgb = false;
    const TextureHandle normalMap = backend->uploadTexture(t);
    ASSERT_NE(normalMap, kNoHandle);
    Mesh quad = frontAndBack();
    const TargetHandle target = backend->createTarget(kWidth, kHeight);
    for (const float w : {1.0f, -1.0f}) {
        quad.tangents.assign(quad.positions.size(), glm::vec4(1.0f, 0.0f, 0.0f, w));
        const MeshHandle mesh = backend->uploadMesh(quad);
        ASSERT_NE(mesh, kNoHandle);
        for (const float scale : {0.0f, 1.0f, 10.0f}) {
            backend->clear(target, Rect{0, 0, kWidth, kHeight}, glm::vec4(0.0f), 1.0f);
            backend->beginFrame(target, simpleFrame(false));
            DrawParams params;
            params.mesh = mesh;
            params.baseColorFactor = kFactor;
            params.metallic = 0.0f;
            params.roughness = 0.4f;
            params.normalTexture = normalMap;
            params.normalScale = scale;
            params.doubleSided = true;
            backend->draw(params, all(quad));
            const Buffers b = backend->readBack(target);
            const auto stored = [](double byte) { return byte / 255.0 * 2.0 - 1.0; };
            const glm::dvec3 m = glm::normalize(glm::dvec3(stored(255) * scale, stored(64) * scale, stored(160)));
            // Front: basis (+x, +y·w, +z); the back face flips all three.
            const glm::dvec3 front(m.x, m.y * w, m.z);
            const test::ShadedMaterial material{glm::dvec3(kFactor), 0.0, 0.4};
            const glm::vec4 frontColour = shadedAt(kFrontX, kCentroidY, 0.5f, glm::vec3(front), material);
            const glm::vec4 backColour = shadedAt(kBackX, kCentroidY, 0.5f, -glm::vec3(front), material);
            EXPECT_TRUE(colorIs(b, kFrontX, kCentroidY, frontColour)) << "front, w " << w << ", scale " << scale;
            EXPECT_TRUE(colorIs(b, kBackX, kCentroidY, backColour)) << "back, w " << w << ", scale " << scale;
        }
        backend->releaseMesh(mesh);
    }
    backend->destroyTarget(target);
}

// KHR_materials_clearcoat: a coat of factor × the coat map's red and roughness × its map's green
// over the material, its normal the coat normal map's in the tangent basis (or the surface's, and
// never the base normal map's), on front and back faces.
TEST_P(GlBackendGLTest, ClearCoatLiesOverTheMaterialWithItsOwnMapsAndNormal) {
    Backend* backend = backend_.get();
    const auto texel = [&](std::uint8_t r, std::uint8_t g, std::uint8_t b) {
        return uploadTexel(*backend, {r, g, b, 255}, false);
    };
    const TextureHandle coatMap = texel(128, 64, 0), normals = texel(255, 64, 160);
    Mesh quad = frontAndBack();
    quad.tangents.assign(quad.positions.size(), glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
    const MeshHandle mesh = backend->uploadMesh(quad);
    ASSERT_NE(mesh, kNoHandle);
    const TargetHandle target = backend->createTarget(kWidth, kHeight);
    const auto drawn = [&](DrawParams params) {
        backend->clear(target, Rect{0, 0, kWidth, kHeight}, glm::vec4(0.0f), 1.0f);
        backend->beginFrame(target, simpleFrame(false));
        params.mesh = mesh;
        params.baseColorFactor = kFactor;
        params.metallic = 0.5f;
        params.roughness = 0.6f;
        params.doubleSided = true;
        backend->draw(params, all(quad));
        return backend->readBack(target);
    };
    const double unorm = 1.0 / 255.0;
    const auto stored = [&](double byte) { return byte * unorm * 2.0 - 1.0; };
    const glm::dvec3 mapped = glm::normalize(glm::dvec3(stored(255) * 2.0, stored(64) * 2.0, stored(160)));
    const glm::dvec3 baseMapped = glm::normalize(glm::dvec3(stored(255), stored(64), stored(160)));
    struct Case {
        const char* what;
        float coat, roughness;
        TextureHandle coatTexture, roughnessTexture, normalTexture, baseNormal;
        double expectedCoat, expectedRoughness;
        glm::dvec3 coatNormal;  // in the tangent basis (+x, +y, +z); 0: the surface's
    };
    const Case cases[] = {
        {"smooth coat", 1.0f, 0.0f, kNoHandle, kNoHandle, kNoHandle, kNoHandle, 1.0, 0.0, {}},
        {"half a rough coat", 0.5f, 0.7f, kNoHandle, kNoHandle, kNoHandle, kNoHandle, 0.5, 0.7, {}},
        {"coat maps", 1.0f, 0.5f, coatMap, coatMap, kNoHandle, kNoHandle, 128 * unorm, 0.5 * 64 * unorm, {}},
        {"coat normal map", 1.0f, 0.1f, kNoHandle, kNoHandle, normals, kNoHandle, 1.0, 0.1, mapped},
        {"base normal map only", 1.0f, 0.1f, kNoHandle, kNoHandle, kNoHandle, normals, 1.0, 0.1, {}},
    };
    for (const Case& c : cases) {
        DrawParams params;
        params.clearcoat = c.coat;
        params.clearcoatRoughness = c.roughness;
        params.clearcoatTexture = c.coatTexture;
        params.clearcoatRoughnessTexture = c.roughnessTexture;
        params.clearcoatNormalTexture = c.normalTexture;
        params.clearcoatNormalScale = 2.0f;
        params.normalTexture = c.baseNormal;  // at scale 1
        const Buffers b = drawn(params);
        test::ShadedMaterial material{glm::dvec3(kFactor), 0.5, 0.6};
        material.coat = c.expectedCoat;
        material.coatRoughness = c.expectedRoughness;
        for (const bool front : {true, false}) {
            const double side = front ? 1.0 : -1.0;  // a back face flips the whole basis
            const glm::dvec3 surface(0.0, 0.0, side);
            const glm::dvec3 n = c.baseNormal != kNoHandle ? side * baseMapped : surface;
            material.coatNormal = c.coatNormal == glm::dvec3(0.0) ? surface : side * c.coatNormal;
            const int x = front ? kFrontX : kBackX;
            EXPECT_TRUE(colorIs(b, x, kCentroidY, shadedAt(x, kCentroidY, 0.5f, glm::vec3(n), material), 2))
                << c.what << (front ? ", front" : ", back");
        }
    }
    // A coat of 0 is none: the same bytes as no coat at all, its maps unread.
    DrawParams uncoated;
    DrawParams zero = uncoated;
    zero.clearcoatTexture = coatMap;
    zero.clearcoatNormalTexture = normals;
    EXPECT_EQ(drawn(zero).rgba, drawn(uncoated).rgba);
    backend->releaseMesh(mesh);
    backend->destroyTarget(target);
}

TEST_P(GlBackendGLTest, TexturedMeshWithoutUvsSamplesTheFirstTexel) {
    Texture tex;
    tex.width = 2;
    tex.height = 1;
    tex.filter = Filter::Nearest;
    tex.rgba = {255, 0, 0, 255, 0, 255, 0, 255};  // red at (0, 0), green beside it
    Mesh quad;
    quad.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    quad.normals.assign(4, glm::vec3(0, 0, 1));
    quad.indices = {0, 1, 2, 0, 2, 3};
    const Buffers b = drawUnlitTextured(*backend_, quad, tex, false);
    for (auto [x, y] : {std::pair{1, 1}, std::pair{62, 46}, std::pair{40, 10}})
        EXPECT_TRUE(colorIs(b, x, y, {1, 0, 0, 1}, 0)) << x << ", " << y;
}

std::string kindName(const ::testing::TestParamInfo<ContextKind>& info) {
    std::string name = contextKindName(info.param);
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
}

INSTANTIATE_TEST_SUITE_P(Contexts, GlBackendGLTest, ::testing::ValuesIn(availableContextKinds()), kindName);

// Same scene on every context kind: all run llvmpipe here, so the images must match byte for byte.
TEST(GlBackendCrossContextGLTest, AllContextKindsGiveIdenticalImages) {
    const std::vector<ContextKind> kinds = availableContextKinds();
    if (kinds.size() < 2) GTEST_SKIP() << "only one context kind in this build";
    std::vector<std::unique_ptr<Backend>> backends;
    for (ContextKind kind : kinds) backends.push_back(makeBackend(kind));
    for (const auto& b : backends) ASSERT_NE(b, nullptr);
    // Give each context different GL object names (i extra targets and textures), so a call that
    // reached the wrong context would touch the wrong objects instead of same-named twins.
    for (std::size_t i = 0; i < backends.size(); ++i) {
        for (std::size_t k = 0; k < i; ++k) {
            EXPECT_NE(backends[i]->createTarget(8, 8), kNoHandle);
            EXPECT_NE(backends[i]->uploadTexture(checkerTexture()), kNoHandle);
        }
    }
    // Render in turn, twice round, so the backends switch contexts between frames.
    std::vector<Buffers> images;
    for (int round = 0; round < 2; ++round)
        for (auto& backend : backends) images.push_back(renderDenseScene(*backend, true));
    for (std::size_t i = 1; i < images.size(); ++i)
        EXPECT_TRUE(identical(
            images[0], images[i],
            std::string("cross-") + contextKindName(kinds[0]) + "-vs-" + contextKindName(kinds[i % kinds.size()])));
    const Buffers simpleFirst = drawTwoTriangles(*backends.front(), true, true);
    for (std::size_t i = 1; i < backends.size(); ++i)
        EXPECT_TRUE(identical(simpleFirst, drawTwoTriangles(*backends[i], true, true),
                              std::string("cross-simple-") + contextKindName(kinds[i])));
    // Destroying one backend (its context not current) leaves the others working.
    backends.front().reset();
    for (std::size_t i = 1; i < backends.size(); ++i)
        EXPECT_TRUE(identical(images[0], renderDenseScene(*backends[i], true),
                              std::string("cross-after-destroy-") + contextKindName(kinds[i])));
}

// Two surfaceless contexts share one EGLDisplay; destroying one must not break the other.
TEST(GlBackendCrossContextGLTest, SurfacelessContextsShareTheDisplaySafely) {
    const auto kinds = availableContextKinds();
    if (std::find(kinds.begin(), kinds.end(), ContextKind::EglSurfaceless) == kinds.end())
        GTEST_SKIP() << "EGL not built";
    auto first = makeBackend(ContextKind::EglSurfaceless);
    auto second = makeBackend(ContextKind::EglSurfaceless);
    ASSERT_TRUE(first && second);
    const Buffers before = renderDenseScene(*second, true);
    first.reset();
    EXPECT_TRUE(identical(before, renderDenseScene(*second, true), "surfaceless-after-destroy"));
    second.reset();
    // And the display comes back after the last one went.
    auto third = makeBackend(ContextKind::EglSurfaceless);
    ASSERT_TRUE(third);
    EXPECT_TRUE(identical(before, renderDenseScene(*third, true), "surfaceless-recreated"));
}

}  // namespace
}  // namespace frugal
