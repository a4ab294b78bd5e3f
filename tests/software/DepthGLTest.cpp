// A file's camera as users expect it, and depth that holds at any near/far ratio (pipeline/Camera.h):
// - the aspect ratio: a camera whose file says 1.0 frames an 800×600 or 1920×1080 image as the same
//   camera given explicitly does (the image's aspect ratio, the vertical field of view), not
//   stretched;
// - the fitted depth range: no front surface flips when the file's near plane moves by one part in
//   10^6 (the 2CylinderEngine's planes, 0.05 to 10^6, z-fight without the fit);
// - the extremes, on llvmpipe and the software reference: near/far ratios 10², 10⁶, 10¹², an infinite
//   far plane, coordinates at 10⁻⁶ and 10⁶. d32f separates two planes 10⁻⁶ of their distance apart
//   where d24 cannot, and the reference equals llvmpipe bit for bit in both formats;
// - what the fit changes in d24 images: only pixels where two triangles tie in depth.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "GlReference.h"
#include "RenderSupport.h"
#include "pipeline/Frame.h"
#include "pipeline/SceneRenderer.h"
#include "scene/Load.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

const glm::vec4 kBackground{0.12f, 0.13f, 0.15f, 1.0f};

std::string enginePath() {
    return std::string(FRUGAL_ASSIMP_GLTF2_DIR) + "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
}

// The mean difference of two colour images over every channel, in 8-bit steps.
double meanColourDifference(const Buffers& a, const Buffers& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.rgba.size() && i < b.rgba.size(); ++i)
        sum += std::abs(int(a.rgba[i]) - int(b.rgba[i]));
    return a.rgba.empty() ? 0.0 : sum / double(a.rgba.size());
}

std::size_t differingIds(const Buffers& a, const Buffers& b) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.ids.size(); ++i) n += a.ids[i] != b.ids[i];
    return n;
}

// The frame as `camera` sees it in depth `format`, rendered with `projection` instead of the
// camera's when given.
Buffers render(Backend& backend, const Scene& scene, int width, int height, const Camera& camera,
               DepthFormat format = DepthFormat::D24, std::optional<glm::mat4> projection = std::nullopt) {
    const TargetHandle target = backend.createTarget(width, height, format);
    Result<SceneRenderer> renderer = SceneRenderer::create(backend, scene);
    Result<FrameSetup> setup = setUpFrame(scene, camera, 0.0, width, height, true, format);
    EXPECT_NE(target, kNoHandle);
    EXPECT_TRUE(renderer) << renderer.error().message;
    EXPECT_TRUE(setup) << setup.error().message;
    if (target == kNoHandle || !renderer || !setup) return {};
    if (projection) setup->params.projection = *projection;
    renderer->renderFrame(target, width, height, setup->params, setup->world, kBackground);
    Buffers out = backend.readBack(target);
    backend.destroyTarget(target);
    return out;
}

class DepthGLTest : public ::testing::Test {
protected:
    void SetUp() override {
        llvmpipe = test::makeReference();
        ASSERT_NE(llvmpipe, nullptr);
        software = makeSoftwareBackend();
    }
    std::unique_ptr<Backend> llvmpipe, software;
};

// The engine's camera says aspectRatio 1. Drawn at 800×600 and 1920×1080 it frames what the same
// eye, direction and vertical field of view given explicitly frame: a mean difference under one
// 8-bit step (the explicit camera's view matrix and field of view differ from the node's in the last
// bits, which moves edges of the engine's 121,000 small triangles by a hair). Its old projection
// (aspect 1 on a wider image) is the stretched picture the test would catch.
TEST_F(DepthGLTest, AFileCameraIsNotStretched) {
    Result<Scene> scene = loadScene(enginePath());
    ASSERT_TRUE(scene) << scene.error().message;
    ASSERT_EQ(scene->cameras.size(), 1u);
    ASSERT_EQ(scene->cameras[0].aspect, 1.0f);
    const glm::mat4 node = scene->worldTransforms(0.0)[std::size_t(scene->cameras[0].node)];
    Camera explicitCamera;
    explicitCamera.eye = glm::vec3(node[3]);
    explicitCamera.target = glm::vec3(node[3]) - glm::vec3(node[2]) * 1000.0f;
    explicitCamera.up = glm::vec3(node[1]);
    explicitCamera.yfovDegrees = glm::degrees(scene->cameras[0].yfov);
    for (const auto& [width, height] : {std::pair{800, 600}, std::pair{1920, 1080}}) {
        const Buffers file = render(*llvmpipe, *scene, width, height, {});
        const Buffers given = render(*llvmpipe, *scene, width, height, explicitCamera);
        Result<FrameSetup> setup = setUpFrame(*scene, {}, 0.0, width, height, true);
        ASSERT_TRUE(setup);
        const glm::mat4 stretched = glm::perspective(scene->cameras[0].yfov, 1.0f, setup->view.znear, setup->view.zfar);
        const Buffers old = render(*llvmpipe, *scene, width, height, {}, DepthFormat::D24, stretched);
        const std::size_t pixels = std::size_t(width) * std::size_t(height);
        const double same = meanColourDifference(file, given), stretch = meanColourDifference(file, old);
        std::printf(
            "[ engine %dx%d ] mean colour difference from the explicit camera %.4f (ids differ at %zu of %zu), "
            "from the stretched projection %.2f\n",
            width, height, same, differingIds(file, given), pixels, stretch);
        EXPECT_LT(same, 1.0) << width << "x" << height;
        EXPECT_GT(stretch, 10.0) << width << "x" << height;
    }
}

// With the file's planes (0.05 to 10^6 around an engine 1,200 to 2,000 away) a 24-bit buffer cannot
// tell the blue caps and the fins from what lies just behind them. Z-fighting, counted two ways on
// 800×600: front surfaces (ids) that differ from the d32f render, which separates them; and front
// surfaces that flip when the near plane moves by one part in 10^6, and by 1 %. Fitted: none.
TEST_F(DepthGLTest, TheFittedRangeDoesNotZFight) {
    Result<Scene> scene = loadScene(enginePath());
    ASSERT_TRUE(scene) << scene.error().message;
    const float near = scene->cameras[0].znear;
    const Buffers reference = render(*llvmpipe, *scene, 800, 600, {}, DepthFormat::D32F);
    std::map<std::string, std::size_t> wrong, flips, bigFlips;
    for (const DepthRange range : {DepthRange::Fit, DepthRange::File}) {
        Camera camera;
        camera.depthRange = range;
        const Buffers image = render(*llvmpipe, *scene, 800, 600, camera);
        const std::string name = depthRangeName(range);
        wrong[name] = differingIds(image, reference);
        Camera moved = camera;
        moved.znear = std::max(near * (1.0f + 1e-6f), std::nextafter(near, 1.0f));
        flips[name] = differingIds(image, render(*llvmpipe, *scene, 800, 600, moved));
        moved.znear = near * 1.01f;
        bigFlips[name] = differingIds(image, render(*llvmpipe, *scene, 800, 600, moved));
    }
    std::printf(
        "[ engine 800x600, d24 ] front surfaces other than d32f's: fit %zu, file %zu; flipped by near x "
        "(1 + 1e-6): fit %zu, file %zu; by near x 1.01: fit %zu, file %zu\n",
        wrong["fit"], wrong["file"], flips["fit"], flips["file"], bigFlips["fit"], bigFlips["file"]);
    EXPECT_EQ(wrong["fit"], 0u);
    EXPECT_EQ(flips["fit"], 0u);
    EXPECT_EQ(bigFlips["fit"], 0u);
    EXPECT_GT(wrong["file"], 100u) << "the file's planes z-fight: the test would prove nothing otherwise";
    EXPECT_GT(bigFlips["file"], 100u);
}

// Two parallel squares facing the camera, `gap` apart at distance `d`; the far one is drawn first,
// so where the buffer cannot separate them the first drawn keeps the pixel.
Scene twoPlanes(double d, double gap) {
    Scene scene;
    for (const double z : {-(d + gap), -d}) {
        const float h = float(d * 0.3);
        Mesh mesh;
        mesh.positions = {{-h, -h, float(z)}, {h, -h, float(z)}, {h, h, float(z)}, {-h, h, float(z)}};
        mesh.normals.assign(4, glm::vec3(0, 0, 1));
        mesh.indices = {0, 1, 2, 0, 2, 3};
        mesh.material = 0;
        Node node;
        node.meshes = {int(scene.meshes.size())};
        scene.meshes.push_back(mesh);
        scene.roots.push_back(int(scene.nodes.size()));
        scene.nodes.push_back(node);
    }
    scene.materials.push_back(Material{});
    scene.buildInstances();
    return scene;
}

// The share of pixels the near square owns (its ids are 3 and 4: the far square's are 1 and 2).
double nearShare(const Buffers& b) {
    std::size_t near = 0, covered = 0;
    for (std::uint32_t id : b.ids) {
        covered += id != 0;
        near += id >= 3;
    }
    return covered ? double(near) / double(covered) : 0.0;
}

// Where a buffer cannot separate the squares, which one keeps the pixels is decided by the float
// rounding of each square's depth, the same at every pixel: so every case is drawn at 8 distances
// (d, 1.0137·d, ...). d32f must separate them at all 8; d24, where it cannot, keeps the far square
// on most.
TEST_F(DepthGLTest, D32fSeparatesPlanesAMillionthOfTheirDistanceApartAtEveryRatio) {
    struct Case {
        const char* name;
        double near, far, d;  // far 0 = infinite
        bool d24Separates;
    };
    const Case cases[] = {
        {"ratio 1e2", 1.0, 1e2, 2.0, true},  // 8 steps of 24 bits apart
        {"ratio 1e6", 1.0, 1e6, 1e3, false},
        {"ratio 1e12, coordinates 1e6", 1.0, 1e12, 1e6, false},
        {"infinite far", 1.0, 0.0, 1e3, false},
        {"coordinates 1e-6, ratio 1e6", 1e-9, 1e-3, 1e-6, false},
        {"coordinates 1e6, ratio 1e6", 1e3, 1e9, 1e6, false},
    };
    for (const Case& c : cases) {
        for (const DepthFormat format : {DepthFormat::D24, DepthFormat::D32F}) {
            const std::string label = std::string(c.name) + ", " + depthFormatName(format);
            double shares = 0.0;
            int separated = 0;
            for (int k = 0; k < 8; ++k) {
                const double d = c.d * (1.0 + 0.0137 * k);
                const Scene scene = twoPlanes(d, d * 1e-6);
                Camera camera;
                camera.eye = glm::vec3(0.0f);
                camera.target = glm::vec3(0, 0, -1);
                camera.znear = float(c.near);
                camera.zfar = float(c.far);
                camera.depthRange = DepthRange::File;  // the planes as given: the format alone separates
                const Buffers gl = render(*llvmpipe, scene, 64, 48, camera, format);
                const Buffers sw = render(*software, scene, 64, 48, camera, format);
                test::expectMatches("Extremes-" + label + "-" + std::to_string(k), gl, sw, 1.0, 0);
                EXPECT_EQ(gl.depth, sw.depth) << label << ", distance " << d;
                const double share = nearShare(gl);
                shares += share;
                separated += share == 1.0;
            }
            std::printf("[ %s ] the near square owns every pixel at %d of 8 distances (%.1f %% of the pixels)\n",
                        label.c_str(), separated, 100.0 * shares / 8.0);
            if (format == DepthFormat::D32F || c.d24Separates)
                EXPECT_EQ(separated, 8) << label;
            else
                EXPECT_LT(shares / 8.0, 0.5) << label << ": d24 was expected not to separate them";
        }
    }
}

// The triangle behind an id (frugal/Scene.h: instance firstId + source primitive).
struct Hit {
    const Instance* instance = nullptr;
    std::uint32_t triangle = 0;
};

std::optional<Hit> triangleOf(const Scene& scene, std::uint32_t id) {
    for (const Instance& instance : scene.instances) {
        const Mesh& mesh = scene.meshes[std::size_t(instance.mesh)];
        for (std::uint32_t t = 0; t < mesh.triangleCount(); ++t) {
            const std::uint32_t source = mesh.triangleSource.empty() ? t : mesh.triangleSource[t];
            if (instance.firstId + source == id) return Hit{&instance, t};
        }
    }
    return std::nullopt;
}

// Window depth (D24 convention, 0 near, 1 far) of a triangle's plane at the centre of pixel (x, y),
// in double; nullopt when a vertex is behind the eye.
std::optional<double> planeDepthAt(const Scene& scene, const FrameSetup& setup, const Hit& hit, int x, int y, int width,
                                   int height) {
    const Mesh& mesh = scene.meshes[std::size_t(hit.instance->mesh)];
    const glm::dmat4 mvp = glm::dmat4(setup.params.projection) * glm::dmat4(setup.params.view) *
                           glm::dmat4(setup.world[std::size_t(hit.instance->node)]);
    glm::dvec3 w[3];
    for (int k = 0; k < 3; ++k) {
        const glm::dvec4 c =
            mvp *
            glm::dvec4(glm::dvec3(mesh.positions[mesh.indices[3 * std::size_t(hit.triangle) + std::size_t(k)]]), 1.0);
        if (!(c.w > 0.0)) return std::nullopt;
        w[k] = {(c.x / c.w + 1.0) * 0.5 * width, (c.y / c.w + 1.0) * 0.5 * height, (c.z / c.w + 1.0) * 0.5};
    }
    const glm::dvec3 n = glm::cross(w[1] - w[0], w[2] - w[0]);
    if (n.z == 0.0) return std::nullopt;
    return w[0].z - (n.x * (x + 0.5 - w[0].x) + n.y * (y + 0.5 - w[0].y)) / n.z;
}

// What the default fit changes in the d24 images of the built-in scenes (whose file planes are
// today's): every pixel whose front triangle changes is one where the two triangles lie within two
// 24-bit steps of each other under the file's planes or the fitted ones, i.e. a depth tie that the
// other planes' rounding resolves the other way. Counted and printed; the software reference is
// llvmpipe's bits (SceneGLTest).
TEST_F(DepthGLTest, TheFitChangesOnlyPixelsWhereTrianglesTieInDepth) {
    struct Frame {
        const char* scene;
        double time;
    };
    const Frame frames[] = {{"builtin:default", 0.0},    {"builtin:cubes", 0.0}, {"builtin:cubes", 1.0 / 30},
                            {"builtin:cubes", 2.0 / 30}, {"builtin:cubes", 0.5}, {"builtin:materials", 0.0}};
    std::size_t changed = 0, explained = 0;
    for (const Frame& f : frames) {
        Result<Scene> scene = loadScene(f.scene);
        ASSERT_TRUE(scene) << scene.error().message;
        const int width = 800, height = 600;
        Camera fileCamera, fitCamera;
        fileCamera.depthRange = DepthRange::File;
        const auto frameAt = [&](const Camera& camera) {
            const test::RenderedFrame r =
                test::renderScene(*software, *scene, width, height, f.time, true, kBackground, camera);
            return r.buffers;
        };
        const Buffers file = frameAt(fileCamera), fit = frameAt(fitCamera);
        Result<FrameSetup> fileSetup = setUpFrame(*scene, fileCamera, f.time, width, height, true);
        Result<FrameSetup> fitSetup = setUpFrame(*scene, fitCamera, f.time, width, height, true);
        ASSERT_TRUE(fileSetup && fitSetup);
        std::size_t here = 0;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
                if (file.ids[i] == fit.ids[i]) continue;
                ++here;
                const std::optional<Hit> a = triangleOf(*scene, file.ids[i]), b = triangleOf(*scene, fit.ids[i]);
                ASSERT_TRUE(a && b) << f.scene << ": a covered pixel became background or the reverse at " << x << ", "
                                    << y;
                bool tie = false;
                for (const FrameSetup* setup : {&*fileSetup, &*fitSetup}) {
                    const std::optional<double> za = planeDepthAt(*scene, *setup, *a, x, y, width, height);
                    const std::optional<double> zb = planeDepthAt(*scene, *setup, *b, x, y, width, height);
                    tie = tie || (za && zb && std::abs(*za - *zb) * 16777215.0 <= 2.0);
                }
                explained += tie;
                EXPECT_TRUE(tie) << f.scene << " t " << f.time << ": pixel " << x << ", " << y << " changed from id "
                                 << file.ids[i] << " to " << fit.ids[i] << " without a depth tie";
            }
        std::printf("[ %s t=%.3f ] %zu pixels change triangle under the fitted planes\n", f.scene, f.time, here);
        changed += here;
    }
    std::printf("[ built-in scenes ] %zu pixels changed, %zu of them depth ties\n", changed, explained);
}

}  // namespace
}  // namespace frugal
