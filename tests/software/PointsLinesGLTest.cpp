// Points and line segments (Mesh::topology), the software backend against llvmpipe (the GL
// backend): coverage, depth and ids identical, colour within one step, for seeded random draws of
// every kind raster/PointsLines.h has a rule for: arbitrary positions, positions on the 1/256 grid,
// on pixel centres and edges, exactly on the frustum's edges, beyond near and far, with w near 0 and
// negative, zero-length and nearly zero-length segments, 45° and axis-aligned ones; one and four
// samples, D24 and D32F, a target that spans several 64×64 tiles; lit (normals), bare (no normals:
// base colour plus emission) and vertex-coloured draws. Each draw is compared whole: many points or
// segments in one draw, so the order within a draw is tested too (later primitives overwrite earlier
// ones on depth ties only under the depth test's rule).
#include <array>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "GlReference.h"

namespace frugal {
namespace {

using test::compareBuffers;
using test::Comparison;

const glm::vec4 kClear{0.1f, 0.2f, 0.3f, 1.0f};

// Draws `mesh` whole on both backends into targets of the given size, format and samples; reads
// both back (a multisampled target resolved: sample 0's depth and id, the samples' mean colour).
std::array<Buffers, 2> renderBoth(Backend& reference, Backend& software, const Mesh& mesh, int width, int height,
                                  DepthFormat format, int samples, const glm::mat4& projection,
                                  const DrawParams& params) {
    std::array<Buffers, 2> out;
    Backend* backends[2] = {&reference, &software};
    for (int i = 0; i < 2; ++i) {
        Backend& b = *backends[i];
        const TargetHandle target = b.createTarget(width, height, format, samples);
        const MeshHandle handle = b.uploadMesh(mesh);
        EXPECT_NE(target, kNoHandle);
        EXPECT_NE(handle, kNoHandle);
        if (target == kNoHandle || handle == kNoHandle) return out;
        b.clear(target, Rect{0, 0, width, height}, kClear, farDepth(format));
        FrameParams frame;
        frame.projection = projection;
        frame.depthFormat = format;
        b.beginFrame(target, frame);
        DrawParams draw = params;
        draw.mesh = handle;
        b.draw(draw, {{IndexRange{0, std::uint32_t(mesh.primitiveCount())}}});
        out[std::size_t(i)] = b.readBack(target);
        b.releaseMesh(handle);
        b.destroyTarget(target);
    }
    return out;
}

enum Kind { Random, Grid, Centres, Edges, FrustumEdges, NearFar, SmallW, Short, Diagonal, kKinds };
const char* kKindNames[] = {"random",   "grid",    "centres", "edges",   "frustum-edges",
                            "near-far", "small-w", "short",   "diagonal"};

// Clip-space positions made from mesh positions by a projection that maps (x, y, z) to
// (x, y, a·z + b, z): a vertex's w is its z, its clip z follows from it.
class Generator {
public:
    Generator(int width, int height, unsigned seed) : w_(float(width)), h_(float(height)), rng_(seed) {}

    float uniform(float a, float b) { return std::uniform_real_distribution<float>(a, b)(rng_); }
    int integer(int a, int b) { return std::uniform_int_distribution<int>(a, b)(rng_); }

    // A vertex at window (x, y) for clip w = `w` (the window position within the float rounding of
    // the vertex stage; exact at w = 1 on a 64-pixel-wide target).
    glm::vec3 window(float x, float y, float w) {
        return {(x / (w_ * 0.5f) - 1.0f) * w, (y / (h_ * 0.5f) - 1.0f) * w, w};
    }
    glm::vec3 vertex(int kind) {
        switch (kind) {
            case Grid:
                return window(float(integer(-256, int(w_) * 256 + 256)) / 256.0f,
                              float(integer(-256, int(h_) * 256 + 256)) / 256.0f, 1.0f);
            case Centres:
                return window(float(integer(0, int(w_) - 1)) + 0.5f, float(integer(0, int(h_) - 1)) + 0.5f, 1.0f);
            case Edges:
                return window(float(integer(0, int(w_))), float(integer(0, int(h_))), 1.0f);
            case FrustumEdges: {  // x or y exactly ±w
                const float w = uniform(0.5f, 2.0f);
                glm::vec3 p{uniform(-w, w), uniform(-w, w), w};
                (integer(0, 1) ? p.x : p.y) = integer(0, 1) ? w : -w;
                return p;
            }
            case SmallW: {  // w near 0 or below it: the clipper's unbounded ends
                const float w = integer(0, 2) == 0 ? uniform(-0.5f, 0.0f) : uniform(1e-4f, 0.2f);
                return {uniform(-1.2f, 1.2f) * w, uniform(-1.2f, 1.2f) * w, w};
            }
            default: {
                const float w = uniform(0.3f, 3.0f);
                return {uniform(-1.3f, 1.3f) * w, uniform(-1.3f, 1.3f) * w, w};
            }
        }
    }
    // The second end of a segment from `a`.
    glm::vec3 partner(int kind, const glm::vec3& a) {
        switch (kind) {
            case Short: {
                const float d = integer(0, 2) == 0 ? 0.0f : integer(0, 1) ? 1e-7f : uniform(0.0f, 0.02f);
                return a + glm::vec3(d * uniform(-1.0f, 1.0f), d * uniform(-1.0f, 1.0f), 0.0f);
            }
            case Diagonal: {  // exact 45°, or along an axis, on the grid
                const float d = float(integer(-4096, 4096)) / 256.0f / (w_ * 0.5f);
                const int axis = integer(0, 2);
                return a + glm::vec3(axis != 1 ? d : 0.0f, axis != 0 ? (integer(0, 1) ? d : -d) : 0.0f, 0.0f);
            }
            case SmallW:  // the other end in front of the eye: the segment crosses w = 0
                return vertex(Random);
            default:
                return vertex(kind);
        }
    }

private:
    float w_, h_;
    std::mt19937 rng_;
};

// (x, y, a·z + b, z), the clip-space z spanning the near and far planes over the w range for NearFar.
glm::mat4 projectionFor(int kind, DepthFormat format) {
    glm::mat4 m(0.0f);
    m[0][0] = 1.0f;
    m[1][1] = 1.0f;
    m[2][3] = 1.0f;         // w = z
    if (kind == NearFar) {  // z_clip = 1.6·w − 1.3: beyond far above w ≈ 1.08, beyond near below w ≈ 0.5
        m[2][2] = 1.6f;
        m[3][2] = -1.3f;
    } else if (kind == SmallW) {  // z_clip / w = 0.4 at every w: inside near and far even at w near 0
        m[2][2] = 0.4f;
    } else if (format == DepthFormat::D32F) {  // z_clip / w in (0, 1)
        m[2][2] = 0.5f;
        m[3][2] = 0.1f;
    } else {
        m[2][2] = 0.3f;
        m[3][2] = 0.2f;
    }
    return m;
}

struct Tally {
    std::string name;
    std::size_t draws = 0, covered = 0, coverage = 0, depth = 0, ids = 0;
    int colorWorst = 0;
    bool saved = false;

    void add(const std::array<Buffers, 2>& out) {
        const Comparison c = compareBuffers(out[0], out[1]);
        ++draws;
        covered += c.covered, coverage += c.coverage, depth += c.depth, ids += c.ids;
        colorWorst = std::max(colorWorst, c.colorWorst);
        if ((c.sizeMismatch || c.coverage || c.depth || c.ids || c.colorWorst > 1) && !saved) {
            saved = true;
            ADD_FAILURE() << name << ": draw " << draws << ": " << c.summary() << "; images in "
                          << (test::outputDir() / name).string();
            test::saveImages(name, out[0], out[1]);
        }
    }
    void check() const {
        EXPECT_EQ(coverage, 0u) << name;
        EXPECT_EQ(depth, 0u) << name;
        EXPECT_EQ(ids, 0u) << name;
        EXPECT_LE(colorWorst, 1) << name;
        std::printf(
            "[ %s ] %zu draws, %zu pixels covered; coverage differs at %zu, depth at %zu, ids at %zu, colour "
            "worst %d\n",
            name.c_str(), draws, covered, coverage, depth, ids, colorWorst);
    }
};

struct Config {
    Topology topology;
    int width, height, samples;
    DepthFormat format;
};

// `draws` draws of `perDraw` points or segments of each kind; every third draw lit (normals), every
// third bare with vertex colours, the rest bare and plain.
void compareKinds(Backend& reference, Backend& software, const Config& config, int draws, int perDraw, unsigned seed) {
    Generator gen(config.width, config.height, seed);
    std::size_t coveredAll = 0;
    for (int kind = 0; kind < kKinds; ++kind) {
        if (config.topology == Topology::Points && (kind == Short || kind == Diagonal)) continue;
        Tally tally;
        tally.name = std::string("PointsLines-") + topologyName(config.topology) + "-" + std::to_string(config.width) +
                     "x" + std::to_string(config.height) + "-x" + std::to_string(config.samples) + "-" +
                     depthFormatName(config.format) + "-" + kKindNames[kind];
        for (int d = 0; d < draws; ++d) {
            Mesh mesh;
            mesh.topology = config.topology;
            for (int p = 0; p < perDraw; ++p) {
                const glm::vec3 a = gen.vertex(kind);
                mesh.positions.push_back(a);
                if (config.topology == Topology::Lines) mesh.positions.push_back(gen.partner(kind, a));
            }
            for (std::uint32_t i = 0; i < mesh.positions.size(); ++i) mesh.indices.push_back(i);
            const int style = d % 3;
            if (style == 0)
                for (std::size_t i = 0; i < mesh.positions.size(); ++i)
                    mesh.normals.push_back(glm::normalize(glm::vec3(gen.uniform(-1, 1), gen.uniform(-1, 1), 1.0f)));
            if (style == 1)
                for (std::size_t i = 0; i < mesh.positions.size(); ++i)
                    mesh.colors.push_back({gen.uniform(0, 1), gen.uniform(0, 1), gen.uniform(0, 1), 1.0f});
            DrawParams params;
            params.baseColorFactor = {0.8f, 0.6f, 0.4f, 1.0f};
            params.metallic = 0.0f;
            params.roughness = 0.5f;
            params.emissive = {0.05f, 0.1f, 0.0f};
            params.firstId = 1 + std::uint32_t(d) * 1000;
            tally.add(renderBoth(reference, software, mesh, config.width, config.height, config.format, config.samples,
                                 projectionFor(kind, config.format), params));
        }
        tally.check();
        coveredAll += tally.covered;
    }
    EXPECT_GT(coveredAll, 0u) << "nothing was drawn: the test would prove nothing";
}

class PointsLinesGLTest : public test::ReferencePairTest {};

TEST_F(PointsLinesGLTest, PointsOneSample) {
    compareKinds(*reference, *software, {Topology::Points, 64, 64, 1, DepthFormat::D24}, 6, 200, 1);
    compareKinds(*reference, *software, {Topology::Points, 150, 100, 1, DepthFormat::D32F}, 4, 200, 2);
}

TEST_F(PointsLinesGLTest, PointsFourSamples) {
    compareKinds(*reference, *software, {Topology::Points, 64, 64, 4, DepthFormat::D24}, 6, 200, 3);
    compareKinds(*reference, *software, {Topology::Points, 150, 100, 4, DepthFormat::D32F}, 4, 200, 4);
}

TEST_F(PointsLinesGLTest, SegmentsOneSample) {
    compareKinds(*reference, *software, {Topology::Lines, 64, 64, 1, DepthFormat::D24}, 6, 40, 5);
    compareKinds(*reference, *software, {Topology::Lines, 150, 100, 1, DepthFormat::D32F}, 4, 40, 6);
}

TEST_F(PointsLinesGLTest, SegmentsFourSamples) {
    compareKinds(*reference, *software, {Topology::Lines, 64, 64, 4, DepthFormat::D24}, 6, 40, 7);
    compareKinds(*reference, *software, {Topology::Lines, 150, 100, 4, DepthFormat::D32F}, 4, 40, 8);
}

// A strip and a loop as the glTF loader makes them (segment i = (v_i, v_{i+1}), the loop closed),
// with repeated vertices (zero-length segments) among them: shared pixels drawn once, by the later
// segment, exactly as llvmpipe draws GL_LINE_STRIP and GL_LINE_LOOP.
TEST_F(PointsLinesGLTest, DegenerateStripsAndLoops) {
    Generator gen(64, 64, 9);
    for (const int samples : {1, 4}) {
        Tally tally;
        tally.name = "PointsLines-strips-x" + std::to_string(samples);
        for (int d = 0; d < 20; ++d) {
            std::vector<glm::vec3> strip;
            for (int v = 0; v < 12; ++v) {
                strip.push_back(gen.vertex(v % 3 == 0 ? Grid : Random));
                if (gen.integer(0, 3) == 0) strip.push_back(strip.back());  // a zero-length segment
            }
            Mesh mesh;
            mesh.topology = Topology::Lines;
            mesh.positions = strip;
            for (std::uint32_t i = 0; i + 1 < strip.size(); ++i) mesh.indices.insert(mesh.indices.end(), {i, i + 1});
            if (d % 2 == 1) mesh.indices.insert(mesh.indices.end(), {std::uint32_t(strip.size() - 1), 0u});
            DrawParams params;
            params.firstId = 7;
            tally.add(renderBoth(*reference, *software, mesh, 64, 64, DepthFormat::D24, samples,
                                 projectionFor(Random, DepthFormat::D24), params));
        }
        tally.check();
        EXPECT_GT(tally.covered, 0u);
    }
}

}  // namespace
}  // namespace frugal
