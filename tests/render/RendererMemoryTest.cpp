// Renderer::extraBytes: the memory a method keeps beyond the plain render's, as `frugal report`'s
// extra-memory column shows it. Counted from what each part holds, on the software backend (no GL).
#include <gtest/gtest.h>

#include <frugal/Renderer.h>

namespace frugal {
namespace {

std::uint64_t extraBytes(const Scene& scene, Settings settings) {
    settings.backend = BackendKind::Software;
    settings.width = 64;
    settings.height = 48;
    Result<Renderer> renderer = Renderer::create(scene, settings);
    EXPECT_TRUE(renderer) << renderer.error().message;
    return renderer ? renderer->extraBytes() : 0;
}

TEST(RendererMemoryTest, EachMethodCountsWhatItKeeps) {
    Result<Scene> loaded = loadScene("builtin:cubes?count=4");
    ASSERT_TRUE(loaded) << loaded.error().message;
    const Scene& scene = *loaded;
    const std::uint64_t triangles = scene.triangleCount();
    Settings s;
    EXPECT_EQ(extraBytes(scene, s), 0u) << "the plain render is the baseline";
    s.order = Order::Key;
    EXPECT_EQ(extraBytes(scene, s), 0u) << "an order keeps nothing";

    Settings reuse;
    reuse.reuse = true;
    EXPECT_EQ(extraBytes(scene, reuse), 64u * 48u * 12u) << "the static pair: RGBA8 + depth + ids a pixel";

    Settings hsr;
    hsr.hsr = Hsr::Adaptive;
    EXPECT_GE(extraBytes(scene, hsr), 4u * triangles) << "each triangle's polygon";

    Settings cull;
    cull.cull = Cull::Conservative;
    const std::uint64_t conservative = extraBytes(scene, cull);
    EXPECT_GE(conservative, 16u * triangles) << "at least each triangle's facing plane";
    cull.cull = Cull::Paper;
    EXPECT_GT(extraBytes(scene, cull), conservative) << "the paper's method keeps the hull too";
    cull.reuse = true;
    cull.cull = Cull::Conservative;
    EXPECT_EQ(extraBytes(scene, cull), conservative + 64u * 48u * 12u) << "the parts add up";
}

}  // namespace
}  // namespace frugal
