#include "render/Plan.h"

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

}  // namespace frugal
