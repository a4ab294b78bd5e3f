#include "pipeline/Plan.h"

#include <algorithm>
#include <tuple>

namespace frugal {

DrawList orderDraws(const Scene& scene, DrawList list, Order order) {
    if (order != Order::Key) return list;
    const auto key = [&scene](const DrawCommand& command) {
        const Mesh& mesh = scene.meshes[std::size_t(scene.instances[std::size_t(command.instance)].mesh)];
        const int texture = mesh.material >= 0 ? scene.materials[std::size_t(mesh.material)].baseColorTexture : -1;
        return std::tuple(texture, !mesh.colors.empty(), scene.instances[std::size_t(command.instance)].mesh);
    };
    std::stable_sort(list.begin(), list.end(), [&](const DrawCommand& a, const DrawCommand& b) { return key(a) < key(b); });
    return list;
}

bool blendedInstance(const Scene& scene, int instance) {
    const int material = scene.meshes[std::size_t(scene.instances[std::size_t(instance)].mesh)].material;
    return material >= 0 && scene.materials[std::size_t(material)].alphaMode == AlphaMode::Blend;
}

bool anyBlended(const Scene& scene) {
    return std::any_of(scene.materials.begin(), scene.materials.end(),
                       [](const Material& m) { return m.alphaMode == AlphaMode::Blend; });
}

DrawList fullDrawList(const Scene& scene) {
    DrawList list;
    list.reserve(scene.instances.size());
    for (int i = 0; i < int(scene.instances.size()); ++i) {
        const Mesh& mesh = scene.meshes[scene.instances[i].mesh];
        if (mesh.primitiveCount() == 0) continue;
        list.push_back({i, {{0, std::uint32_t(mesh.primitiveCount())}}});
    }
    return list;
}

}  // namespace frugal
