// SceneRenderer against a recording backend: what it uploads, the order and parameters of its calls,
// and that a refused upload is an error instead of a mesh silently missing from every frame.
#include <gtest/gtest.h>

#include "pipeline/SceneRenderer.h"

namespace frugal {
namespace {

// Records every call; refuses meshes and textures named "refuse".
class RecordingBackend final : public Backend {
public:
    struct Draw {
        DrawParams params;
        std::vector<IndexRange> ranges;
    };
    std::vector<std::string> calls;
    std::vector<Draw> draws;

    std::string name() const override { return "recording"; }
    std::string renderer() const override { return "test"; }
    int maxTargetSize() const override { return 64; }
    int maxTextureSize() const override { return 32; }
    bool supportsDepthFormat(DepthFormat) const override { return true; }
    int maxSamples() const override { return 1; }
    TargetHandle createTarget(int, int, DepthFormat, int, ColorFormat) override { return TargetHandle{1}; }
    void destroyTarget(TargetHandle) override {}
    void releaseMesh(MeshHandle mesh) override { calls.push_back("release mesh " + std::to_string(mesh.id)); }
    bool updateVertices(MeshHandle mesh, std::span<const glm::vec3>, std::span<const glm::vec3>,
                        std::span<const glm::vec4>) override {
        calls.push_back("update mesh " + std::to_string(mesh.id));
        return true;
    }
    void releaseTexture(TextureHandle texture) override { calls.push_back("release texture " + std::to_string(texture.id)); }
    MeshHandle uploadMesh(const Mesh& mesh) override {
        return mesh.name == "refuse" ? kNoHandle : MeshHandle(10 + meshes_++);
    }
    TextureHandle uploadTexture(const Texture& texture) override {
        return texture.name == "refuse" ? kNoHandle : TextureHandle(20 + textures_++);
    }
    void beginFrame(TargetHandle, const FrameParams&) override { calls.push_back("begin"); }
    void draw(const DrawParams& params, std::span<const IndexRange> ranges) override {
        calls.push_back("draw");
        draws.push_back({params, {ranges.begin(), ranges.end()}});
    }
    void drawInstances(const DrawParams& params, std::span<const InstanceParams> instances, IndexRange range) override {
        calls.push_back("instances " + std::to_string(instances.size()));
        for (const InstanceParams& instance : instances) {
            DrawParams one = params;
            one.model = instance.model;
            one.firstId = instance.firstId;
            draws.push_back({one, {range}});
        }
    }
    void clear(TargetHandle, const Rect&, const glm::vec4&, float) override { calls.push_back("clear"); }
    void copy(TargetHandle, TargetHandle, const Rect&, bool, bool, bool) override { calls.push_back("copy"); }
    void readBackInto(TargetHandle, Buffers& out, Planes) override { out = Buffers{}; }
    void finish() override {}
    StateChanges stateChanges() const override { return {}; }

private:
    int meshes_ = 0, textures_ = 0;
};

Mesh oneTriangle(const std::string& name, int material) {
    Mesh mesh;
    mesh.name = name;
    mesh.material = material;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    mesh.indices = {0, 1, 2};
    return mesh;
}

// Node 0 draws mesh 1 (textured, double-sided material 1), node 1 draws mesh 0 (material 0).
Scene twoMeshScene() {
    Scene scene;
    scene.meshes = {oneTriangle("a", 0), oneTriangle("b", 1)};
    Material plain;
    plain.baseColorFactor = glm::vec4(0.5f, 0.25f, 1.0f, 1.0f);
    Material textured;
    textured.baseColorTexture = 0;
    textured.doubleSided = true;
    scene.materials = {plain, textured};
    Texture texture;
    texture.name = "t";
    texture.width = texture.height = 1;
    texture.rgba = {1, 2, 3, 4};
    scene.textures = {texture};
    scene.nodes.resize(2);
    scene.nodes[0].meshes = {1};
    scene.nodes[1].meshes = {0};
    scene.nodes[1].translation = glm::vec3(3, 0, 0);
    scene.roots = {0, 1};
    scene.buildInstances();
    return scene;
}

TEST(SceneRendererTest, AFrameIsClearBeginThenEveryInstanceInOrderWithItsMaterial) {
    const Scene scene = twoMeshScene();
    RecordingBackend backend;
    Result<SceneRenderer> renderer = SceneRenderer::create(backend, scene);
    ASSERT_TRUE(renderer) << renderer.error().message;
    const std::vector<glm::mat4> world = scene.worldTransforms(0.0);
    renderer->renderFrame(TargetHandle{1}, 8, 8, FrameParams{}, world, glm::vec4(0.0f));
    EXPECT_EQ(backend.calls, (std::vector<std::string>{"clear", "begin", "draw", "draw"}));
    ASSERT_EQ(backend.draws.size(), 2u);
    const DrawParams& first = backend.draws[0].params;  // instance 0: node 0, mesh 1
    EXPECT_EQ(first.mesh.id, 11u);
    EXPECT_EQ(first.texture.id, 20u);
    EXPECT_TRUE(first.doubleSided);
    EXPECT_EQ(first.firstId, scene.instances[0].firstId);
    const DrawParams& second = backend.draws[1].params;  // instance 1: node 1, mesh 0
    EXPECT_EQ(second.mesh.id, 10u);
    EXPECT_TRUE(second.texture == kNoHandle);
    EXPECT_FALSE(second.doubleSided);
    EXPECT_EQ(second.baseColorFactor, scene.materials[0].baseColorFactor);
    EXPECT_EQ(second.model, world[1]);
    EXPECT_EQ(second.firstId, scene.instances[1].firstId);
    EXPECT_NE(first.firstId, second.firstId);
}

// Blended instances are drawn after the rest, far to near by the view depth of their mesh's
// centroid (ties in list order); the others keep the list's order. Each draw carries its alpha mode.
TEST(SceneRendererTest, BlendedInstancesComeLastFarToNear) {
    Scene scene;
    scene.meshes = {oneTriangle("opaque", 0), oneTriangle("blended", 1), oneTriangle("masked", 2)};
    Material blended, masked;
    blended.alphaMode = AlphaMode::Blend;
    masked.alphaMode = AlphaMode::Mask;
    masked.alphaCutoff = 0.25f;
    scene.materials = {Material{}, blended, masked};
    // Nodes (z): blended at −1, opaque at −2, blended at −5, blended at −1 again, masked at −3.
    const int meshes[] = {1, 0, 1, 1, 2};
    const float depths[] = {-1.0f, -2.0f, -5.0f, -1.0f, -3.0f};
    for (int n = 0; n < 5; ++n) {
        Node node;
        node.meshes = {meshes[n]};
        node.translation = glm::vec3(0.0f, 0.0f, depths[n]);
        scene.nodes.push_back(node);
        scene.roots.push_back(n);
    }
    scene.buildInstances();
    RecordingBackend backend;
    Result<SceneRenderer> renderer = SceneRenderer::create(backend, scene);
    ASSERT_TRUE(renderer) << renderer.error().message;
    renderer->setBatching(false);
    const std::vector<glm::mat4> world = scene.worldTransforms(0.0);
    renderer->renderFrame(TargetHandle{1}, 8, 8, FrameParams{}, world, glm::vec4(0.0f));
    ASSERT_EQ(backend.draws.size(), 5u);
    const float order[] = {-2.0f, -3.0f, -5.0f, -1.0f, -1.0f};  // opaque, masked, then blended far first
    for (int k = 0; k < 5; ++k) EXPECT_EQ(backend.draws[std::size_t(k)].params.model[3].z, order[k]) << k;
    EXPECT_EQ(backend.draws[0].params.alphaMode, AlphaMode::Opaque);
    EXPECT_EQ(backend.draws[1].params.alphaMode, AlphaMode::Mask);
    EXPECT_EQ(backend.draws[1].params.alphaCutoff, 0.25f);
    for (int k = 2; k < 5; ++k) EXPECT_EQ(backend.draws[std::size_t(k)].params.alphaMode, AlphaMode::Blend) << k;
    EXPECT_EQ(backend.draws[3].params.firstId, scene.instances[0].firstId) << "ties keep the list's order";
    EXPECT_EQ(backend.draws[4].params.firstId, scene.instances[3].firstId);

    // From the other side (looking down +z), the nearest blended instance is the one at −5.
    FrameParams behind;
    behind.view = glm::mat4(glm::vec4(-1, 0, 0, 0), glm::vec4(0, 1, 0, 0), glm::vec4(0, 0, -1, 0), glm::vec4(0, 0, -10, 1));
    backend.draws.clear();
    renderer->renderFrame(TargetHandle{1}, 8, 8, behind, world, glm::vec4(0.0f));
    ASSERT_EQ(backend.draws.size(), 5u);
    EXPECT_EQ(backend.draws[2].params.model[3].z, -1.0f);
    EXPECT_EQ(backend.draws[4].params.model[3].z, -5.0f);
}

TEST(SceneRendererTest, ARefusedUploadIsAnErrorThatNamesIt) {
    Scene scene = twoMeshScene();
    scene.meshes[1].name = "refuse";
    RecordingBackend backend;
    EXPECT_EQ(SceneRenderer::create(backend, scene).error().message,
              "mesh 1 'refuse' (3 vertices, 1 triangles): recording could not store it (out of memory)");
    scene.meshes[1].name = "b";
    scene.meshes[1].indices.push_back(7);  // breaks the upload contract: not a multiple of 3
    scene.meshes[1].name = "refuse";
    EXPECT_EQ(SceneRenderer::create(backend, scene).error().message,
              "mesh 1 'refuse' (3 vertices, 1 triangles): recording refused it: its arrays break the upload "
              "contract (pipeline/Backend.h)");
    scene = twoMeshScene();
    scene.textures[0].name = "refuse";
    EXPECT_EQ(SceneRenderer::create(backend, scene).error().message,
              "texture 0 'refuse' (1x1): recording refused it (its limit is 32 pixels a side; or out of memory)");
}

TEST(SceneRendererTest, ReleasesWhatItUploadedOnceWhenDestroyedOrWhenAnUploadFails) {
    const Scene scene = twoMeshScene();
    RecordingBackend backend;
    {
        Result<SceneRenderer> renderer = SceneRenderer::create(backend, scene);
        ASSERT_TRUE(renderer) << renderer.error().message;
        SceneRenderer moved = std::move(*renderer);  // the moved-from renderer releases nothing
        EXPECT_TRUE(backend.calls.empty());
    }
    EXPECT_EQ(backend.calls, (std::vector<std::string>{"release mesh 10", "release mesh 11", "release texture 20"}));

    backend.calls.clear();
    Scene refused = twoMeshScene();
    refused.textures[0].name = "refuse";
    EXPECT_FALSE(SceneRenderer::create(backend, refused));
    EXPECT_EQ(backend.calls, (std::vector<std::string>{"release mesh 12", "release mesh 13"}));
}

TEST(SceneRendererTest, CullAllBackFacesOverridesDoubleSidedMaterialsAndDrawsTheGivenList) {
    const Scene scene = twoMeshScene();
    RecordingBackend backend;
    Result<SceneRenderer> renderer = SceneRenderer::create(backend, scene);
    ASSERT_TRUE(renderer) << renderer.error().message;
    renderer->setCullAllBackFaces(true);
    const DrawList list{DrawCommand{0, {IndexRange{0, 1}}}};
    renderer->renderFrame(TargetHandle{1}, 8, 8, FrameParams{}, scene.worldTransforms(0.0), glm::vec4(0.0f), list);
    ASSERT_EQ(backend.draws.size(), 1u);
    EXPECT_EQ(backend.draws[0].params.mesh.id, 11u);
    EXPECT_FALSE(backend.draws[0].params.doubleSided);
}

TEST(SceneRendererTest, ConsecutiveDrawsOfOneMeshAndRangeAreOneBatchInOrder) {
    // Four nodes: mesh 0, mesh 0, mesh 1, mesh 0. The first two go out as one batch with their own
    // transforms and ids; then mesh 1 alone; then mesh 0 alone (not consecutive with the batch).
    Scene scene;
    scene.meshes = {oneTriangle("a", -1), oneTriangle("b", -1)};
    for (int n = 0; n < 4; ++n) {
        Node node;
        node.translation = glm::vec3(float(n), 0, 0);
        node.meshes = {n == 2 ? 1 : 0};
        scene.nodes.push_back(node);
        scene.roots.push_back(n);
    }
    scene.buildInstances();
    RecordingBackend backend;
    Result<SceneRenderer> renderer = SceneRenderer::create(backend, scene);
    ASSERT_TRUE(renderer.ok());
    const std::vector<glm::mat4> world = scene.worldTransforms(0.0);
    renderer->renderFrame(TargetHandle{1}, 8, 8, FrameParams{}, world, glm::vec4(0.0f));
    EXPECT_EQ(backend.calls, (std::vector<std::string>{"clear", "begin", "instances 2", "draw", "draw"}));
    ASSERT_EQ(backend.draws.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(backend.draws[i].params.model, world[i]) << i;
        EXPECT_EQ(backend.draws[i].params.firstId, scene.instances[i].firstId) << i;
    }
    // Batching off, or different ranges: one draw each.
    backend.calls.clear();
    renderer->setBatching(false);
    renderer->renderFrame(TargetHandle{1}, 8, 8, FrameParams{}, world, glm::vec4(0.0f));
    EXPECT_EQ(backend.calls, (std::vector<std::string>{"clear", "begin", "draw", "draw", "draw", "draw"}));
    backend.calls.clear();
    renderer->setBatching(true);
    const DrawList split{{0, {{0, 1}}}, {1, {{0, 0}, {0, 1}}}};
    renderer->renderFrame(TargetHandle{1}, 8, 8, FrameParams{}, world, glm::vec4(0.0f), split);
    EXPECT_EQ(backend.calls, (std::vector<std::string>{"clear", "begin", "draw", "draw"}));
}

TEST(SceneRendererTest, KeyOrderGroupsDrawsByTextureProgramAndMesh) {
    Scene scene;
    scene.meshes = {oneTriangle("a", -1), oneTriangle("b", -1)};
    for (int n = 0; n < 4; ++n) {
        Node node;
        node.meshes = {n % 2};
        scene.nodes.push_back(node);
        scene.roots.push_back(n);
    }
    scene.buildInstances();
    const DrawList list = fullDrawList(scene);
    const DrawList keyed = orderDraws(scene, list, Order::Key);
    ASSERT_EQ(keyed.size(), 4u);
    EXPECT_EQ(keyed[0].instance, 0);  // stable within a key
    EXPECT_EQ(keyed[1].instance, 2);
    EXPECT_EQ(keyed[2].instance, 1);
    EXPECT_EQ(keyed[3].instance, 3);
    const DrawList same = orderDraws(scene, list, Order::Submit);
    for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(same[i].instance, list[i].instance);
}

}  // namespace
}  // namespace frugal
