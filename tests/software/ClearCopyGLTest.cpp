// clear(rect) and copy(rect) on the software backend against the GL backend: the same rectangle
// clipping (negative, oversized, empty rectangles), the same values (Mesa's float → unorm8 rule;
// util_pack_z for a clear of the whole target, a quad through the pipeline for part of it), the same
// planes touched, interleaved with draws so that pending work is flushed in order.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <string>
#include <vector>

#include "GlReference.h"

namespace frugal {
namespace {

class ClearCopyGLTest : public ::testing::Test {
protected:
    void SetUp() override {
        reference = test::makeReference();
        ASSERT_NE(reference, nullptr);
        software = makeSoftwareBackend();
        backends = {reference.get(), software.get()};
    }
    std::unique_ptr<Backend> reference, software;
    std::array<Backend*, 2> backends{};
};

// The documented values: 0.3 → 76 (0.3f·255 rounds to 76.5 in float, then to even), depth 0.5 →
// 0x800000 for a whole-target clear.
TEST_F(ClearCopyGLTest, KnownClearValues) {
    for (Backend* backend : backends) {
        const TargetHandle target = backend->createTarget(8, 4);
        backend->clear(target, Rect{0, 0, 8, 4}, glm::vec4(0.3f, 0.5f, 1.5f, -2.0f), 0.5f);
        const Buffers b = backend->readBack(target);
        EXPECT_EQ(b.rgba[0], 76) << backend->name();
        EXPECT_EQ(b.rgba[1], 128) << backend->name();
        EXPECT_EQ(b.rgba[2], 255) << backend->name();
        EXPECT_EQ(b.rgba[3], 0) << backend->name();
        EXPECT_EQ(b.depth[0], 0x800000u) << backend->name();
        EXPECT_EQ(b.ids[0], 0u) << backend->name();
        backend->destroyTarget(target);
    }
}

// D32F stores a whole clear's value as it is (clamped to [0, 1] by the backend), 0 for a new target.
TEST_F(ClearCopyGLTest, KnownClearValuesD32f) {
    for (Backend* backend : backends) {
        const TargetHandle target = backend->createTarget(8, 4, DepthFormat::D32F);
        ASSERT_NE(target, kNoHandle) << backend->name();
        EXPECT_EQ(backend->readBack(target).depth[0], 0u) << backend->name();
        for (const float z : {0.3f, 1.0f, 1.5f, -0.25f}) {
            backend->clear(target, Rect{0, 0, 8, 4}, glm::vec4(0.0f), z);
            const Buffers b = backend->readBack(target);
            EXPECT_EQ(b.depthFormat, DepthFormat::D32F);
            EXPECT_EQ(b.windowDepth(0), std::clamp(z, 0.0f, 1.0f)) << backend->name() << " " << z;
        }
        backend->destroyTarget(target);
    }
}

// New targets are transparent black, far, id 0 on both.
TEST_F(ClearCopyGLTest, NewTargetsAreDefined) {
    for (const DepthFormat format : {DepthFormat::D24, DepthFormat::D32F}) {
        Buffers out[2];
        for (int i = 0; i < 2; ++i) {
            const TargetHandle target = backends[i]->createTarget(13, 7, format);
            out[i] = backends[i]->readBack(target);
            backends[i]->destroyTarget(target);
        }
        EXPECT_EQ(out[0].rgba, out[1].rgba);
        EXPECT_EQ(out[0].depth, out[1].depth);
        EXPECT_EQ(out[0].ids, out[1].ids);
        EXPECT_EQ(out[0].depth[0], test::farValue(format));
    }
}

// Multisampled targets read back resolved: cleared ones as GL reads them (the depth through the
// resolve blit's round trip), in both formats, for the whole target and a part.
TEST_F(ClearCopyGLTest, MultisampledClearsReadBackAlike) {
    for (const DepthFormat format : {DepthFormat::D24, DepthFormat::D32F})
        for (const float z : {1.0f, 0.999f, 0.5f, 0.25f, 1e-7f, 0.0f})
            for (const bool whole : {true, false}) {
                Buffers out[2];
                for (int i = 0; i < 2; ++i) {
                    const TargetHandle target = backends[i]->createTarget(13, 7, format, 4);
                    ASSERT_NE(target, kNoHandle);
                    backends[i]->clear(target, whole ? Rect{0, 0, 13, 7} : Rect{2, 1, 5, 4}, {0.3f, 0.6f, 0.1f, 1}, z);
                    out[i] = backends[i]->readBack(target);
                    backends[i]->destroyTarget(target);
                }
                const test::Comparison c = test::compareBuffers(out[0], out[1]);
                EXPECT_TRUE(c.depth == 0 && c.ids == 0 && c.color == 0)
                    << depthFormatName(format) << ", z " << z << (whole ? ", whole" : ", part") << ": " << c.summary()
                    << " (GL depth " << out[0].depth[3 * 13 + 4] << ", software " << out[1].depth[3 * 13 + 4] << ")";
            }
}

// Random sequences of clears (whole and partial, in and out of bounds), copies between two targets
// (any subset of planes), and draws; both targets compared after every step. Multisampled targets
// (`samples` 4) are compared as read back: resolved.
void randomSequences(Backend& reference, Backend& software, DepthFormat format, int samples = 1) {
    const std::array<Backend*, 2> backends{&reference, &software};
    const int width = 53, height = 37;
    std::mt19937 rng(9);
    const auto uniform = [&](float a, float b) { return std::uniform_real_distribution<float>(a, b)(rng); };
    const auto integer = [&](int a, int b) { return std::uniform_int_distribution<int>(a, b)(rng); };

    Mesh mesh;
    for (int i = 0; i < 40; ++i) {
        for (int k = 0; k < 3; ++k) {
            mesh.positions.push_back({uniform(-1.2f, 1.2f), uniform(-1.2f, 1.2f), uniform(-0.9f, 0.9f)});
            mesh.normals.push_back(glm::normalize(glm::vec3(uniform(-1, 1), uniform(-1, 1), 1.0f)));
        }
        const auto base = std::uint32_t(3 * i);
        mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
    }
    std::array<std::array<TargetHandle, 2>, 2> targets{};  // [backend][target]
    std::array<MeshHandle, 2> meshes{};
    for (int i = 0; i < 2; ++i) {
        targets[i] = {backends[i]->createTarget(width, height, format, samples),
                      backends[i]->createTarget(width, height, format, samples)};
        meshes[i] = backends[i]->uploadMesh(mesh);
    }
    const auto randomRect = [&] {
        switch (integer(0, 5)) {
            case 0:
                return Rect{0, 0, width, height};  // whole target: pipe->clear
            case 1:
                return Rect{-10, -10, width + 20, height + 20};  // covers it all after clipping
            case 2:
                return Rect{integer(-5, width), integer(-5, height), integer(-3, 20), integer(-3, 20)};  // maybe empty
            default: {
                const int x = integer(0, width - 1), y = integer(0, height - 1);
                return Rect{x, y, integer(1, width - x), integer(1, height - y)};
            }
        }
    };
    for (int step = 0; step < 300; ++step) {
        const int op = integer(0, 2);
        const int which = integer(0, 1);
        const Rect rect = randomRect();
        const glm::vec4 color{uniform(-0.2f, 1.2f), uniform(0, 1), uniform(0, 1), uniform(0, 1)};
        const float depth = integer(0, 3) == 0 ? uniform(-0.5f, 1.5f) : uniform(0, 1);
        const bool planes[3] = {integer(0, 1) == 1, integer(0, 1) == 1, integer(0, 1) == 1};
        FrameParams frame;
        frame.writeIds = integer(0, 3) != 0;
        frame.depthFormat = format;
        DrawParams draw;
        draw.doubleSided = integer(0, 1) == 1;
        draw.firstId = std::uint32_t(integer(1, 1000));
        const std::uint32_t first = std::uint32_t(integer(0, 39));
        const IndexRange range{first, std::uint32_t(integer(1, 40 - int(first)))};
        for (int i = 0; i < 2; ++i) {
            Backend& b = *backends[i];
            switch (op) {
                case 0:
                    b.clear(targets[i][which], rect, color, depth);
                    break;
                case 1:
                    b.copy(targets[i][which], targets[i][1 - which], rect, planes[0], planes[1], planes[2]);
                    break;
                default:
                    b.beginFrame(targets[i][which], frame);
                    draw.mesh = meshes[i];
                    b.draw(draw, {&range, 1});
                    break;
            }
        }
        // Read back now and then, so that several draws (with and without ids), clears and copies
        // are pending together.
        if (step % 10 != 9) continue;
        for (int t = 0; t < 2; ++t) {
            const Buffers a = reference.readBack(targets[0][t]);
            const Buffers b = software.readBack(targets[1][t]);
            const test::Comparison c = test::compareBuffers(a, b);
            const bool same = c.depth == 0 && c.ids == 0 && c.color == 0 && !c.sizeMismatch;
            EXPECT_TRUE(same) << depthFormatName(format) << ", " << samples << " samples, after step " << step
                              << ", target " << t << ": " << c.summary();
            if (!same) {
                test::saveImages(std::string("ClearCopy-") + depthFormatName(format) + "-" + std::to_string(samples) +
                                     "-step" + std::to_string(step),
                                 a, b);
                return;
            }
        }
    }
}

TEST_F(ClearCopyGLTest, RandomSequencesMatch) { randomSequences(*reference, *software, DepthFormat::D24); }
TEST_F(ClearCopyGLTest, RandomSequencesMatchD32f) { randomSequences(*reference, *software, DepthFormat::D32F); }
TEST_F(ClearCopyGLTest, RandomSequencesMatchMultisampled) {
    randomSequences(*reference, *software, DepthFormat::D24, 4);
    randomSequences(*reference, *software, DepthFormat::D32F, 4);
}

// A copy between targets of different sizes is refused by contract (assert), a copy onto itself and
// one with no planes do nothing; a clear of an empty rectangle does nothing.
TEST_F(ClearCopyGLTest, NoOpsDoNothing) {
    // Both targets hold a pattern in every plane (a draw writes ids), so a no-op that touched any
    // pixel of any plane would show.
    Mesh mesh;
    mesh.positions = {{-1, -1, 0.2f}, {1, -1, -0.3f}, {0, 1, 0.1f}};
    mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    mesh.indices = {0, 1, 2};
    const IndexRange all{0, 1};
    for (Backend* backend : backends) {
        const TargetHandle a = backend->createTarget(16, 16), b = backend->createTarget(16, 16);
        const MeshHandle triangle = backend->uploadMesh(mesh);
        ASSERT_NE(triangle, kNoHandle);
        for (const TargetHandle t : {a, b}) {
            backend->clear(t, Rect{0, 0, 16, 16}, glm::vec4(0.25f, 0.5f, 0.75f, 1.0f), 0.75f);
            backend->clear(t, Rect{2, 3, 5, 7}, glm::vec4(1.0f, 0.0f, t == a ? 1.0f : 0.0f, 1.0f), 0.25f);
            backend->beginFrame(t, FrameParams{});
            DrawParams draw;
            draw.mesh = triangle;
            draw.firstId = t == a ? 100 : 200;
            backend->draw(draw, {&all, 1});
        }
        const Buffers before[2] = {backend->readBack(a), backend->readBack(b)};
        std::size_t ids = 0;
        for (std::uint32_t id : before[1].ids) ids += id != 0;
        ASSERT_GT(ids, 0u) << backend->name() << ": the draw must leave ids to protect";

        backend->copy(a, a, Rect{0, 0, 8, 8}, true, true, true);
        backend->copy(a, b, Rect{0, 0, 16, 16}, false, false, false);
        backend->copy(a, b, Rect{3, 3, 0, 9}, true, true, true);
        backend->copy(a, b, Rect{16, 0, 4, 4}, true, true, true);
        backend->clear(b, Rect{4, 4, 0, 5}, glm::vec4(1.0f), 0.0f);
        backend->clear(b, Rect{4, 4, 5, -1}, glm::vec4(1.0f), 0.0f);
        backend->clear(b, Rect{20, 20, 5, 5}, glm::vec4(1.0f), 0.0f);
        backend->clear(a, Rect{-9, 0, 9, 16}, glm::vec4(1.0f), 0.0f);

        const Buffers after[2] = {backend->readBack(a), backend->readBack(b)};
        for (int k = 0; k < 2; ++k) {
            const test::Comparison c = test::compareBuffers(after[k], before[k]);
            EXPECT_TRUE(c.color == 0 && c.depth == 0 && c.ids == 0 && !c.sizeMismatch)
                << backend->name() << ", target " << (k == 0 ? "a" : "b") << ": " << c.summary();
        }
        backend->destroyTarget(a);
        backend->destroyTarget(b);
    }
}

}  // namespace
}  // namespace frugal
