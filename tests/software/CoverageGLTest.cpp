// The software backend against llvmpipe (GL backend, EGL surfaceless), triangle by triangle:
// coverage, 24-bit depth and ids must be identical, colour within 1 (it is identical too). Seeded
// random triangles of every kind the rasterizer has rules for: arbitrary, snapped to the 1/256 grid,
// vertices on pixel centres and on pixel edges, slivers, triangles far larger than the viewport,
// perspective ones and ones crossing the near plane, both windings, single- and double-sided, at
// 256×256, 61×47 (odd sizes expose the fused viewport) and 800×600. Then many triangles per draw
// (overlaps, ties, the parallel setup), degenerate input (NaN, Inf, w = 0), the draw module's
// second face cull at batch boundaries, extreme target sizes, and the kernels against each other.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "GlReference.h"

namespace frugal {
namespace {

using test::compareBuffers;
using test::Comparison;

const glm::vec4 kClear{0.1f, 0.2f, 0.3f, 1.0f};

// The same target (of one depth format) and mesh on the reference and on the software backend.
class Twin {
public:
    Twin(Backend& reference, Backend& software, int width, int height, DepthFormat format = DepthFormat::D24)
        : width_(width), height_(height), format_(format) {
        backends_ = {&reference, &software};
        for (int i = 0; i < 2; ++i) {
            targets_[i] = backends_[i]->createTarget(width, height, format);
            EXPECT_NE(targets_[i], kNoHandle) << "createTarget(" << width << ", " << height << ") on " << i;
        }
    }
    ~Twin() {
        for (int i = 0; i < 2; ++i) backends_[i]->destroyTarget(targets_[i]);
    }
    Twin(const Twin&) = delete;
    Twin& operator=(const Twin&) = delete;

    void upload(const Mesh& mesh) {
        for (int i = 0; i < 2; ++i) {
            meshes_[i] = backends_[i]->uploadMesh(mesh);
            ASSERT_NE(meshes_[i], kNoHandle);
        }
    }

    // Clears, draws `ranges` of the mesh with `draw` (its mesh is filled in), reads both back.
    std::array<Buffers, 2> render(FrameParams frame, DrawParams draw, const std::vector<IndexRange>& ranges) {
        std::array<Buffers, 2> out;
        frame.depthFormat = format_;
        for (int i = 0; i < 2; ++i) {
            backends_[i]->clear(targets_[i], Rect{0, 0, width_, height_}, kClear, farDepth(format_));
            backends_[i]->beginFrame(targets_[i], frame);
            draw.mesh = meshes_[i];
            backends_[i]->draw(draw, ranges);
            out[i] = backends_[i]->readBack(targets_[i]);
        }
        return out;
    }

private:
    int width_, height_;
    DepthFormat format_;
    std::array<Backend*, 2> backends_{};
    std::array<TargetHandle, 2> targets_{};
    std::array<MeshHandle, 2> meshes_{};
};

// Sums comparisons and keeps the images of the first failure.
struct Tally {
    std::string name;
    std::size_t draws = 0, failedDraws = 0, covered = 0, coverage = 0, depth = 0, ids = 0;
    std::uint32_t depthWorst = 0;
    int colorWorst = 0;
    bool saved = false;

    void add(const std::array<Buffers, 2>& out, const std::string& what) {
        const Comparison c = compareBuffers(out[0], out[1]);
        ++draws;
        covered += c.covered;
        coverage += c.coverage;
        depth += c.depth;
        ids += c.ids;
        depthWorst = std::max(depthWorst, c.depthWorst);
        colorWorst = std::max(colorWorst, c.colorWorst);
        const bool bad = c.sizeMismatch || c.coverage || c.depth || c.ids || c.colorWorst > 1;
        failedDraws += bad;
        if (bad && !saved) {
            saved = true;
            ADD_FAILURE() << name << ": first failing draw: " << what << ": " << c.summary() << "; images in "
                          << (test::outputDir() / name).string();
            test::saveImages(name, out[0], out[1]);
        }
    }
    void check() const {
        EXPECT_EQ(coverage, 0u) << summary();
        EXPECT_EQ(depth, 0u) << summary();
        EXPECT_EQ(ids, 0u) << summary();
        EXPECT_LE(colorWorst, 1) << summary();
        EXPECT_GT(covered, 0u) << "nothing was drawn: the test would prove nothing";
        std::printf("[ %s ] %s\n", name.c_str(), summary().c_str());
    }
    std::string summary() const {
        return std::to_string(draws) + " draws (" + std::to_string(failedDraws) + " failing), " +
               std::to_string(covered) + " pixels covered; coverage differs at " + std::to_string(coverage) +
               ", depth at " + std::to_string(depth) + " (worst " + std::to_string(depthWorst) + " LSB), ids at " +
               std::to_string(ids) + ", colour worst " + std::to_string(colorWorst);
    }
};

// Triangle kinds (see the file comment); the clip-space ones use identity matrices.
enum Kind { Random, Snapped, Centres, Edges, Sliver, Huge, Perspective, NearPlane, kKinds };
const char* kindName(int k) {
    static const char* names[] = {"random", "snapped", "centres",     "edges",
                                  "sliver", "huge",    "perspective", "near-plane"};
    return names[k];
}

struct Case {
    glm::vec3 p[3];
    glm::mat4 model{1.0f}, view{1.0f}, projection{1.0f};
};

// GL's perspective projection, or for D32F the reversed zero-to-one one (pipeline/Camera.h).
glm::mat4 perspectiveFor(DepthFormat format, float fov, float aspect, float znear, float zfar) {
    return format == DepthFormat::D32F ? glm::perspectiveRH_ZO(fov, aspect, zfar, znear)
                                       : glm::perspective(fov, aspect, znear, zfar);
}

class Generator {
public:
    Generator(int width, int height, unsigned seed, DepthFormat format = DepthFormat::D24)
        : w_(float(width)), h_(float(height)), format_(format), rng_(seed) {}

    float uniform(float a, float b) { return std::uniform_real_distribution<float>(a, b)(rng_); }
    int integer(int a, int b) { return std::uniform_int_distribution<int>(a, b)(rng_); }

    // Window position → NDC (what the vertex stage maps back to nearly the same window position).
    glm::vec3 fromWindow(float x, float y, float z) {
        return {(x - w_ * 0.5f) / (w_ * 0.5f), (y - h_ * 0.5f) / (h_ * 0.5f), z};
    }

    Case make(int kind) {
        Case c;
        const auto z = [&] { return uniform(-0.95f, 0.95f); };
        switch (kind) {
            case Random:
                for (auto& p : c.p) p = {uniform(-1.3f, 1.3f), uniform(-1.3f, 1.3f), z()};
                break;
            case Snapped:
                for (auto& p : c.p)
                    p = fromWindow(float(integer(-64, int(w_) * 256 + 64)) / 256.0f + 0.5f,
                                   float(integer(-64, int(h_) * 256 + 64)) / 256.0f + 0.5f, z());
                break;
            case Centres:
                for (auto& p : c.p)
                    p = fromWindow(float(integer(0, int(w_) - 1)) + 0.5f, float(integer(0, int(h_) - 1)) + 0.5f, z());
                break;
            case Edges:
                for (auto& p : c.p) p = fromWindow(float(integer(0, int(w_))), float(integer(0, int(h_))), z());
                break;
            case Sliver: {
                const glm::vec3 a{uniform(-1.0f, 1.0f), uniform(-1.0f, 1.0f), z()};
                const glm::vec3 d{uniform(-1.0f, 1.0f), uniform(-1.0f, 1.0f), uniform(-0.1f, 0.1f)};
                const float along = uniform(0.2f, 0.8f), across = uniform(-0.03f, 0.03f);
                c.p[0] = a;
                c.p[1] = a + d;
                c.p[2] = a + d * along + glm::vec3(-d.y, d.x, 0.0f) * across;
                break;
            }
            case Huge:
                for (auto& p : c.p) p = {uniform(-1e4f, 1e4f), uniform(-1e4f, 1e4f), z()};
                break;
            case Perspective:
            case NearPlane: {
                const float spread = kind == NearPlane ? 3.0f : 1.5f;
                for (auto& p : c.p) p = {uniform(-spread, spread), uniform(-spread, spread), uniform(-spread, spread)};
                const glm::vec3 axis = glm::normalize(glm::vec3(uniform(-1, 1), uniform(-1, 1), 1.0f));
                c.model = glm::rotate(
                    glm::translate(glm::mat4(1.0f), glm::vec3(uniform(-0.5f, 0.5f), uniform(-0.5f, 0.5f), 0.0f)),
                    uniform(-3.0f, 3.0f), axis);
                c.model = glm::scale(c.model, glm::vec3(uniform(0.5f, 1.5f)));
                // NearPlane puts the eye inside the triangles' box, so many cross the near plane.
                const float distance = kind == NearPlane ? uniform(0.0f, 1.0f) : uniform(4.0f, 6.0f);
                c.view = glm::lookAt(glm::vec3(uniform(-0.3f, 0.3f), uniform(-0.3f, 0.3f), distance), glm::vec3(0.0f),
                                     glm::vec3(0.0f, 1.0f, 0.0f));
                c.projection =
                    perspectiveFor(format_, uniform(0.5f, 1.4f), w_ / h_, kind == NearPlane ? 0.3f : 0.1f, 30.0f);
                break;
            }
            default:
                break;
        }
        return c;
    }

    // Per-vertex attributes, so shading is compared too.
    void decorate(Mesh& mesh) {
        for (std::size_t i = mesh.normals.size(); i < mesh.positions.size(); ++i) {
            mesh.normals.push_back(
                glm::normalize(glm::vec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)) + glm::vec3(1e-3f)));
            mesh.colors.push_back({uniform(0, 1), uniform(0, 1), uniform(0, 1), uniform(0.5f, 1)});
        }
    }

private:
    float w_, h_;
    DepthFormat format_;
    std::mt19937 rng_;
};

class CoverageGLTest : public test::ReferencePairTest {};

// One triangle per draw, `perKind` of each kind. In D32F the clip-space kinds (z in [−0.95, 0.95],
// w = 1) cross the zero-to-one near plane z = 0 half the time: its clipping is compared too.
void singleTriangles(Backend& reference, Backend& software, int width, int height, int perKind, unsigned seed,
                     DepthFormat format = DepthFormat::D24) {
    Twin twin(reference, software, width, height, format);
    Generator gen(width, height, seed, format);
    const int count = perKind * kKinds;
    std::vector<Case> cases;
    Mesh mesh;
    for (int i = 0; i < count; ++i) {
        cases.push_back(gen.make(i % kKinds));
        for (const glm::vec3& p : cases.back().p) mesh.positions.push_back(p);
        const auto base = std::uint32_t(3 * i);
        mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
    }
    gen.decorate(mesh);
    twin.upload(mesh);

    std::array<Tally, kKinds> tallies;
    for (int k = 0; k < kKinds; ++k)
        tallies[k].name = "SingleTriangle-" + std::to_string(width) + "x" + std::to_string(height) + "-" +
                          depthFormatName(format) + "-" + kindName(k);
    for (int i = 0; i < count; ++i) {
        const Case& c = cases[i];
        FrameParams frame;
        frame.view = c.view;
        frame.projection = c.projection;
        DrawParams draw;
        draw.model = c.model;
        draw.doubleSided = (i / kKinds) % 2 == 0;  // every kind both ways
        draw.firstId = 1 + std::uint32_t(i);
        tallies[i % kKinds].add(twin.render(frame, draw, {{std::uint32_t(i), 1}}), "triangle " + std::to_string(i));
    }
    for (const Tally& t : tallies) t.check();
}

TEST_F(CoverageGLTest, SingleTrianglesAt256x256) { singleTriangles(*reference, *software, 256, 256, 100, 1); }
TEST_F(CoverageGLTest, SingleTrianglesAt61x47) { singleTriangles(*reference, *software, 61, 47, 100, 2); }
TEST_F(CoverageGLTest, SingleTrianglesAt800x600) { singleTriangles(*reference, *software, 800, 600, 25, 3); }
// The float depth buffer with reversed Z: the same coverage and ids, and every stored float equal.
TEST_F(CoverageGLTest, SingleTrianglesAt256x256D32f) {
    singleTriangles(*reference, *software, 256, 256, 100, 21, DepthFormat::D32F);
}
TEST_F(CoverageGLTest, SingleTrianglesAt61x47D32f) {
    singleTriangles(*reference, *software, 61, 47, 100, 22, DepthFormat::D32F);
}

// Thousands of triangles in one draw: overlaps, equal depths (ties keep the first drawn), the
// parallel setup, bins across tiles; with ids (array pass) and without (indexed pass), and through
// several index ranges, adjacent and out of order.
void manyTrianglesPerDraw(Backend& reference, Backend& software, DepthFormat format) {
    for (const auto& size : {std::array<int, 2>{800, 600}, std::array<int, 2>{61, 47}}) {
        const int width = size[0], height = size[1];
        Twin twin(reference, software, width, height, format);
        Generator gen(width, height, 7, format);
        Mesh mesh;
        const int count = 6000;
        for (int i = 0; i < count; ++i) {
            const Case c = gen.make(i % 3 == 0 ? Perspective : Random);
            // Perspective positions are used with one camera below; the clip-space kinds shrink so
            // that most triangles are small, as in real meshes.
            for (const glm::vec3& p : c.p) mesh.positions.push_back(i % 3 == 0 ? p : p * 2.0f);
            const auto base = std::uint32_t(3 * i);
            mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
            if (i % 50 == 1) {  // an exact duplicate of the previous triangle: a depth tie
                const std::size_t n = mesh.positions.size();
                mesh.positions.insert(mesh.positions.end(),
                                      {mesh.positions[n - 3], mesh.positions[n - 2], mesh.positions[n - 1]});
                mesh.indices.insert(mesh.indices.end(), {std::uint32_t(n), std::uint32_t(n + 1), std::uint32_t(n + 2)});
                ++i;
            }
        }
        gen.decorate(mesh);
        twin.upload(mesh);
        const std::uint32_t triangles = std::uint32_t(mesh.triangleCount());
        Tally tally;
        tally.name =
            "ManyTriangles-" + std::to_string(width) + "x" + std::to_string(height) + "-" + depthFormatName(format);
        for (int pass = 0; pass < 4; ++pass) {
            FrameParams frame;
            frame.view = glm::lookAt(glm::vec3(0.2f, -0.3f, 5.0f), glm::vec3(0.0f), glm::vec3(0, 1, 0));
            frame.projection = perspectiveFor(format, 0.9f, float(width) / float(height), 0.5f, 20.0f);
            frame.writeIds = pass != 1;
            DrawParams draw;
            draw.doubleSided = pass < 2;  // passes 2 and 3 cull back faces
            draw.firstId = 100;
            std::vector<IndexRange> ranges{{0, triangles}};
            if (pass == 3) ranges = {{4000, 1000}, {10, 990}, {1000, 1500}, {2500, 1500}, {5000, triangles - 5000}};
            tally.add(twin.render(frame, draw, ranges), "pass " + std::to_string(pass));
        }
        tally.check();
    }
}

TEST_F(CoverageGLTest, ManyTrianglesPerDraw) { manyTrianglesPerDraw(*reference, *software, DepthFormat::D24); }
TEST_F(CoverageGLTest, ManyTrianglesPerDrawD32f) { manyTrianglesPerDraw(*reference, *software, DepthFormat::D32F); }

// NaN, Inf and w = 0 must neither crash nor hang, and give what llvmpipe gives: triangles with a
// non-finite clip distance vanish; w = 0 at a vertex that needs clipping is clipped away.
TEST_F(CoverageGLTest, DegenerateInputMatchesLlvmpipe) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    glm::mat4 wIsZ(1.0f);  // w = z, z_clip = z/2: a vertex at z = 0 has w = 0
    wIsZ[3][3] = 0.0f;
    wIsZ[2][3] = 1.0f;
    wIsZ[2][2] = 0.5f;
    const glm::mat4 identity(1.0f);
    struct Input {
        const char* name;
        glm::vec3 p[3];
        glm::mat4 projection;
    };
    const Input inputs[] = {
        {"plain", {{-0.5f, -0.5f, 0}, {0.5f, -0.5f, 0}, {0, 0.5f, 0}}, identity},
        {"nan-x", {{nan, -0.5f, 0}, {0.5f, -0.5f, 0}, {0, 0.5f, 0}}, identity},
        {"nan-z", {{-0.5f, -0.5f, nan}, {0.5f, -0.5f, 0}, {0, 0.5f, 0}}, identity},
        {"all-nan", {{nan, nan, nan}, {nan, nan, nan}, {nan, nan, nan}}, identity},
        {"inf-x", {{inf, -0.5f, 0}, {0.5f, -0.5f, 0}, {0, 0.5f, 0}}, identity},
        {"minus-inf-y", {{-0.5f, -inf, 0}, {0.5f, -0.5f, 0}, {0, 0.5f, 0}}, identity},
        {"inf-z", {{-0.5f, -0.5f, inf}, {0.5f, -0.5f, 0}, {0, 0.5f, 0}}, identity},
        {"w0-origin", {{0, 0, 0}, {0.5f, -0.5f, 1}, {0, 0.5f, 1}}, wIsZ},
        {"w0-x", {{0.5f, 0, 0}, {0.5f, -0.5f, 1}, {0, 0.5f, 1}}, wIsZ},
        {"w0-xy", {{0.5f, 0.5f, 0}, {0.5f, -0.5f, 1}, {-0.5f, 0.5f, 1}}, wIsZ},
        {"all-w0", {{0.5f, 0.5f, 0}, {0.5f, -0.5f, 0}, {-0.5f, 0.5f, 0}}, wIsZ},
        {"huge-1e30", {{-1e30f, -1e30f, 0}, {1e30f, -1e30f, 0}, {0, 1e30f, 0}}, identity},
        {"huge-3e38", {{-3e38f, -3e38f, 0}, {3e38f, -3e38f, 0}, {0, 3e38f, 0}}, identity},
        {"huge-1e20-w", {{-1e20f, -1e20f, 0.5f}, {1e20f, -1e20f, 0.5f}, {0, 1e20f, 0.5f}}, wIsZ},
        {"tiny-w", {{0.5f, 0.5f, 1e-30f}, {0.5f, -0.5f, 1}, {-0.5f, 0.5f, 1}}, wIsZ},
    };
    Mesh mesh;
    for (const Input& in : inputs) {
        for (const glm::vec3& p : in.p) mesh.positions.push_back(p);
        const auto base = std::uint32_t(mesh.positions.size() - 3);
        mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
    }
    for (const DepthFormat format : {DepthFormat::D24, DepthFormat::D32F}) {
        Twin twin(*reference, *software, 64, 64, format);
        twin.upload(mesh);
        for (std::uint32_t i = 0; i < std::size(inputs); ++i) {
            for (bool doubleSided : {true, false}) {
                FrameParams frame;
                frame.projection = inputs[i].projection;
                DrawParams draw;
                draw.doubleSided = doubleSided;
                const auto out = twin.render(frame, draw, {{i, 1}});
                test::expectMatches(std::string("Degenerate-") + depthFormatName(format) + "-" + inputs[i].name +
                                        (doubleSided ? "-both" : "-front"),
                                    out[0], out[1], 1.0, 0);
            }
        }
    }
}

// Slivers that the fixed-point area calls front-facing but the float determinant does not: llvmpipe's
// draw module culls them only in batches that needed clipping (Rasterizer.h, 2a). Triangle 0 needs
// clipping; the slivers sit on both sides of the batch boundary (1365 triangles for the id pass, 341
// for the indexed one), so the software backend must cull exactly those before the boundary.
TEST_F(CoverageGLTest, DrawModuleCullsOnlyInClippedBatches) {
    const int size = 256;
    const auto window = [&](float n) { return std::fma(n, size * 0.5f, size * 0.5f); };
    // Front by fixed-point area, not by float determinant (computed as both backends do here).
    const auto flips = [&](const glm::vec3 p[3]) {
        float x[3], y[3];
        long long X[3], Y[3];
        for (int i = 0; i < 3; ++i) {
            x[i] = window(p[i].x);
            y[i] = window(p[i].y);
            X[i] = std::llrint((x[i] - 0.5f) * 256.0f);
            Y[i] = std::llrint((y[i] - 0.5f) * 256.0f);
        }
        const long long area = (X[0] - X[1]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[0] - Y[1]);
        const float det = (x[0] - x[2]) * (y[1] - y[2]) - (y[0] - y[2]) * (x[1] - x[2]);
        return area < 0 && !(det > 0.0f);
    };
    Generator gen(size, size, 5);
    std::vector<std::array<glm::vec3, 3>> slivers;
    for (int attempt = 0; attempt < 2000000 && slivers.size() < 40; ++attempt) {
        const glm::vec3 a{gen.uniform(-0.9f, 0.9f), gen.uniform(-0.9f, 0.9f), 0.0f};
        const glm::vec3 d{gen.uniform(-0.45f, 0.45f), gen.uniform(-0.45f, 0.45f), 0.0f};
        const glm::vec3 p[3] = {
            a, a + d, a + d * gen.uniform(0.3f, 0.7f) + glm::vec3(-d.y, d.x, 0.0f) * gen.uniform(-2e-5f, 2e-5f)};
        if (flips(p)) slivers.push_back({p[0], p[1], p[2]});
    }
    ASSERT_EQ(slivers.size(), 40u);

    for (bool ids : {true, false}) {
        const int boundary = ids ? 1365 : 341;
        Mesh mesh;
        mesh.positions = {{-0.95f, -0.95f, 0}, {-0.9f, -0.95f, 0}, {-0.93f, -0.9f, -3.0f}};  // crosses the near plane
        mesh.indices = {0, 1, 2};
        const int total = 2 * boundary + 30, first = boundary - 20;
        for (int t = 1; t < total; ++t) {
            const auto base = std::uint32_t(mesh.positions.size());
            const int k = t - first;
            if (k >= 0 && k < 40)
                mesh.positions.insert(mesh.positions.end(), slivers[k].begin(), slivers[k].end());
            else
                mesh.positions.insert(mesh.positions.end(), 3, glm::vec3(0.99f));  // degenerate filler
            mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
        }
        Twin twin(*reference, *software, size, size);
        twin.upload(mesh);
        FrameParams frame;
        frame.writeIds = ids;
        DrawParams draw;
        const auto out = twin.render(frame, draw, {{0, std::uint32_t(total)}});
        const Comparison c = compareBuffers(out[0], out[1]);
        EXPECT_EQ(c.coverage + c.depth + c.ids, 0u) << (ids ? "id pass: " : "indexed pass: ") << c.summary();
        EXPECT_GT(c.covered, 0u) << "the slivers after the boundary must draw something";
        if (c.coverage + c.depth + c.ids)
            test::saveImages(ids ? "DrawModuleCull-ids" : "DrawModuleCull-indexed", out[0], out[1]);
    }
}

// 1×1 and 4096×4096 targets; the largest size both accept.
TEST_F(CoverageGLTest, ExtremeTargetSizes) {
    EXPECT_EQ(software->maxTargetSize(), 16384);
    EXPECT_EQ(software->maxTargetSize(), reference->maxTargetSize());
    EXPECT_EQ(software->createTarget(0, 10), kNoHandle);
    EXPECT_EQ(software->createTarget(10, -1), kNoHandle);
    EXPECT_EQ(software->createTarget(16385, 1), kNoHandle);
    for (const int size : {1, 4096}) {
        Twin twin(*reference, *software, size, size);
        Generator gen(size, size, 11);
        Mesh mesh;
        for (int i = 0; i < 64; ++i) {
            const Case c = gen.make(i % 2 ? Random : Sliver);
            mesh.positions.insert(mesh.positions.end(), {c.p[0], c.p[1], c.p[2]});
            const auto base = std::uint32_t(3 * i);
            mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
        }
        gen.decorate(mesh);
        twin.upload(mesh);
        const auto out = twin.render(FrameParams{}, DrawParams{}, {{0, 64}});
        test::expectMatches("Size-" + std::to_string(size), out[0], out[1], 1.0, 1);
    }
}

// The portable kernels (fused or not, as the CPU has FMA) and one thread give the same bits as the
// AVX2 kernels on two threads.
TEST_F(CoverageGLTest, KernelsAndThreadCountsAgree) {
    SoftwareOptions portable;
    portable.simd = false;
    portable.threads = 1;
    std::unique_ptr<Backend> other = makeSoftwareBackend(portable);
    SoftwareOptions two;
    two.threads = 2;
    std::unique_ptr<Backend> simd = makeSoftwareBackend(two);
    Twin twin(*simd, *other, 200, 150);
    Generator gen(200, 150, 13);
    Mesh mesh;
    for (int i = 0; i < 9000; ++i) {
        const Case c = gen.make(i % kKinds == NearPlane ? Perspective : i % kKinds);
        mesh.positions.insert(mesh.positions.end(), {c.p[0] * 0.5f, c.p[1] * 0.5f, c.p[2] * 0.5f});
        const auto base = std::uint32_t(3 * i);
        mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
    }
    gen.decorate(mesh);
    twin.upload(mesh);
    FrameParams frame;
    frame.view = glm::lookAt(glm::vec3(0.0f, 0.0f, 1.2f), glm::vec3(0.0f), glm::vec3(0, 1, 0));
    frame.projection = glm::perspective(1.0f, 200.0f / 150.0f, 0.3f, 10.0f);
    DrawParams draw;
    draw.doubleSided = true;
    const auto out = twin.render(frame, draw, {{0, 9000}});
    test::expectMatches("Kernels", out[0], out[1], 1.0, 0);
    EXPECT_NE(simd->renderer(), other->renderer());
}

}  // namespace
}  // namespace frugal
