// Extents (src/reuse/Extents.h) against what the software rasterizer really covers: single triangles
// drawn with ids at small sizes, and every pixel carrying a triangle's id must lie inside that
// triangle's extent. Random, thin, sub-pixel, tiny and huge triangles; triangles crossing the near
// plane (all w > 0, or a vertex behind the eye), outside one plane, with a NaN or an infinite
// vertex; a 1×1 viewport; an orthographic projection. Extents must also stay tight for ordinary
// triangles (a few pixels around what is covered), or reuse would redraw everything.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "TestSupport.h"
#include "pipeline/SceneRenderer.h"
#include "reuse/Extents.h"
#include "software/SoftwareBackend.h"

namespace frugal::test {
namespace {

using reuse::Box;
using reuse::ExtentBuilder;

const glm::vec4 kBackground{0.0f, 0.0f, 0.0f, 1.0f};

std::string str(const Box& b) {
    std::ostringstream out;
    out << "[" << b.x0 << "," << b.x1 << ")x[" << b.y0 << "," << b.y1 << ")";
    return out.str();
}

std::string str(const glm::vec3& p) {
    std::ostringstream out;
    out.precision(9);
    out << "(" << p.x << ", " << p.y << ", " << p.z << ")";
    return out.str();
}

struct Coverage {
    Box box;                // bounding box of the covered pixels
    std::size_t pixels = 0; // covered pixels
    std::size_t outside = 0;  // of those, outside the extent
    std::string first;        // the first one outside
};

// One mesh holding every triangle of a test (3 vertices each, in order, double-sided so that both
// windings draw), uploaded once to a software backend; each triangle is then drawn alone with ids.
class Probe {
public:
    Probe(const std::vector<glm::vec3>& positions, int width, int height, const glm::mat4& projection,
          const glm::mat4& view = glm::mat4(1.0f))
        : width_(width), height_(height), builder_(width, height) {
        Mesh mesh = looseTriangles(positions);
        Material material;
        material.doubleSided = true;
        scene_ = oneMeshScene(std::move(mesh), material);
        params_.view = view;
        params_.projection = projection;
        params_.writeIds = true;
        world_ = scene_.worldTransforms(0.0);
        backend_ = makeSoftwareBackend();
        target_ = backend_->createTarget(width, height);
        EXPECT_NE(target_, kNoHandle);
        Result<SceneRenderer> made = SceneRenderer::create(*backend_, scene_);
        EXPECT_TRUE(made) << (made ? "" : made.error().message);
        if (made) renderer_.emplace(std::move(*made));
        // As TemporalReuse does: view-projection × world, in float with glm.
        builder_.project(projection * view * world_[0], scene_.meshes[0].positions);
    }
    ~Probe() {
        renderer_.reset();
        if (target_ != kNoHandle) backend_->destroyTarget(target_);
    }
    Probe(const Probe&) = delete;
    Probe& operator=(const Probe&) = delete;

    std::uint32_t triangles() const { return std::uint32_t(scene_.meshes[0].triangleCount()); }
    Box extent(std::uint32_t t) const { return builder_.triangle(3 * t, 3 * t + 1, 3 * t + 2); }
    const ExtentBuilder& builder() const { return builder_; }

    // Draws triangle t alone (or triangles [t, t + count)) and compares its pixels with `extent`.
    Coverage cover(std::uint32_t t, const Box& extent, std::uint32_t count = 1) {
        Coverage c;
        if (!renderer_ || target_ == kNoHandle) return c;
        const DrawList list{{0, {{t, count}}}};
        renderer_->renderFrame(target_, width_, height_, params_, world_, kBackground, list);
        const Buffers buffers = backend_->readBack(target_);
        for (int y = 0; y < height_; ++y)
            for (int x = 0; x < width_; ++x) {
                const std::uint32_t id = buffers.ids[std::size_t(y) * std::size_t(width_) + std::size_t(x)];
                if (id == 0) continue;
                EXPECT_GE(id, t + 1);
                EXPECT_LT(id, t + 1 + count);
                ++c.pixels;
                c.box.add(Box{x, y, x + 1, y + 1});
                const bool inside = x >= extent.x0 && x < extent.x1 && y >= extent.y0 && y < extent.y1;
                if (!inside && c.outside++ == 0) c.first = "(" + std::to_string(x) + ", " + std::to_string(y) + ")";
            }
        return c;
    }

    // Every triangle: its pixels inside its extent. Returns the coverage of each.
    std::vector<Coverage> checkAll(const std::string& label) {
        std::vector<Coverage> all;
        for (std::uint32_t t = 0; t < triangles(); ++t) {
            const Box e = extent(t);
            all.push_back(cover(t, e));
            const Coverage& c = all.back();
            EXPECT_EQ(c.outside, 0u) << label << ": triangle " << t << " " << describe(t) << " covers " << c.outside
                                     << " pixels outside its extent " << str(e) << ", first " << c.first
                                     << "; covered box " << str(c.box);
            // Extents are always inside the target.
            EXPECT_TRUE(e.empty() || (e.x0 >= 0 && e.y0 >= 0 && e.x1 <= width_ && e.y1 <= height_))
                << label << ": triangle " << t << " extent " << str(e);
        }
        return all;
    }

    std::string describe(std::uint32_t t) const {
        const std::vector<glm::vec3>& p = scene_.meshes[0].positions;
        return str(p[3 * t]) + " " + str(p[3 * t + 1]) + " " + str(p[3 * t + 2]);
    }

    int width() const { return width_; }
    int height() const { return height_; }

private:
    int width_, height_;
    Scene scene_;
    FrameParams params_;
    std::vector<glm::mat4> world_;
    std::unique_ptr<Backend> backend_;
    TargetHandle target_ = kNoHandle;
    std::optional<SceneRenderer> renderer_;
    ExtentBuilder builder_;
};

constexpr int kW = 64, kH = 48;

glm::mat4 perspective(int w = kW, int h = kH, float zfar = 10.0f) {
    return glm::perspective(glm::radians(60.0f), float(w) / float(h), 0.1f, zfar);
}

// Window coordinates = eye coordinates (x, y), z in (-1, 1) visible: drawing in pixels.
glm::mat4 pixelOrtho(int w = kW, int h = kH) { return glm::ortho(0.0f, float(w), 0.0f, float(h), -1.0f, 1.0f); }

// Random eye-space triangles around (and beyond) the frustum of perspective(): some cross the
// near or far plane, some leave the sides, all with w > 0 unless `behind`.
std::vector<glm::vec3> randomEyeTriangles(unsigned seed, int count, float zmin, float zmax) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> z(zmin, zmax), s(-1.3f, 1.3f), jitter(-0.8f, 0.8f);
    std::vector<glm::vec3> p;
    for (int t = 0; t < count; ++t) {
        // Mostly small to medium triangles: a centre plus offsets.
        const float cz = z(rng);
        const glm::vec3 centre(s(rng) * std::abs(cz) * 0.6f, s(rng) * std::abs(cz) * 0.45f, cz);
        const float size = std::abs(cz) * (t % 3 == 0 ? 0.6f : 0.15f);
        for (int k = 0; k < 3; ++k) {
            glm::vec3 v = centre + size * glm::vec3(jitter(rng), jitter(rng), jitter(rng));
            v.z = std::min(v.z, -1e-4f);  // w > 0
            p.push_back(v);
        }
    }
    return p;
}

TEST(ReuseExtents, RandomTrianglesContainTheirPixels) {
    Probe probe(randomEyeTriangles(1, 2000, -12.0f, -0.05f), kW, kH, perspective());
    const std::vector<Coverage> all = probe.checkAll("random perspective");
    std::size_t covering = 0;
    for (const Coverage& c : all) covering += c.pixels > 0 ? 1 : 0;
    EXPECT_GT(covering, 1000u) << "the sample must mostly be visible triangles to prove anything";

}

TEST(ReuseExtents, OrthographicTrianglesContainTheirPixels) {
    // Eye z from in front of the near plane to beyond the far one: clipped by both.
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> x(-2.6f, 2.6f), y(-2.0f, 2.0f), z(-10.0f, 1.0f), d(-0.7f, 0.7f);
    std::vector<glm::vec3> p;
    for (int t = 0; t < 1000; ++t) {
        const glm::vec3 c(x(rng), y(rng), z(rng));
        const float size = t % 4 == 0 ? 3.0f : 1.0f;
        for (int k = 0; k < 3; ++k) p.push_back(c + size * glm::vec3(d(rng), d(rng), 4.0f * d(rng)));
    }
    Probe probe(p, kW, kH, glm::ortho(-2.0f, 2.0f, -1.5f, 1.5f, 0.5f, 8.0f));
    const std::vector<Coverage> all = probe.checkAll("orthographic");
    std::size_t covering = 0;
    for (const Coverage& c : all) covering += c.pixels > 0 ? 1 : 0;
    EXPECT_GT(covering, 300u);
}

TEST(ReuseExtents, ThinAndSubPixelTrianglesContainTheirPixels) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> px(-2.0f, float(kW) + 2.0f), py(-2.0f, float(kH) + 2.0f), angle(0.0f, 6.2831853f),
        length(2.0f, 70.0f), width(0.001f, 0.6f), unit(0.0f, 1.0f);
    std::vector<glm::vec3> p;
    for (int t = 0; t < 500; ++t) {  // slivers: long, at any angle, less than a pixel wide
        const glm::vec3 a(px(rng), py(rng), 0.0f);
        const float phi = angle(rng), len = length(rng), w = width(rng);
        const glm::vec3 dir(std::cos(phi), std::sin(phi), 0.0f), normal(-dir.y, dir.x, 0.0f);
        p.insert(p.end(), {a, a + len * dir, a + unit(rng) * len * dir + w * normal});
    }
    for (int t = 0; t < 500; ++t) {  // sub-pixel: inside one pixel, often around its centre
        const glm::vec3 c(std::floor(px(rng)) + (t % 2 ? 0.5f : unit(rng)), std::floor(py(rng)) + (t % 2 ? 0.5f : unit(rng)), 0.0f);
        for (int k = 0; k < 3; ++k) p.push_back(c + glm::vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, 0.0f));
    }
    for (int t = 0; t < 500; ++t) {  // on the 1/256 sub-pixel grid, on pixel centres and edges
        for (int k = 0; k < 3; ++k) {
            const float gx = std::round(px(rng) * 2.0f) / 2.0f + float(int(unit(rng) * 3.0f)) / 256.0f;
            const float gy = std::round(py(rng) * 2.0f) / 2.0f + float(int(unit(rng) * 3.0f)) / 256.0f;
            p.push_back({gx * (t % 5 == 0 ? 0.2f : 1.0f), gy, 0.0f});
        }
    }
    Probe probe(p, kW, kH, pixelOrtho());
    const std::vector<Coverage> all = probe.checkAll("thin and sub-pixel");
    std::size_t covering = 0;
    for (const Coverage& c : all) covering += c.pixels > 0 ? 1 : 0;
    EXPECT_GT(covering, 500u);
}

TEST(ReuseExtents, TinyTrianglesGetTinyExtents) {
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> px(0.0f, float(kW)), py(0.0f, float(kH)), unit(-1.0f, 1.0f);
    std::vector<glm::vec3> p;
    for (int t = 0; t < 200; ++t) {
        const float size = std::pow(10.0f, -1.0f - float(t % 6));  // 0.1 .. 1e-6 pixels
        // Half of them around a pixel centre, where a tiny triangle can still cover one pixel.
        const glm::vec3 c = t % 2 ? glm::vec3(std::floor(px(rng)) + 0.5f, std::floor(py(rng)) + 0.5f, 0.0f)
                                  : glm::vec3(px(rng), py(rng), 0.0f);
        for (int k = 0; k < 3; ++k) p.push_back(c + size * glm::vec3(unit(rng), unit(rng), 0.0f));
    }
    Probe probe(p, kW, kH, pixelOrtho());
    const std::vector<Coverage> all = probe.checkAll("tiny");
    for (std::uint32_t t = 0; t < probe.triangles(); ++t) {
        const Box e = probe.extent(t);
        EXPECT_LE(e.x1 - e.x0, 4) << "triangle " << t << " " << str(e);
        EXPECT_LE(e.y1 - e.y0, 4) << "triangle " << t << " " << str(e);
        EXPECT_LE(all[t].pixels, 1u);
    }
}

TEST(ReuseExtents, NearPlaneCrossingWithPositiveWStaysBounded) {
    // One or two vertices between the eye and the near plane (0 < w < 0.1), the others beyond it.
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> nearZ(-0.099f, -0.001f), farZ(-6.0f, -0.2f), s(-1.0f, 1.0f);
    std::vector<glm::vec3> p;
    for (int t = 0; t < 800; ++t) {
        for (int k = 0; k < 3; ++k) {
            const bool close = k == 0 || (k == 1 && t % 2 == 0);
            const float z = close ? nearZ(rng) : farZ(rng);
            p.push_back({s(rng) * std::abs(z) * 0.8f, s(rng) * std::abs(z) * 0.6f, z});
        }
    }
    // A designed one: its close vertex projects near the centre, so the extent is small.
    p.insert(p.end(), {{0.001f, 0.001f, -0.05f}, {0.3f, 0.0f, -2.0f}, {0.0f, 0.3f, -2.0f}});
    Probe probe(p, kW, kH, perspective());
    const std::vector<Coverage> all = probe.checkAll("near plane, w > 0");
    const std::uint32_t last = probe.triangles() - 1;
    const Box e = probe.extent(last);
    EXPECT_FALSE(e == probe.builder().screen()) << "every w > 0: the extent is bounded, " << str(e);
    EXPECT_LT(e.area(), std::int64_t(kW) * kH / 4) << str(e);
    EXPECT_GT(all[last].pixels, 0u) << "the designed triangle is visible";
    std::size_t covering = 0;
    for (const Coverage& c : all) covering += c.pixels > 0 ? 1 : 0;
    EXPECT_GT(covering, 200u);
}

TEST(ReuseExtents, AVertexAtOrBehindTheEyeMeansTheWholeScreen) {
    std::vector<glm::vec3> p = {
        {0.0f, 0.0f, 1.0f},  {0.5f, 0.2f, -2.0f}, {-0.4f, 0.3f, -3.0f},   // one vertex behind (w < 0)
        {0.3f, 0.3f, 0.5f},  {-0.3f, 0.2f, 2.0f}, {0.1f, -0.3f, -1.0f},   // two behind
        {0.2f, 0.1f, 0.0f},  {0.5f, 0.2f, -2.0f}, {-0.4f, 0.3f, -3.0f},   // w == 0 exactly
        {5.0f, 0.0f, 1.0f},  {0.2f, 0.1f, -2.0f}, {0.3f, -0.1f, -2.0f},   // behind and far to the side
    };
    std::mt19937 rng(6);
    std::uniform_real_distribution<float> s(-2.0f, 2.0f), behind(0.01f, 3.0f), front(-5.0f, -0.2f);
    for (int t = 0; t < 100; ++t)
        for (int k = 0; k < 3; ++k) p.push_back({s(rng), s(rng), k == t % 3 ? behind(rng) : front(rng)});
    Probe probe(p, kW, kH, perspective());
    const std::vector<Coverage> all = probe.checkAll("behind the eye");
    // The designed ones: the whole screen.
    for (std::uint32_t t = 0; t < 4; ++t)
        EXPECT_TRUE(probe.extent(t) == probe.builder().screen()) << "triangle " << t << ": " << str(probe.extent(t));
    // The random ones: the whole screen, or empty when all three vertices lie outside one clip
    // plane (homogeneous clipping is linear, so such a triangle is invisible even with w < 0).
    std::size_t whole = 0;
    for (std::uint32_t t = 4; t < probe.triangles(); ++t) {
        const Box e = probe.extent(t);
        EXPECT_TRUE(e == probe.builder().screen() || e.empty()) << "triangle " << t << ": " << str(e);
        if (e.empty()) {
            EXPECT_EQ(all[t].pixels, 0u) << "triangle " << t;
        }
        whole += e == probe.builder().screen() ? 1 : 0;
    }
    EXPECT_GT(whole, 30u);
}

TEST(ReuseExtents, OutsideOnePlaneIsEmptyAndDrawsNothing) {
    const std::vector<glm::vec3> p = {
        {5.0f, 0.0f, -2.0f},    {6.0f, 1.0f, -2.0f},    {7.0f, -1.0f, -3.0f},    // right of the frustum
        {-5.0f, 0.0f, -2.0f},   {-6.0f, 1.0f, -2.0f},   {-7.0f, -1.0f, -3.0f},   // left
        {0.0f, 4.0f, -2.0f},    {1.0f, 5.0f, -2.0f},    {-1.0f, 6.0f, -3.0f},    // above
        {0.0f, -4.0f, -2.0f},   {1.0f, -5.0f, -2.0f},   {-1.0f, -6.0f, -3.0f},   // below
        {0.0f, 0.0f, -20.0f},   {5.0f, 0.0f, -30.0f},   {0.0f, 5.0f, -25.0f},    // beyond the far plane
        {0.0f, 0.0f, -0.05f},   {0.01f, 0.0f, -0.05f},  {0.0f, 0.01f, -0.09f},   // between eye and near plane
        {0.0f, 0.0f, 1.0f},     {1.0f, 0.0f, 2.0f},     {0.0f, 1.0f, 3.0f},      // all behind the eye
        {3.0f, 3.0f, -1.0f},    {300.0f, 0.5f, -1.0f},  {4.0f, -0.5f, -1.0f},    // right, one vertex huge
    };
    Probe probe(p, kW, kH, perspective());
    const std::vector<Coverage> all = probe.checkAll("outside one plane");
    for (std::uint32_t t = 0; t < probe.triangles(); ++t) {
        EXPECT_TRUE(probe.extent(t).empty()) << "triangle " << t << " " << probe.describe(t) << ": " << str(probe.extent(t));
        EXPECT_EQ(all[t].pixels, 0u) << "triangle " << t;
    }
}

TEST(ReuseExtents, NotANumberOrInfiniteVertexMeansTheWholeScreen) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const std::vector<glm::vec3> p = {
        {nan, 0.0f, -2.0f},   {0.5f, 0.2f, -2.0f},  {-0.4f, 0.3f, -3.0f},
        {0.0f, 0.0f, nan},    {0.5f, 0.2f, -2.0f},  {-0.4f, 0.3f, -3.0f},
        {nan, nan, nan},      {nan, nan, nan},      {nan, nan, nan},
        {inf, 0.0f, -2.0f},   {0.5f, 0.2f, -2.0f},  {-0.4f, 0.3f, -3.0f},
        {0.0f, -inf, -2.0f},  {0.5f, 0.2f, -2.0f},  {-0.4f, 0.3f, -3.0f},
        {0.0f, 0.0f, -inf},   {0.5f, 0.2f, -2.0f},  {-0.4f, 0.3f, -3.0f},
        {nan, 0.0f, -2.0f},   {50.0f, 0.2f, -2.0f}, {60.0f, 0.3f, -3.0f},  // NaN with the rest off to the right
    };
    Probe probe(p, kW, kH, perspective());
    probe.checkAll("non-finite");
    for (std::uint32_t t = 0; t < probe.triangles(); ++t)
        EXPECT_TRUE(probe.extent(t) == probe.builder().screen()) << "triangle " << t << ": " << str(probe.extent(t));
    // A NaN in the matrix, not in the positions, is the same.
    ExtentBuilder builder(kW, kH);
    glm::mat4 mvp = perspective();
    mvp[3][0] = nan;
    const std::vector<glm::vec3> one = {{0.0f, 0.0f, -2.0f}, {0.1f, 0.0f, -2.0f}, {0.0f, 0.1f, -2.0f}};
    builder.project(mvp, one);
    EXPECT_TRUE(builder.triangle(0, 1, 2) == builder.screen());
}

TEST(ReuseExtents, HugeCoordinatesContainTheirPixels) {
    std::vector<glm::vec3> p;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> s(-1.0f, 1.0f), z(-6.0f, -0.5f);
    for (int e = 6; e <= 20; e += 2) {
        const float big = std::pow(10.0f, float(e));
        // Huge in x / y at ordinary depth: big triangles crossing the screen, or half-planes.
        p.insert(p.end(), {{big, 0.0f, -3.0f}, {-big, big, -3.0f}, {0.0f, -big, -3.0f}});
        p.insert(p.end(), {{0.0f, 0.0f, -2.0f}, {big, 0.3f, -2.0f}, {0.3f, big, -3.0f}});
        p.insert(p.end(), {{-0.5f, -0.2f, -2.0f}, {big, -big, -2.5f}, {0.4f, 0.3f, -2.0f}});
        // Huge along the view: far beyond the far plane, crossing it.
        p.insert(p.end(), {{0.0f, 0.0f, -big}, {0.5f, 0.1f, -2.0f}, {-0.5f, 0.2f, -3.0f}});
        p.insert(p.end(), {{big, big, -big}, {0.5f, 0.1f, -2.0f}, {-0.5f, 0.2f, -3.0f}});
        // Random directions scaled by `big`, with one ordinary vertex.
        for (int t = 0; t < 60; ++t)
            p.insert(p.end(), {{s(rng) * big, s(rng) * big, z(rng) * (t % 2 ? big : 1.0f)},
                               {s(rng) * big, s(rng), z(rng)},
                               {s(rng), s(rng), z(rng)}});
    }
    Probe probe(p, kW, kH, perspective(kW, kH, 1e30f));
    const std::vector<Coverage> all = probe.checkAll("huge");
    std::size_t covering = 0;
    for (const Coverage& c : all) covering += c.pixels > 0 ? 1 : 0;
    EXPECT_GT(covering, 20u);
}

TEST(ReuseExtents, OneByOneViewport) {
    std::vector<glm::vec3> p = randomEyeTriangles(8, 200, -6.0f, -0.05f);
    // Triangles around the only pixel's centre, sub-pixel and large.
    p.insert(p.end(), {{-0.01f, -0.01f, -1.0f}, {0.01f, -0.01f, -1.0f}, {0.0f, 0.01f, -1.0f}});
    p.insert(p.end(), {{-2.0f, -2.0f, -1.0f}, {2.0f, -2.0f, -1.0f}, {0.0f, 2.0f, -1.0f}});
    p.insert(p.end(), {{0.1f, 0.1f, -1.0f}, {2.0f, 0.1f, -1.0f}, {0.1f, 2.0f, -1.0f}});  // misses the centre
    Probe probe(p, 1, 1, perspective(1, 1));
    const std::vector<Coverage> all = probe.checkAll("1x1");
    std::size_t covering = 0;
    for (const Coverage& c : all) covering += c.pixels > 0 ? 1 : 0;
    EXPECT_GE(covering, 3u);
    EXPECT_EQ(all[probe.triangles() - 2].pixels, 1u);
    EXPECT_TRUE(probe.extent(probe.triangles() - 2) == (Box{0, 0, 1, 1}));
}

// Window coordinates of an eye-space point under `projection`, in double; nullopt when w ≤ 0.
std::optional<glm::dvec2> window(const glm::mat4& projection, const glm::vec3& eye, int w, int h) {
    const glm::dvec4 c = glm::dmat4(projection) * glm::dvec4(glm::dvec3(eye), 1.0);
    if (!(c.w > 0.0)) return std::nullopt;
    return glm::dvec2((c.x / c.w + 1.0) * 0.5 * w, (c.y / c.w + 1.0) * 0.5 * h);
}

TEST(ReuseExtents, OrdinaryTrianglesAreTight) {
    // Inside the viewport and between the near and far planes: the extent is the projected
    // vertices' box grown by at most 2 pixels a side.
    const glm::mat4 projection = perspective();
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> z(-8.0f, -0.5f), s(-0.5f, 0.5f), d(-0.3f, 0.3f);
    std::vector<glm::vec3> p;
    while (p.size() < 3 * 1000) {
        const float cz = z(rng);
        const glm::vec3 c(s(rng) * std::abs(cz), s(rng) * std::abs(cz) * 0.7f, cz);
        glm::vec3 v[3];
        bool inside = true;
        for (glm::vec3& vertex : v) {
            vertex = c + std::abs(cz) * glm::vec3(d(rng), d(rng), 0.2f * d(rng));
            const std::optional<glm::dvec2> win = window(projection, vertex, kW, kH);
            inside = inside && win && win->x > 0.0 && win->x < kW && win->y > 0.0 && win->y < kH && vertex.z < -0.2f &&
                     vertex.z > -9.5f;
        }
        if (inside) p.insert(p.end(), {v[0], v[1], v[2]});
    }
    Probe probe(p, kW, kH, projection);
    probe.checkAll("tight");
    for (std::uint32_t t = 0; t < probe.triangles(); ++t) {
        glm::dvec2 lo(1e9), hi(-1e9);
        for (int k = 0; k < 3; ++k) {
            const glm::dvec2 win = *window(projection, p[3 * t + std::uint32_t(k)], kW, kH);
            lo = glm::min(lo, win);
            hi = glm::max(hi, win);
        }
        const Box e = probe.extent(t);
        EXPECT_GE(e.x0, int(std::floor(lo.x)) - 2) << "triangle " << t << " " << str(e);
        EXPECT_GE(e.y0, int(std::floor(lo.y)) - 2) << "triangle " << t << " " << str(e);
        EXPECT_LE(e.x1, int(std::ceil(hi.x)) + 2) << "triangle " << t << " " << str(e);
        EXPECT_LE(e.y1, int(std::ceil(hi.y)) + 2) << "triangle " << t << " " << str(e);
    }
}

TEST(ReuseExtents, RectanglesAreAtMostTwoPixelsLooserThanTheirPixels) {
    // Axis-aligned rectangles (two triangles) of at least 2×2 pixels anywhere in the target: the
    // union of the two extents against the box of the pixels the rectangle covers.
    std::mt19937 rng(10);
    std::uniform_real_distribution<float> x(-1.0f, float(kW) - 2.0f), y(-1.0f, float(kH) - 2.0f), size(2.0f, 30.0f);
    std::vector<glm::vec3> p;
    for (int r = 0; r < 500; ++r) {
        const float x0 = x(rng), y0 = y(rng), x1 = x0 + size(rng), y1 = y0 + size(rng);
        p.insert(p.end(), {{x0, y0, 0.0f}, {x1, y0, 0.0f}, {x1, y1, 0.0f}, {x0, y0, 0.0f}, {x1, y1, 0.0f}, {x0, y1, 0.0f}});
    }
    Probe probe(p, kW, kH, pixelOrtho());
    for (std::uint32_t r = 0; r < probe.triangles() / 2; ++r) {
        Box e = probe.extent(2 * r);
        e.add(probe.extent(2 * r + 1));
        const Coverage c = probe.cover(2 * r, e, 2);
        ASSERT_GT(c.pixels, 0u) << "rectangle " << r;
        EXPECT_EQ(c.outside, 0u) << "rectangle " << r << " " << str(e) << " covered " << str(c.box);
        // Clipped to the target, both sides are; the slack is what remains.
        EXPECT_LE(c.box.x0 - e.x0, 2) << "rectangle " << r << " " << str(e) << " covered " << str(c.box);
        EXPECT_LE(c.box.y0 - e.y0, 2) << "rectangle " << r << " " << str(e) << " covered " << str(c.box);
        EXPECT_LE(e.x1 - c.box.x1, 2) << "rectangle " << r << " " << str(e) << " covered " << str(c.box);
        EXPECT_LE(e.y1 - c.box.y1, 2) << "rectangle " << r << " " << str(e) << " covered " << str(c.box);
    }
}

TEST(ReuseExtents, BoxHelpers) {
    Box a{2, 3, 10, 8}, b{9, 7, 12, 20}, c{10, 0, 15, 3}, empty{};
    EXPECT_TRUE(overlaps(a, b));
    EXPECT_FALSE(overlaps(a, c));  // touching edges do not overlap (half-open)
    EXPECT_FALSE(overlaps(a, empty));
    EXPECT_EQ(a.area(), 40);
    EXPECT_EQ(empty.area(), 0);
    Box u = empty;
    u.add(a);
    EXPECT_TRUE(u == a);
    u.add(empty);
    EXPECT_TRUE(u == a);
    u.add(b);
    EXPECT_TRUE(u == (Box{2, 3, 12, 20}));
    const Rect r = toRect(a);
    EXPECT_EQ(r.x, 2);
    EXPECT_EQ(r.y, 3);
    EXPECT_EQ(r.width, 8);
    EXPECT_EQ(r.height, 5);
}

}  // namespace
}  // namespace frugal::test
