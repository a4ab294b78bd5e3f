// The regression matrix: GL (llvmpipe) against the software reference on built-in scenes, the bunny
// and an "extremes" set generated here, with each case's tolerance stated in one table. A failing
// case writes actual, reference and error-mask PNGs to FRUGAL_TEST_OUTPUT_DIR/matrix-<case>/.
// (The assimp glTF models and texture sampling are in SceneGLTest; single triangles in
// CoverageGLTest.)
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <random>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "GlReference.h"
#include "lab/ImageCompare.h"
#include "pipeline/Frame.h"
#include "pipeline/SceneRenderer.h"
#include "scene/Load.h"
#include "scene/MeshBuild.h"
#include "software/Shading.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

// What a case may differ by. Everything measured so far is exact; a wider tolerance must say why.
struct Tolerance {
    std::size_t coverage = 0;      // pixels covered on one side only
    std::uint32_t depthLsb = 0;    // 24-bit steps
    double idAgreement = 0.9999;   // share of pixels with the same id (the task's bar)
    int colour = 1;                // 8-bit steps (the task's bar)
    double colourShare = 0.001;    // of the covered pixels, the share whose colour differs at all
};

struct MatrixCase {
    std::string name;
    std::function<Scene()> scene;
    int width, height;
    Camera camera;
    Tolerance tolerance;
    ToneMap tonemap = ToneMap::None;
    int samples = 1;  // 4: multisampled, resolved (raster/Rasterizer.h, 6.)
    ShadingModel shading = ShadingModel::Full;
    bool environmentSpecular = true;  // false: the environment's diffuse lobe alone (Lighting)
    bool environmentMap = false;      // lit by test::testSky's map instead of the uniform environment
    // A float target (ColorFormat::Rgba32F): the linear colours must also agree within kLinearTolerance
    // (the 8-bit images are their display encoding, compared as above).
    bool linear = false;
};

// What the linear colours of GL and the reference may differ by, relative to the larger of the two
// (or to 1e-3 below it): 0.1 % for all but 0.01 % of the values, 1 % for every one. The shading's
// operations differ where llvmpipe's sqrt, pow, exp2 and division round otherwise than the
// reference's, and texture filtering where its 8-bit paths round a texel's weights (Shading.h): the
// 8-bit images show these as one level on a few pixels. Measured on these cases: at most 9 values
// beyond 0.1 % (of 690,000), the worst 0.76 % (a clear coat under the sky map).
constexpr double kLinearTolerance = 1e-3, kLinearShare = 1e-4, kLinearWorst = 1e-2;

// How many values of two linear images differ by more than kLinearTolerance (both the same size), and
// the largest relative difference.
std::pair<std::size_t, double> linearDifferences(const std::vector<float>& a, const std::vector<float>& b) {
    std::size_t beyond = 0;
    double worst = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const double x = a[i], y = b[i], scale = std::max({std::fabs(x), std::fabs(y), 1e-3});
        const double relative = std::fabs(x - y) / scale;
        if (!(relative <= kLinearTolerance)) ++beyond;  // NaN on one side counts
        if (relative > worst) worst = relative;
    }
    return {beyond, worst};
}

// The sky of the environment cases, prefiltered once.
std::shared_ptr<const EnvironmentMap> skyMap() {
    static const std::shared_ptr<const EnvironmentMap> map =
        prefilterEnvironment(HdrImage{128, 64, test::testSky(128, 64)}, "test sky", 2);
    return map;
}

Scene loaded(const std::string& spec) {
    Result<Scene> scene = loadScene(spec);
    EXPECT_TRUE(scene) << scene.error().message;
    return scene ? std::move(*scene) : Scene{};
}

// One instance of `mesh` (finalised unless `raw`), white single- or double-sided material.
Scene single(Mesh mesh, bool doubleSided = true, bool raw = false) {
    if (!raw) finalizeMesh(mesh, true);
    Material material;
    material.baseColorFactor = {0.9f, 0.7f, 0.4f, 1.0f};
    material.doubleSided = doubleSided;
    return test::oneMeshScene(std::move(mesh), material);
}

// A UV sphere of radius `r` centred at `c`: smooth normals, a range of triangle sizes and slopes.
Mesh sphere(float r, const glm::vec3& c = glm::vec3(0.0f), int rings = 24, int segments = 48) {
    Mesh mesh;
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j <= segments; ++j) {
            const float theta = glm::pi<float>() * float(i) / float(rings);
            const float phi = glm::two_pi<float>() * float(j) / float(segments);
            const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            mesh.positions.push_back(c + r * n);
            mesh.normals.push_back(n);
            mesh.uvs.push_back({float(j) / float(segments), float(i) / float(rings)});
        }
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const std::uint32_t a = std::uint32_t(i * (segments + 1) + j), b = a + std::uint32_t(segments + 1);
            mesh.indices.insert(mesh.indices.end(), {a, a + 1, b, a + 1, b + 1, b});
        }
    return mesh;
}

// Spheres from 0.01 to 900 units away: with near 1e-3 and far 1e3 the near/far ratio is 1e6.
Scene depthRange() {
    Mesh mesh;
    float distance = 0.01f;
    for (int k = 0; k < 8; ++k, distance *= 3.5f) {
        Mesh s = sphere(distance * 0.3f, glm::vec3(distance * 0.4f * float(k % 3 - 1), 0.0f, -distance), 12, 24);
        const auto base = std::uint32_t(mesh.positions.size());
        mesh.positions.insert(mesh.positions.end(), s.positions.begin(), s.positions.end());
        mesh.normals.insert(mesh.normals.end(), s.normals.begin(), s.normals.end());
        for (std::uint32_t i : s.indices) mesh.indices.push_back(base + i);
    }
    return single(mesh);
}

// Long thin triangles fanning through the view, some nearly edge-on.
Scene slivers() {
    Mesh mesh;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int t = 0; t < 400; ++t) {
        const glm::vec3 a(u(rng) * 3, u(rng) * 3, u(rng));
        const glm::vec3 dir = glm::normalize(glm::vec3(u(rng), u(rng), u(rng) * 0.2f));
        const glm::vec3 side = glm::normalize(glm::cross(dir, glm::vec3(0, 0, 1))) * (1e-3f + 1e-2f * (u(rng) + 1));
        const auto base = std::uint32_t(mesh.positions.size());
        mesh.positions.insert(mesh.positions.end(), {a, a + dir * 6.0f, a + dir * 6.0f + side});
        mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
    }
    return single(mesh);
}

// A ground plane 1e5 across under a camera 1 unit above it: triangles far larger than the viewport
// that cross the near plane and every side plane.
Scene groundPlane() {
    Mesh mesh;
    const float h = 5e4f;
    mesh.positions = {{-h, 0, -h}, {-h, 0, h}, {h, 0, h}, {h, 0, -h}, {0, 0.5f, -3}, {2, 0.5f, -6}, {-2, 1.5f, -6}};
    mesh.indices = {0, 1, 2, 0, 2, 3, 4, 5, 6};
    return single(mesh);
}

// Vertices exactly on pixel centres and pixel edges of a 64×48 target (orthographic camera with one
// world unit a pixel): the fill rule decides every shared edge.
Scene pixelGrid() {
    Mesh mesh;
    for (int y = 0; y <= 12; ++y)
        for (int x = 0; x <= 16; ++x) {
            const float offset = (x + y) % 2 ? 0.5f : 0.0f;  // alternate centres and edges
            mesh.positions.push_back({float(x * 4) + offset - 32.0f, float(y * 4) + offset - 24.0f, 0.0f});
        }
    for (int y = 0; y < 12; ++y)
        for (int x = 0; x < 16; ++x) {
            const std::uint32_t a = std::uint32_t(y * 17 + x), b = a + 17;
            mesh.indices.insert(mesh.indices.end(), {a, a + 1, b + 1, a, b + 1, b});
        }
    Scene scene = single(mesh);
    SceneCamera camera;
    camera.perspective = false;
    camera.xmag = 32.0f;
    camera.ymag = 24.0f;
    camera.znear = 1.0f;
    camera.zfar = 20.0f;
    test::addCameraNode(scene, camera, {0, 0, 10});
    return scene;
}

// NaN and Inf positions handed to the backends as they are (no finalizeMesh): both must drop the
// same triangles and draw the rest identically.
Scene nonFinite() {
    Mesh mesh = sphere(1.0f);
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (std::size_t i = 0; i < mesh.positions.size(); i += 37) mesh.positions[i].x = (i / 37) % 2 ? nan : inf;
    for (std::size_t i = 5; i < mesh.positions.size(); i += 53) mesh.positions[i].z = -inf;
    return single(mesh, true, true);
}

// `mesh` with a material of its own, placed at `at`.
void place(Scene& scene, Mesh mesh, const Material& material, glm::vec3 at) {
    mesh.material = *scene.addMaterial(material);
    const int index = *scene.addMesh(std::move(mesh), false);
    (void)scene.addInstance(index, glm::translate(glm::mat4(1.0f), at));
}

// A texture of random texels.
int randomTexture(Scene& scene, std::mt19937& rng, int w, int h, bool srgb, Filter filter, Wrap wrap) {
    Texture t;
    t.width = w;
    t.height = h;
    t.srgb = srgb;
    t.filter = t.minFilter = filter;
    t.wrapS = t.wrapT = wrap;
    for (int i = 0; i < w * h * 4; ++i) t.rgba.push_back(std::uint8_t(rng() & 0xFFu));
    return *scene.addTexture(std::move(t));
}

// Spheres of every corner of the material space, metallic {0, 0.5, 1} × roughness {0, 0.02, 0.25, 0.6,
// 1}, in three base colours, one of them unlit and one emissive; their silhouettes show grazing angles, and the
// smooth ones the light's highlight at its sharpest.
Scene materials() {
    Scene scene;
    const float metallic[] = {0.0f, 0.5f, 1.0f}, roughness[] = {0.0f, 0.02f, 0.25f, 0.6f, 1.0f};
    const glm::vec4 colours[] = {{0.9f, 0.7f, 0.4f, 1.0f}, {0.05f, 0.3f, 0.8f, 1.0f}, {1.0f, 1.0f, 1.0f, 1.0f}};
    Mesh mesh = sphere(0.45f, glm::vec3(0.0f), 32, 64);
    finalizeMesh(mesh, true);
    for (int m = 0; m < 3; ++m)
        for (int r = 0; r < 5; ++r) {
            Material material;
            material.baseColorFactor = colours[(m + r) % 3];
            material.metallicFactor = metallic[m];
            material.roughnessFactor = roughness[r];
            material.unlit = m == 1 && r == 4;
            if (m == 2 && r == 1) material.emissiveFactor = {0.6f, 0.2f, 0.05f};
            place(scene, mesh, material, {float(r) - 2.0f, float(m) - 1.0f, 0.0f});
        }
    scene.buildInstances();
    return scene;
}

// The maps (Material): metallic-roughness, occlusion at strengths 0, 0.5 and 1, emissive, all of
// them with a base colour texture and a texture transform, on an unlit material (which ignores
// them), with nearest and mirrored samplers; textures of generated values, linear data and sRGB.
Scene maps() {
    Scene scene;
    std::mt19937 rng(38);
    const auto texture = [&](int w, int h, bool srgb, Filter filter, Wrap wrap) {
        return randomTexture(scene, rng, w, h, srgb, filter, wrap);
    };
    const int mr = texture(8, 8, false, Filter::Linear, Wrap::Repeat);
    const int mrNearest = texture(5, 3, false, Filter::Nearest, Wrap::MirroredRepeat);
    const int occlusion = texture(16, 4, false, Filter::Linear, Wrap::ClampToEdge);
    const int emissive = texture(4, 4, true, Filter::Linear, Wrap::Repeat);
    const int base = texture(6, 6, true, Filter::Linear, Wrap::MirroredRepeat);
    std::vector<Material> materials(12);
    materials[0].metallicRoughnessTexture = mr;
    materials[1].metallicRoughnessTexture = mrNearest;
    materials[1].baseColorFactor = {0.9f, 0.5f, 0.2f, 1.0f};
    for (int k = 0; k < 3; ++k) {
        materials[std::size_t(2 + k)].occlusionTexture = occlusion;
        materials[std::size_t(2 + k)].occlusionStrength = float(k) * 0.5f;
        materials[std::size_t(2 + k)].metallicFactor = float(k) * 0.5f;
        materials[std::size_t(2 + k)].roughnessFactor = 0.3f;
    }
    materials[5].emissiveTexture = emissive;
    materials[5].emissiveFactor = {1.0f, 0.8f, 0.5f};
    materials[5].metallicFactor = 0.0f;
    for (int k : {6, 7, 8}) {
        Material& m = materials[std::size_t(k)];
        m.baseColorTexture = base;
        m.metallicRoughnessTexture = mr;
        m.occlusionTexture = occlusion;
        m.occlusionStrength = 0.7f;
        m.emissiveTexture = emissive;
        m.emissiveFactor = {0.3f, 0.3f, 0.3f};
    }
    materials[7].baseColorTransform = glm::mat3(glm::vec3(2.0f, 1.0f, 0.0f), glm::vec3(-1.5f, 3.0f, 0.0f),
                                                glm::vec3(0.25f, -0.5f, 1.0f));
    materials[8].unlit = true;
    materials[9].metallicRoughnessTexture = mr;
    materials[9].metallicFactor = 0.0f;  // the map scales factors: 0 stays 0
    materials[10].metallicRoughnessTexture = mrNearest;
    materials[10].roughnessFactor = 0.0f;
    materials[11].emissiveTexture = emissive;  // a factor of 0: no emission
    Mesh mesh = sphere(0.45f, glm::vec3(0.0f), 24, 48);
    finalizeMesh(mesh, true);
    for (int k = 0; k < 12; ++k)
        place(scene, mesh, materials[std::size_t(k)], {float(k % 4) - 1.5f, float(k / 4) - 1.0f, 0.0f});
    scene.buildInstances();
    return scene;
}

// KHR_materials_pbrSpecularGlossiness: specular colours grey (0.04, 0.2) and coloured, glossiness
// 0, 0.5 and 1, a specular-glossiness map (sRGB rgb, linear alpha; nearest and linear) with and
// without a diffuse texture, an occlusion map beside it, a metallic-roughness map it must ignore
// and an unlit one.
Scene specularGlossiness() {
    Scene scene;
    std::mt19937 rng(41);
    const int map = randomTexture(scene, rng, 8, 8, true, Filter::Linear, Wrap::Repeat);
    const int nearest = randomTexture(scene, rng, 5, 7, true, Filter::Nearest, Wrap::MirroredRepeat);
    const int diffuse = randomTexture(scene, rng, 6, 6, true, Filter::Linear, Wrap::Repeat);
    const int data = randomTexture(scene, rng, 4, 4, false, Filter::Linear, Wrap::ClampToEdge);
    Mesh mesh = sphere(0.45f, glm::vec3(0.0f), 24, 48);
    finalizeMesh(mesh, true);
    const glm::vec3 speculars[] = {glm::vec3(0.04f), glm::vec3(0.2f), {0.9f, 0.6f, 0.2f}, glm::vec3(1.0f)};
    const float glossiness[] = {0.0f, 0.5f, 1.0f};
    for (int k = 0; k < 12; ++k) {
        Material m;
        m.specularGlossiness = true;
        m.baseColorFactor = {0.5f, 0.6f, 0.8f, 1.0f};
        m.specularFactor = speculars[k % 4];
        m.glossinessFactor = glossiness[k % 3];
        m.metallicFactor = 1.0f;  // not read
        if (k >= 4) m.specularGlossinessTexture = k % 2 ? map : nearest;
        if (k >= 6) m.baseColorTexture = diffuse;
        if (k == 8) m.occlusionTexture = data;
        if (k == 9) m.metallicRoughnessTexture = data;  // not read
        if (k == 10) m.emissiveFactor = {0.2f, 0.1f, 0.0f};
        m.unlit = k == 11;
        place(scene, mesh, m, {float(k % 4) - 1.5f, float(k / 4) - 1.0f, 0.0f});
    }
    scene.buildInstances();
    return scene;
}

// Alpha. Top row: masked spheres, a random texture's alpha against cutoffs 0, 0.3, 0.5 and 1,
// nearest and linear, three of them double-sided so that their inside shows through the holes.
// Below, over an opaque backdrop that covers half of them (the rest blend over the background):
// blended spheres with alpha from the factor, from vertex colours and from a texture, a
// double-sided one whose back faces blend under its front, two that overlap (drawn far to near),
// and alphas of 0 (colour unchanged; depth and ids written) and 1.
Scene alpha() {
    Scene scene;
    std::mt19937 rng(40);
    const int holes = randomTexture(scene, rng, 8, 8, true, Filter::Nearest, Wrap::Repeat);
    const int smooth = randomTexture(scene, rng, 6, 6, true, Filter::Linear, Wrap::Repeat);
    Mesh mesh = sphere(0.45f, glm::vec3(0.0f), 24, 48);
    finalizeMesh(mesh, true);
    const float cutoffs[] = {0.0f, 0.3f, 0.5f, 1.0f};
    for (int k = 0; k < 4; ++k) {
        Material m;
        m.baseColorTexture = k % 2 ? holes : smooth;
        m.alphaMode = AlphaMode::Mask;
        m.alphaCutoff = cutoffs[k];
        m.doubleSided = k != 2;
        m.metallicFactor = 0.0f;
        m.roughnessFactor = 0.4f;
        place(scene, mesh, m, {float(k) - 1.5f, 1.0f, 0.0f});
    }
    Mesh backdrop;
    backdrop.positions = {{-2.6f, -2.0f, -1.0f}, {0.2f, -2.0f, -1.0f}, {0.2f, 0.5f, -1.0f}, {-2.6f, 0.5f, -1.0f}};
    backdrop.indices = {0, 1, 2, 0, 2, 3};
    finalizeMesh(backdrop, false);
    Material opaque;
    opaque.baseColorFactor = {0.2f, 0.5f, 0.3f, 0.3f};  // its alpha is ignored: written as 1
    opaque.metallicFactor = 0.0f;
    place(scene, backdrop, opaque, {0.0f, 0.0f, 0.0f});
    Material blend;
    blend.alphaMode = AlphaMode::Blend;
    blend.metallicFactor = 0.0f;
    blend.roughnessFactor = 0.5f;
    blend.baseColorFactor = {0.9f, 0.3f, 0.2f, 0.5f};
    place(scene, mesh, blend, {-1.5f, -0.1f, 0.0f});
    Mesh coloured = mesh;
    coloured.colors.resize(coloured.positions.size());
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (glm::vec4& c : coloured.colors) c = {u(rng), u(rng), u(rng), u(rng)};
    blend.baseColorFactor = {1.0f, 1.0f, 1.0f, 1.0f};
    place(scene, coloured, blend, {-0.5f, -0.1f, 0.0f});
    blend.baseColorTexture = smooth;
    blend.doubleSided = true;
    place(scene, mesh, blend, {0.5f, -0.1f, 0.0f});
    blend.baseColorTexture = -1;
    blend.baseColorFactor = {0.2f, 0.4f, 0.9f, 0.35f};
    place(scene, mesh, blend, {1.5f, -0.1f, 0.0f});
    blend.doubleSided = false;
    place(scene, mesh, blend, {-0.25f, -1.2f, 0.0f});
    blend.baseColorFactor = {0.9f, 0.9f, 0.2f, 0.6f};
    place(scene, mesh, blend, {0.25f, -1.2f, 0.4f});
    blend.baseColorFactor.a = 0.0f;
    place(scene, mesh, blend, {-1.6f, -1.2f, 0.0f});
    blend.baseColorFactor.a = 1.0f;
    place(scene, mesh, blend, {1.6f, -1.2f, 0.0f});
    scene.buildInstances();
    return scene;
}

// Normal maps of generated texels at scales 0, 1, 10 and −1, in the basis of generated tangents
// (from the sphere's uvs, when the renderer uploads it) and of the file's (random unit vectors, w
// ±1), with mipmap-less linear and nearest samplers; one double-sided (its inside seen through a cut).
// `mesh` without the triangles whose first vertex lies at z >= 0.3 (a sphere's front cap: its inside
// shows).
Mesh withoutFrontCap(Mesh mesh) {
    std::vector<std::uint32_t> kept;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        if (mesh.positions[mesh.indices[3 * t]].z < 0.3f)
            kept.insert(kept.end(), mesh.indices.begin() + std::ptrdiff_t(3 * t),
                        mesh.indices.begin() + std::ptrdiff_t(3 * t + 3));
    mesh.indices = kept;
    mesh.triangleSource.clear();
    finalizeMesh(mesh, false);
    return mesh;
}

// Tangents as a file might give them: random unit directions, random handedness.
void giveRandomTangents(Mesh& mesh, std::mt19937& rng) {
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        const glm::vec3 d = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(0.01f));
        mesh.tangents.push_back(glm::vec4(d, u(rng) < 0.0f ? -1.0f : 1.0f));
    }
}

Scene normalMaps() {
    Scene scene;
    std::mt19937 rng(39);
    const int linear = randomTexture(scene, rng, 8, 8, false, Filter::Linear, Wrap::Repeat);
    const int nearest = randomTexture(scene, rng, 7, 5, false, Filter::Nearest, Wrap::Repeat);
    Mesh mesh = sphere(0.45f, glm::vec3(0.0f), 24, 48);
    finalizeMesh(mesh, true);
    const Mesh cut = withoutFrontCap(mesh);
    const float scales[] = {0.0f, 1.0f, 10.0f, -1.0f};
    for (int k = 0; k < 8; ++k) {
        Material material;
        material.baseColorFactor = {0.8f, 0.6f, 0.3f, 1.0f};
        material.metallicFactor = k % 3 == 0 ? 1.0f : 0.0f;
        material.roughnessFactor = 0.2f + 0.1f * float(k);
        material.normalTexture = k % 2 ? nearest : linear;
        material.normalScale = scales[k % 4];
        material.doubleSided = k == 7;
        Mesh copy = k == 7 ? cut : mesh;
        if (k >= 4 && k < 7) giveRandomTangents(copy, rng);  // the file's tangents
        place(scene, std::move(copy), material, {float(k % 4) - 1.5f, float(k / 4) - 0.5f, 0.0f});
    }
    scene.buildInstances();
    return scene;
}

// KHR_materials_clearcoat: coats of roughness 0, 0.03 and 1 over a rough dielectric and over a
// metal, at factors 1 and 0.5; a coat map (nearest) and a coat roughness map (linear); coat normal
// maps at scales 1 and 10, with generated tangents and with the file's, beside a base normal map
// and alone; a coat over specular-glossiness, over an occluded emissive surface, on the inside of
// a double-sided sphere, on a blended surface, and on an unlit one (which ignores it).
Scene clearcoat() {
    Scene scene;
    std::mt19937 rng(42);
    const int coatMap = randomTexture(scene, rng, 5, 7, false, Filter::Nearest, Wrap::Repeat);
    const int roughnessMap = randomTexture(scene, rng, 8, 8, false, Filter::Linear, Wrap::MirroredRepeat);
    const int normals = randomTexture(scene, rng, 8, 8, false, Filter::Linear, Wrap::Repeat);
    const int data = randomTexture(scene, rng, 4, 4, false, Filter::Linear, Wrap::ClampToEdge);
    Mesh mesh = sphere(0.45f, glm::vec3(0.0f), 24, 48);
    finalizeMesh(mesh, true);
    const Mesh cut = withoutFrontCap(mesh);
    const float coatRoughness[] = {0.0f, 0.03f, 1.0f};
    for (int k = 0; k < 16; ++k) {
        Material m;
        m.baseColorFactor = {0.5f, 0.02f, 0.01f, 1.0f};
        m.metallicFactor = k == 3 ? 1.0f : 0.0f;
        m.roughnessFactor = 0.44f;
        m.clearcoatFactor = k == 3 ? 0.5f : 1.0f;
        m.clearcoatRoughnessFactor = coatRoughness[k % 3];
        Mesh copy = k == 12 ? cut : mesh;
        if (k == 4) m.clearcoatTexture = coatMap;
        if (k == 5) m.clearcoatRoughnessTexture = roughnessMap;
        if (k >= 6 && k <= 9) m.clearcoatNormalTexture = normals;
        m.clearcoatNormalScale = k == 7 ? 10.0f : 1.0f;
        if (k == 8) m.normalTexture = data;
        if (k == 9) giveRandomTangents(copy, rng);  // the file's tangents
        if (k == 10) {
            m.specularGlossiness = true;
            m.specularFactor = {0.9f, 0.6f, 0.2f};
            m.glossinessFactor = 0.5f;
        }
        if (k == 11) {
            m.occlusionTexture = data;
            m.emissiveFactor = {0.3f, 0.2f, 0.1f};
        }
        m.doubleSided = k == 12;
        if (k == 13) {
            m.alphaMode = AlphaMode::Blend;
            m.baseColorFactor.a = 0.4f;
        }
        m.unlit = k == 14;
        if (k == 15) m.clearcoatFactor = 0.0f;  // no coat: its maps are not read
        if (k == 15) m.clearcoatNormalTexture = normals;
        place(scene, std::move(copy), m, {float(k % 4) - 1.5f, float(k / 4) - 1.5f, 0.0f});
    }
    scene.buildInstances();
    return scene;
}

// Mipmaps: strips of floor receding from the camera, magnified near it and minified to the last
// level far away, each under another sampler: mipmaps none, nearest and linear; minification nearest
// and linear under either magnification (glTF's NEAREST_MIPMAP_LINEAR under LINEAR, BoxTextured's);
// sRGB and linear data (llvmpipe's float and 8-bit paths); repeat, clamp and mirrored; sizes 64×64,
// 37×23, 16×64 and 1×1; one strip with a rotating, stretching texture transform. Behind them, a
// sphere whose texture shrinks to a few pixels.
Scene mipmaps() {
    Scene scene;
    std::mt19937 rng(39);
    struct Sampler {
        int w, h;
        bool srgb;
        Filter mag, min;
        MipFilter mip;
        Wrap wrap;
    };
    constexpr Filter N = Filter::Nearest, L = Filter::Linear;
    const Sampler samplers[] = {
        {64, 64, true, L, L, MipFilter::Linear, Wrap::Repeat},
        {64, 64, false, L, L, MipFilter::Linear, Wrap::Repeat},
        {64, 64, false, L, N, MipFilter::Linear, Wrap::Repeat},
        {64, 64, true, L, N, MipFilter::Linear, Wrap::MirroredRepeat},
        {37, 23, false, L, L, MipFilter::Nearest, Wrap::ClampToEdge},
        {37, 23, true, N, N, MipFilter::Nearest, Wrap::Repeat},
        {32, 32, false, N, L, MipFilter::None, Wrap::Repeat},
        {16, 64, false, L, N, MipFilter::Linear, Wrap::MirroredRepeat},
        {64, 64, true, L, L, MipFilter::Linear, Wrap::Repeat},
        {1, 1, true, L, L, MipFilter::Linear, Wrap::Repeat},
    };
    const int strips = int(std::size(samplers));
    for (int k = 0; k < strips; ++k) {
        const Sampler& sampler = samplers[k];
        const int texture = randomTexture(scene, rng, sampler.w, sampler.h, sampler.srgb, sampler.mag, sampler.wrap);
        scene.textures[std::size_t(texture)].minFilter = sampler.min;
        scene.textures[std::size_t(texture)].mipmaps = sampler.mip;
        Material m;
        m.baseColorTexture = texture;
        m.metallicFactor = 0.0f;
        if (k == 8)  // rotated and stretched: footprints longer along one axis than the other
            m.baseColorTransform =
                glm::mat3(glm::vec3(0.8f, 0.6f, 0.0f), glm::vec3(-2.4f, 3.2f, 0.0f), glm::vec3(0.1f, 0.2f, 1.0f));
        Mesh strip;
        const float x0 = float(k) - float(strips) * 0.5f, x1 = x0 + 0.95f;
        strip.positions = {{x0, 0.0f, 2.0f}, {x1, 0.0f, 2.0f}, {x1, 0.0f, -60.0f}, {x0, 0.0f, -60.0f}};
        strip.normals.assign(4, glm::vec3(0.0f, 1.0f, 0.0f));
        strip.uvs = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 40.0f}, {0.0f, 40.0f}};
        strip.indices = {0, 1, 2, 0, 2, 3};
        place(scene, std::move(strip), m, {0.0f, -1.0f, 0.0f});
    }
    Mesh ball = sphere(0.6f, glm::vec3(0.0f), 24, 48);
    finalizeMesh(ball, true);
    Material m;
    m.baseColorTexture = 0;
    m.roughnessFactor = 0.5f;
    place(scene, std::move(ball), m, {1.0f, 0.2f, -12.0f});
    scene.buildInstances();
    return scene;
}

// Colours from black to far past white for the tone-mapping operators: the material spheres, each
// also emissive, from 0 to 6 in hues of every kind, beside unlit and blended ones.
Scene bright() {
    Scene scene = materials();
    for (std::size_t k = 0; k < scene.materials.size(); ++k) {
        Material& m = scene.materials[k];
        const float level = float(k) * 0.4f;
        m.emissiveFactor = glm::vec3(level, level * float(k % 3) * 0.5f, level * float(k % 5) * 0.25f);
        if (k == 4) {
            m.alphaMode = AlphaMode::Blend;
            m.baseColorFactor.a = 0.5f;
        }
    }
    return scene;
}

// KHR_lights_punctual: a floor and spheres of every kind of material (dielectric, metal, rough
// and smooth, specular-glossiness, clear-coated, textured, unlit, blended) under a coloured
// directional light, a point light whose range ends on the floor (so pixels lie beyond it, at it and
// near it), an unbounded point light close to a sphere, and two spot lights whose cones' edges
// cross the floor (one with equal inner and outer angles but for a hair), on nodes rotated, scaled
// and parented.
Scene lights() {
    Scene scene;
    std::mt19937 rng(40);
    Mesh floor;
    floor.positions = {{-6.0f, -1.0f, 4.0f}, {6.0f, -1.0f, 4.0f}, {6.0f, -1.0f, -6.0f}, {-6.0f, -1.0f, -6.0f}};
    floor.normals.assign(4, glm::vec3(0.0f, 1.0f, 0.0f));
    floor.uvs = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
    floor.indices = {0, 1, 2, 0, 2, 3};
    Material plain;
    plain.baseColorFactor = {0.8f, 0.8f, 0.8f, 1.0f};
    plain.metallicFactor = 0.0f;
    plain.roughnessFactor = 0.6f;
    place(scene, std::move(floor), plain, {0.0f, 0.0f, 0.0f});
    const int texture = randomTexture(scene, rng, 8, 8, true, Filter::Linear, Wrap::Repeat);
    Mesh ball = sphere(0.45f, glm::vec3(0.0f), 24, 48);
    finalizeMesh(ball, true);
    for (int k = 0; k < 8; ++k) {
        Material m;
        m.baseColorFactor = {0.9f, 0.6f, 0.3f, 1.0f};
        m.metallicFactor = k == 1 || k == 2 ? 1.0f : 0.0f;
        m.roughnessFactor = k == 2 ? 0.05f : 0.5f;
        if (k == 3) {
            m.specularGlossiness = true;
            m.specularFactor = {0.9f, 0.6f, 0.2f};
            m.glossinessFactor = 0.7f;
        }
        if (k == 4) {
            m.clearcoatFactor = 1.0f;
            m.clearcoatRoughnessFactor = 0.1f;
        }
        if (k == 5) m.baseColorTexture = texture;
        m.unlit = k == 6;
        if (k == 7) {
            m.alphaMode = AlphaMode::Blend;
            m.baseColorFactor.a = 0.5f;
        }
        place(scene, ball, m, {float(k % 4) * 1.4f - 2.1f, -0.5f, float(k / 4) * -1.6f});
    }
    const auto light = [&](LightType type, glm::vec3 color, float intensity, float range, float inner, float outer,
                           glm::vec3 at, glm::quat rotation, int parent) {
        PunctualLight l;
        l.type = type;
        l.color = color;
        l.intensity = intensity;
        l.range = range;
        l.innerConeAngle = inner;
        l.outerConeAngle = outer;
        scene.lights.push_back(l);
        Node node;
        node.translation = at;
        node.rotation = rotation;
        node.light = int(scene.lights.size()) - 1;
        node.parent = parent;
        scene.nodes.push_back(node);
        const int index = int(scene.nodes.size()) - 1;
        if (parent < 0)
            scene.roots.push_back(index);
        else
            scene.nodes[std::size_t(parent)].children.push_back(index);
        return index;
    };
    const glm::quat down = glm::angleAxis(glm::radians(-90.0f), glm::vec3(1.0f, 0.0f, 0.0f));
    light(LightType::Directional, {1.0f, 0.9f, 0.7f}, 1.5f, 0.0f, 0.0f, 0.0f, {0.0f, 5.0f, 0.0f},
          glm::angleAxis(glm::radians(-60.0f), glm::normalize(glm::vec3(1.0f, 0.3f, 0.0f))), -1);
    light(LightType::Point, {0.2f, 0.5f, 1.0f}, 8.0f, 2.5f, 0.0f, 0.0f, {-2.0f, 0.5f, 1.0f}, glm::quat(1, 0, 0, 0), -1);
    const int holder = light(LightType::Point, {1.0f, 0.3f, 0.3f}, 2.0f, 0.0f, 0.0f, 0.0f, {0.7f, 0.3f, 0.6f},
                             glm::quat(1, 0, 0, 0), -1);
    scene.nodes[std::size_t(holder)].scale = glm::vec3(2.0f);  // a scaled parent: the child's axis stays unit
    light(LightType::Spot, {1.0f, 1.0f, 0.8f}, 30.0f, 0.0f, 0.2f, 0.45f, {0.5f, 1.0f, 0.0f}, down, holder);
    light(LightType::Spot, {0.6f, 1.0f, 0.6f}, 20.0f, 6.0f, 0.3f, 0.3001f, {2.0f, 3.0f, -2.0f}, down, -1);
    scene.buildInstances();
    return scene;
}

Scene scaled(float scale) {
    Mesh mesh = sphere(scale);
    for (glm::vec3& p : mesh.positions) p += glm::vec3(scale * 0.3f, -scale * 0.2f, 0.0f);
    return single(mesh, false);
}

Camera lookFrom(glm::vec3 eye, glm::vec3 target, float znear, float zfar) {
    Camera spec;
    spec.eye = eye;
    spec.target = target;
    spec.znear = znear;
    spec.zfar = zfar;
    return spec;
}

Scene morphExtreme() { return test::morphingScene({-1.0f, 10.0f}); }
Scene morphUnnormal() { return test::morphingScene({0.3f, 0.3f}); }
Scene skinCollapsed() { return test::skinnedScene(0.0f); }
Scene skinHuge() { return test::skinnedScene(1e4f); }
Scene skinUnnormal() { return test::skinnedScene(2.0f, false); }
Scene pointsLines() { return test::pointsLinesScene(); }

std::vector<MatrixCase> matrix() {
    const std::string bunny = FRUGAL_BUNNY_OBJ;
    std::vector<MatrixCase> cases = {
        {"default-800x600", [] { return loaded("builtin:default"); }, 800, 600, {}, {}},
        {"default-1920x1080", [] { return loaded("builtin:default"); }, 1920, 1080, {}, {}},
        {"default-61x47", [] { return loaded("builtin:default"); }, 61, 47, {}, {}},
        {"dominoes1404-800x600",
         [] { return loaded("builtin:dominoes?polygons=1404&static=0.9866"); },
         800,
         600,
         {},
         {}},
        {"cubes-800x600", [] { return loaded("builtin:cubes"); }, 800, 600, {}, {}},
        {"bunny-800x600", [bunny] { return loaded(bunny); }, 800, 600, {}, {}},
        {"bunny-1920x1080", [bunny] { return loaded(bunny); }, 1920, 1080, {}, {}},
        {"bunny-61x47", [bunny] { return loaded(bunny); }, 61, 47, {}, {}},
        {"three-bunnies-800x600", [bunny] { return loaded("builtin:copies?count=3&of=" + bunny); }, 800, 600, {}, {}},
        {"bunny-1x1", [bunny] { return loaded(bunny); }, 1, 1, {}, {}},
        {"default-4096x4096", [] { return loaded("builtin:default"); }, 4096, 4096, {}, {}},
        {"tiny-coordinates-1e-6", [] { return scaled(1e-6f); }, 320, 240, {}, {}},
        {"huge-coordinates-1e6", [] { return scaled(1e6f); }, 320, 240, {}, {}},
        {"near-far-ratio-1e6", depthRange, 320, 240, lookFrom({0, 0, 0.001f}, {0, 0, -1}, 1e-3f, 1e3f), {}},
        {"slivers", slivers, 320, 240, lookFrom({0, 0, 8}, {0, 0, 0}, 0.1f, 100.0f), {}},
        {"huge-triangles-crossing-near", groundPlane, 320, 240, lookFrom({0, 1, 0}, {0, 0.2f, -10}, 0.05f, 1e5f), {}},
        {"pixel-centre-edges", pixelGrid, 64, 48, {}, {}},
        {"non-finite-vertices", nonFinite, 160, 120, lookFrom({0, 0, 4}, {0, 0, 0}, 0.1f, 10.0f), {}},
        {"materials", materials, 640, 400, lookFrom({0, 0, 6}, {0, 0, 0}, 0.5f, 20.0f), {}},
        {"maps", maps, 640, 480, lookFrom({0.3f, 0.4f, 5}, {0, 0, 0}, 0.5f, 20.0f), {}},
        {"normal-maps", normalMaps, 640, 360, lookFrom({0.2f, 0.3f, 4.5f}, {0, 0, 0}, 0.5f, 20.0f), {}},
        {"alpha", alpha, 640, 480, lookFrom({0.3f, 0.2f, 5.5f}, {0, 0, 0}, 0.5f, 20.0f), {}},
        {"specular-glossiness", specularGlossiness, 640, 480, lookFrom({0.3f, 0.4f, 5}, {0, 0, 0}, 0.5f, 20.0f), {}},
        {"clearcoat", clearcoat, 640, 560, lookFrom({0.3f, 0.4f, 6}, {0, 0, 0}, 0.5f, 20.0f), {}},
        {"tonemap-pbr-neutral", bright, 640, 400, lookFrom({0, 0, 6}, {0, 0, 0}, 0.5f, 20.0f), {}, ToneMap::PbrNeutral},
        {"tonemap-aces", bright, 640, 400, lookFrom({0, 0, 6}, {0, 0, 0}, 0.5f, 20.0f), {}, ToneMap::Aces},
        {"lights", lights, 640, 400, lookFrom({0.0f, 2.5f, 6.0f}, {0, -0.8f, -1.0f}, 0.5f, 30.0f), {}},
        {"mipmaps", mipmaps, 640, 400, lookFrom({0.0f, 0.6f, 3.0f}, {0, -0.4f, -6.0f}, 0.1f, 100.0f), {}},
        // Morph targets and skins posed on the CPU, drawn alike by both: morph weights of −1 and 10,
        // and not summing to 1; a joint scaled by 0 and by 10⁴, and skin weights not summing to 1.
        {"morph-minus1-and-10", morphExtreme, 480, 360, lookFrom({0.5f, 1.0f, 6.0f}, {0.5f, 0, 0}, 0.5f, 30.0f), {}},
        {"morph-not-summing-to-1", morphUnnormal, 480, 360, lookFrom({0.5f, 1.0f, 6.0f}, {0.5f, 0, 0}, 0.5f, 30.0f), {}},
        {"skin-joint-scaled-0", skinCollapsed, 480, 360, lookFrom({0.5f, 1.0f, 7.0f}, {0.5f, 0.5f, 0}, 0.5f, 30.0f), {}},
        {"skin-joint-scaled-1e4", skinHuge, 480, 360, lookFrom({0.5f, 1.0f, 7.0f}, {0.5f, 0.5f, 0}, 0.5f, 30.0f), {}},
        {"skin-weights-not-summing-to-1", skinUnnormal, 480, 360,
         lookFrom({0.5f, 1.0f, 7.0f}, {0.5f, 0.5f, 0}, 0.5f, 30.0f), {}},
        // Points and segments among triangles (lit segments, bare points, a strip with zero-length
        // segments), and multisampled.
        {"points-lines", pointsLines, 480, 360, lookFrom({0.5f, 1.0f, 7.0f}, {0, 0, 0}, 0.5f, 30.0f), {}},
        {"msaa-points-lines", pointsLines, 480, 360, lookFrom({0.5f, 1.0f, 7.0f}, {0, 0, 0}, 0.5f, 30.0f), {},
         ToneMap::None, 4},
        // Multisampled (4 samples at llvmpipe's positions), resolved: the colour is the samples' mean,
        // depth and ids sample 0's.
        {"msaa-bunny-800x600", [bunny] { return loaded(bunny); }, 800, 600, {}, {}, ToneMap::None, 4},
        {"msaa-default-61x47", [] { return loaded("builtin:default"); }, 61, 47, {}, {}, ToneMap::None, 4},
        {"msaa-cubes-800x600", [] { return loaded("builtin:cubes"); }, 800, 600, {}, {}, ToneMap::None, 4},
        {"msaa-slivers", slivers, 320, 240, lookFrom({0, 0, 8}, {0, 0, 0}, 0.1f, 100.0f), {}, ToneMap::None, 4},
        {"msaa-huge-triangles-crossing-near",
         groundPlane,
         320,
         240,
         lookFrom({0, 1, 0}, {0, 0.2f, -10}, 0.05f, 1e5f),
         {},
         ToneMap::None,
         4},
        {"msaa-pixel-centre-edges", pixelGrid, 64, 48, {}, {}, ToneMap::None, 4},
        {"msaa-non-finite-vertices",
         nonFinite,
         160,
         120,
         lookFrom({0, 0, 4}, {0, 0, 0}, 0.1f, 10.0f),
         {},
         ToneMap::None,
         4},
        {"msaa-near-far-ratio-1e6",
         depthRange,
         320,
         240,
         lookFrom({0, 0, 0.001f}, {0, 0, -1}, 1e-3f, 1e3f),
         {},
         ToneMap::None,
         4},
        {"msaa-alpha", alpha, 640, 480, lookFrom({0.3f, 0.2f, 5.5f}, {0, 0, 0}, 0.5f, 20.0f), {}, ToneMap::None, 4},
        {"msaa-maps", maps, 640, 480, lookFrom({0.3f, 0.4f, 5}, {0, 0, 0}, 0.5f, 20.0f), {}, ToneMap::None, 4},
        {"msaa-mipmaps",
         mipmaps,
         640,
         400,
         lookFrom({0.0f, 0.6f, 3.0f}, {0, -0.4f, -6.0f}, 0.1f, 100.0f),
         {},
         ToneMap::None,
         4},
        // The Lambert approximation (FrameParams::shading) on every kind of material, maps and lights.
        {"lambert-materials",
         materials,
         640,
         400,
         lookFrom({0, 0, 6}, {0, 0, 0}, 0.5f, 20.0f),
         {},
         ToneMap::None,
         1,
         ShadingModel::Lambert},
        {"lambert-maps",
         maps,
         640,
         480,
         lookFrom({0.3f, 0.4f, 5}, {0, 0, 0}, 0.5f, 20.0f),
         {},
         ToneMap::None,
         1,
         ShadingModel::Lambert},
        {"lambert-lights",
         lights,
         640,
         400,
         lookFrom({0.0f, 2.5f, 6.0f}, {0, -0.8f, -1.0f}, 0.5f, 30.0f),
         {},
         ToneMap::None,
         1,
         ShadingModel::Lambert},
        {"lambert-alpha",
         alpha,
         640,
         480,
         lookFrom({0.3f, 0.2f, 5.5f}, {0, 0, 0}, 0.5f, 20.0f),
         {},
         ToneMap::None,
         1,
         ShadingModel::Lambert},
        // The environment's diffuse lobe alone (Lighting::environmentSpecular) on the corners of the
        // material space, under the maps, on specular-glossiness and on clear coats.
        {"no-env-specular-materials",
         materials,
         640,
         400,
         lookFrom({0, 0, 6}, {0, 0, 0}, 0.5f, 20.0f),
         {},
         ToneMap::None,
         1,
         ShadingModel::Full,
         false},
        {"no-env-specular-maps",
         maps,
         640,
         480,
         lookFrom({0.3f, 0.4f, 5}, {0, 0, 0}, 0.5f, 20.0f),
         {},
         ToneMap::None,
         1,
         ShadingModel::Full,
         false},
        {"no-env-specular-specular-glossiness",
         specularGlossiness,
         640,
         480,
         lookFrom({0.3f, 0.4f, 5}, {0, 0, 0}, 0.5f, 20.0f),
         {},
         ToneMap::None,
         1,
         ShadingModel::Full,
         false},
        {"no-env-specular-clearcoat",
         clearcoat,
         640,
         560,
         lookFrom({0.3f, 0.4f, 6}, {0, 0, 0}, 0.5f, 20.0f),
         {},
         ToneMap::None,
         1,
         ShadingModel::Full,
         false},
        // An environment map (Lighting::map) on every kind of material, under the maps, on clear coats,
        // under the Lambert model and with its specular term left out, looked at from below the horizon
        // too (the sun's reflection on the smooth spheres).
        {"env-map-materials",
         materials,
         640,
         400,
         lookFrom({0, 0, 6}, {0, 0, 0}, 0.5f, 20.0f),
         {},
         ToneMap::None,
         1,
         ShadingModel::Full,
         true,
         true},
        {"env-map-materials-below",
         materials,
         640,
         400,
         lookFrom({0.5f, -3.0f, 5.0f}, {0, 0, 0}, 0.5f, 20.0f),
         {},
         ToneMap::None,
         1,
         ShadingModel::Full,
         true,
         true},
        {"env-map-maps",
         maps,
         640,
         480,
         lookFrom({0.3f, 0.4f, 5}, {0, 0, 0}, 0.5f, 20.0f),
         {},
         ToneMap::None,
         1,
         ShadingModel::Full,
         true,
         true},
        {"env-map-specular-glossiness",
         specularGlossiness,
         640,
         480,
         lookFrom({0.3f, 0.4f, 5}, {0, 0, 0}, 0.5f, 20.0f),
         {},
         ToneMap::None,
         1,
         ShadingModel::Full,
         true,
         true},
        {"env-map-clearcoat",
         clearcoat,
         640,
         560,
         lookFrom({0.3f, 0.4f, 6}, {0, 0, 0}, 0.5f, 20.0f),
         {},
         ToneMap::None,
         1,
         ShadingModel::Full,
         true,
         true},
        {"env-map-lambert",
         materials,
         640,
         400,
         lookFrom({0, 0, 6}, {0, 0, 0}, 0.5f, 20.0f),
         {},
         ToneMap::None,
         1,
         ShadingModel::Lambert,
         true,
         true},
        {"env-map-no-specular",
         materials,
         640,
         400,
         lookFrom({0, 0, 6}, {0, 0, 0}, 0.5f, 20.0f),
         {},
         ToneMap::None,
         1,
         ShadingModel::Full,
         false,
         true},
        {"env-map-msaa-aces",
         materials,
         640,
         400,
         lookFrom({0, 0, 6}, {0, 0, 0}, 0.5f, 20.0f),
         {},
         ToneMap::Aces,
         4,
         ShadingModel::Full,
         true,
         true},
        {"msaa-lights",
         lights,
         640,
         400,
         lookFrom({0.0f, 2.5f, 6.0f}, {0, -0.8f, -1.0f}, 0.5f, 30.0f),
         {},
         ToneMap::None,
         4},
    };
    // Linear colour in a float target: the same pixels, blended and resolved in float.
    const auto linear = [](std::string name, std::function<Scene()> scene, int width, int height, Camera camera,
                           ToneMap tonemap = ToneMap::None, int samples = 1, bool environmentMap = false) {
        MatrixCase c{std::move(name), std::move(scene), width, height, camera, {}, tonemap, samples};
        c.environmentMap = environmentMap;
        c.linear = true;
        return c;
    };
    const Camera front = lookFrom({0, 0, 6}, {0, 0, 0}, 0.5f, 20.0f);
    const Camera alphaView = lookFrom({0.3f, 0.2f, 5.5f}, {0, 0, 0}, 0.5f, 20.0f);
    const Camera lightsView = lookFrom({0.0f, 2.5f, 6.0f}, {0, -0.8f, -1.0f}, 0.5f, 30.0f);
    for (const MatrixCase& c :
         {linear("linear-materials", materials, 640, 400, front), linear("linear-alpha", alpha, 640, 480, alphaView),
          linear("linear-msaa-alpha", alpha, 640, 480, alphaView, ToneMap::None, 4),
          linear("linear-maps", maps, 640, 480, lookFrom({0.3f, 0.4f, 5}, {0, 0, 0}, 0.5f, 20.0f)),
          linear("linear-tonemap-aces", bright, 640, 400, front, ToneMap::Aces),
          linear("linear-env-map-clearcoat", clearcoat, 640, 560, lookFrom({0.3f, 0.4f, 6}, {0, 0, 0}, 0.5f, 20.0f),
                 ToneMap::None, 1, true),
          linear("linear-msaa-lights", lights, 640, 400, lightsView, ToneMap::None, 4)})
        cases.push_back(c);
    return cases;
}

class RegressionMatrixGLTest : public ::testing::TestWithParam<MatrixCase> {};

TEST_P(RegressionMatrixGLTest, GlMatchesTheSoftwareReference) {
    const MatrixCase& c = GetParam();
    const Scene scene = c.scene();
    ASSERT_FALSE(scene.instances.empty());
    std::unique_ptr<Backend> gl = test::makeReference();
    ASSERT_NE(gl, nullptr);
    std::unique_ptr<Backend> software = makeSoftwareBackend();

    Result<FrameSetup> setup = setUpFrame(scene, c.camera, 0.0, c.width, c.height, true);
    ASSERT_TRUE(setup) << setup.error().message;
    setup->params.tonemap = c.tonemap;
    setup->params.shading = c.shading;
    setup->params.lighting.environmentSpecular = c.environmentSpecular;
    if (c.environmentMap) setup->params.lighting.map = skyMap();
    Buffers images[2];
    Backend* backends[2] = {gl.get(), software.get()};
    for (int k = 0; k < 2; ++k) {
        const TargetHandle target = backends[k]->createTarget(c.width, c.height, DepthFormat::D24, c.samples,
                                                              c.linear ? ColorFormat::Rgba32F : ColorFormat::Rgba8);
        ASSERT_NE(target, kNoHandle);
        Result<SceneRenderer> renderer = SceneRenderer::create(*backends[k], scene);
        ASSERT_TRUE(renderer) << renderer.error().message;
        renderer->renderFrame(target, c.width, c.height, setup->params, setup->world, glm::vec4(0.12f, 0.13f, 0.15f, 1.0f));
        images[k] = backends[k]->readBack(target);
    }

    Result<ImageComparison> compared = compareBuffers(images[0], images[1]);
    ASSERT_TRUE(compared) << compared.error().message;
    if (c.linear) {
        ASSERT_EQ(images[0].linear.size(), images[0].pixelCount() * 4);
        ASSERT_EQ(images[1].linear.size(), images[0].linear.size());
        const auto [beyond, worst] = linearDifferences(images[0].linear, images[1].linear);
        std::printf("[ matrix %s ] linear: %zu values beyond %.0e, worst relative difference %.2e\n", c.name.c_str(),
                    beyond, kLinearTolerance, worst);
        EXPECT_LE(double(beyond), kLinearShare * double(images[0].linear.size()));
        EXPECT_LE(worst, kLinearWorst);
    }
    const ImageComparison& r = *compared;
    std::size_t covered = 0;
    for (std::uint32_t id : images[1].ids) covered += id != 0;
    const double idAgreement = 1.0 - double(r.idMismatches.value_or(0)) / double(r.pixels);
    std::printf("[ matrix %s ] %zu covered, coverage %zu, depth worst %u LSB, ids %.6f, colour worst %d on %zu\n",
                c.name.c_str(), covered, r.coverageMismatches(), r.depth ? r.depth->maxDifference : 0, idAgreement,
                r.maxChannelDifference, r.failingPixels);
    if (c.name != "bunny-1x1") {
        EXPECT_GT(covered, 0u) << "a case that draws nothing tests nothing";
    }

    const bool ok = r.coverageMismatches() <= c.tolerance.coverage && r.depth &&
                    r.depth->maxDifference <= c.tolerance.depthLsb && idAgreement >= c.tolerance.idAgreement &&
                    r.maxChannelDifference <= c.tolerance.colour &&
                    double(r.failingPixels) <= c.tolerance.colourShare * double(covered);
    EXPECT_LE(r.coverageMismatches(), c.tolerance.coverage);
    ASSERT_TRUE(r.depth.has_value());
    EXPECT_LE(r.depth->maxDifference, c.tolerance.depthLsb);
    EXPECT_GE(idAgreement, c.tolerance.idAgreement);
    EXPECT_LE(r.maxChannelDifference, c.tolerance.colour);
    EXPECT_LE(double(r.failingPixels), c.tolerance.colourShare * double(covered))
        << r.failingPixels << " pixels differ";
    if (!ok) {
        const fs::path dir = test::freshDir("matrix-" + c.name);
        (void)writeFileAtomic((dir / "actual.png").string(), encodeColorPng(images[0]));
        (void)writeFileAtomic((dir / "reference.png").string(), encodeColorPng(images[1]));
        (void)writeFileAtomic((dir / "mask.png").string(), encodeColorPng(r.mask));
        ADD_FAILURE() << "images in " << dir;
    }
}

// What alpha writes, on both backends: a masked quad that discards everything leaves the colour,
// depth and ids of what is behind it; a blended one writes its depth and ids and blends its colour
// over the pixel below (blendOver, within a step); an opaque one writes alpha 1 whatever its alpha.
TEST(AlphaGLTest, MaskDiscardsBlendWritesDepthAndIdsAndBlendsTheColour) {
    const auto quad = [](float z) {
        Mesh mesh;
        mesh.positions = {{-1, -1, z}, {1, -1, z}, {1, 1, z}, {-1, 1, z}};
        mesh.indices = {0, 1, 2, 0, 2, 3};
        finalizeMesh(mesh, false);
        return mesh;
    };
    const auto scene = [&](AlphaMode front, float alpha) {
        Scene s;
        Material back;
        back.baseColorFactor = {0.8f, 0.2f, 0.1f, 0.4f};
        back.unlit = true;
        place(s, quad(-1.0f), back, {0, 0, 0});
        Material over;
        over.baseColorFactor = {0.1f, 0.3f, 0.9f, alpha};
        over.unlit = true;
        over.alphaMode = front;
        place(s, quad(0.0f), over, {0, 0, 0});
        s.buildInstances();
        return s;
    };
    std::unique_ptr<Backend> gl = test::makeReference();
    ASSERT_NE(gl, nullptr);
    std::unique_ptr<Backend> software = makeSoftwareBackend();
    for (Backend* backend : {gl.get(), software.get()}) {
        SCOPED_TRACE(backend->name());
        const auto render = [&](const Scene& s) {
            Result<FrameSetup> setup = setUpFrame(s, lookFrom({0, 0, 3}, {0, 0, 0}, 0.5f, 10.0f), 0.0, 16, 16, true);
            EXPECT_TRUE(setup) << setup.error().message;
            const TargetHandle target = backend->createTarget(16, 16);
            Result<SceneRenderer> renderer = SceneRenderer::create(*backend, s);
            EXPECT_TRUE(renderer) << renderer.error().message;
            renderer->renderFrame(target, 16, 16, setup->params, setup->world, glm::vec4(0.0f));
            Buffers out = backend->readBack(target);
            backend->destroyTarget(target);
            return out;
        };
        const std::size_t centre = 8 * 16 + 4;  // off the quads' diagonal
        const Buffers masked = render(scene(AlphaMode::Mask, 0.2f));
        const Buffers opaque = render(scene(AlphaMode::Opaque, 0.2f));
        const Buffers blended = render(scene(AlphaMode::Blend, 0.5f));
        // The back quad alone is what the masked frame shows, depth and ids included.
        // Ids: the back quad's triangles are 1 and 2, the front one's 3 and 4.
        EXPECT_TRUE(masked.ids[centre] == 1u || masked.ids[centre] == 2u) << "the masked quad writes no id";
        EXPECT_TRUE(opaque.ids[centre] == 3u || opaque.ids[centre] == 4u);
        EXPECT_EQ(blended.ids[centre], opaque.ids[centre]) << "a blended surface writes its id";
        EXPECT_EQ(blended.depth[centre], opaque.depth[centre]) << "and its depth";
        EXPECT_LT(opaque.depth[centre], masked.depth[centre]);
        EXPECT_EQ(masked.rgba[4 * centre + 3], 255) << "an opaque surface's alpha is 1";
        EXPECT_EQ(opaque.rgba[4 * centre + 3], 255);
        std::uint32_t below = 0, src = 0;
        for (int c = 0; c < 4; ++c) below |= std::uint32_t(masked.rgba[4 * centre + std::size_t(c)]) << (8 * c);
        const glm::vec3 colour(0.1f, 0.3f, 0.9f);
        for (int c = 0; c < 3; ++c) src |= std::uint32_t(ColorEncoding::encode(colour[c])) << (8 * c);
        src |= 128u << 24;  // 0.5 · 255 = 127.5, rounded to even
        const std::uint32_t expected = sw::blendOver(src, below);
        for (int c = 0; c < 4; ++c)
            EXPECT_NEAR(int(blended.rgba[4 * centre + std::size_t(c)]), int((expected >> (8 * c)) & 255u), 1) << c;
    }
}

INSTANTIATE_TEST_SUITE_P(Cases, RegressionMatrixGLTest, ::testing::ValuesIn(matrix()), [](const auto& p) {
    std::string name = p.param.name;
    for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
    return name;
});

}  // namespace
}  // namespace frugal
