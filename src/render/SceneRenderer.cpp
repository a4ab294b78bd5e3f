#include "render/SceneRenderer.h"

namespace frugal {

DrawList fullDrawList(const Scene& scene) {
    DrawList list;
    list.reserve(scene.instances.size());
    for (int i = 0; i < int(scene.instances.size()); ++i) {
        const Mesh& mesh = scene.meshes[scene.instances[i].mesh];
        if (mesh.triangleCount() == 0) continue;
        list.push_back({i, {{0, std::uint32_t(mesh.triangleCount())}}});
    }
    return list;
}

SceneRenderer::SceneRenderer(Backend& backend, const Scene& scene)
    : backend_(backend), scene_(scene), full_(fullDrawList(scene)) {
    meshes_.reserve(scene.meshes.size());
    for (const Mesh& mesh : scene.meshes) meshes_.push_back(backend.uploadMesh(mesh));
    textures_.reserve(scene.textures.size());
    for (const Texture& texture : scene.textures) textures_.push_back(backend.uploadTexture(texture));
}

void SceneRenderer::draw(const DrawList& list, const std::vector<glm::mat4>& world) {
    static const Material kDefault{};
    for (const DrawCommand& command : list) {
        if (command.ranges.empty()) continue;
        const Instance& instance = scene_.instances[command.instance];
        const Mesh& mesh = scene_.meshes[instance.mesh];
        const Material& material = mesh.material >= 0 ? scene_.materials[mesh.material] : kDefault;
        DrawParams params;
        params.mesh = meshes_[instance.mesh];
        params.model = world[instance.node];
        params.baseColorFactor = material.baseColorFactor;
        params.texture = material.baseColorTexture >= 0 ? textures_[material.baseColorTexture] : kNoHandle;
        params.doubleSided = material.doubleSided;
        params.firstId = instance.firstId;
        backend_.draw(params, command.ranges);
    }
}

void SceneRenderer::renderFrame(TargetHandle target, int width, int height, const FrameParams& frame,
                                const std::vector<glm::mat4>& world, const glm::vec4& background) {
    backend_.clear(target, Rect{0, 0, width, height}, background, 1.0f);
    backend_.beginFrame(target, frame);
    draw(full_, world);
}

}  // namespace frugal
