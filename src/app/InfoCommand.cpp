#include <ostream>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"

namespace frugal {

const char* infoHelp() {
    return R"(usage: frugal info SCENE [--cull-backfaces]

Prints what SCENE holds: nodes, meshes, instances, triangles, materials, textures, cameras,
animations, bounds at time 0, and every feature of the file that frugal does not model, by name.
)";
}

int runInfo(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    RenderOptions options;
    bool sceneGiven = false;
    CommandLine command{"info", infoHelp()};
    command.option = [&options](const std::string& flag, ArgCursor&) {
        if (flag != "--cull-backfaces") return false;
        options.load.objDoubleSided = false;
        return true;
    };
    command.positional = sceneArgument(options, &sceneGiven);
    command.finish = [&sceneGiven](ArgCursor& cursor) {
        if (!sceneGiven) cursor.fail("info needs a SCENE (a file or builtin:NAME)");
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;
    Result<Scene> loaded = loadScene(options.scene, options.load);
    if (!loaded) {
        err << "error: " << loaded.error() << "\n";
        return kExitError;
    }
    const Scene& scene = *loaded;

    std::size_t vertices = 0;
    for (const Mesh& mesh : scene.meshes) vertices += mesh.positions.size();
    out << "scene: " << scene.source << "\n";
    out << "nodes: " << scene.nodes.size() << " (" << scene.roots.size() << " roots)\n";
    out << "meshes: " << scene.meshes.size() << " (" << vertices << " vertices)\n";
    out << "instances: " << scene.instances.size() << "\n";
    out << "triangles: " << scene.triangleCount() << " (drawn per frame)\n";
    out << "materials: " << scene.materials.size() << "\n";
    for (const Material& m : scene.materials) {
        out << "  '" << m.name << "' base colour " << fmt(m.baseColorFactor.r) << "," << fmt(m.baseColorFactor.g) << ","
            << fmt(m.baseColorFactor.b) << "," << fmt(m.baseColorFactor.a)
            << (m.baseColorTexture >= 0 ? ", texture " + std::to_string(m.baseColorTexture) : std::string())
            << (m.doubleSided ? ", double-sided" : ", single-sided") << "\n";
    }
    out << "textures: " << scene.textures.size() << "\n";
    for (const Texture& t : scene.textures)
        out << "  '" << t.name << "' " << t.width << "x" << t.height << (t.filter == Filter::Nearest ? " nearest" : " linear") << "\n";
    out << "cameras: " << scene.cameras.size() << "\n";
    for (const Camera& c : scene.cameras) {
        out << "  '" << c.name << "' " << (c.perspective ? "perspective yfov " + fmt(glm::degrees(c.yfov)) + " deg" : std::string("orthographic"))
            << ", znear " << fmt(c.znear) << ", zfar " << (c.zfar > 0 ? fmt(c.zfar) : std::string("infinite")) << "\n";
    }
    std::size_t channels = 0;
    for (const Animation& a : scene.animations) channels += a.channels.size();
    out << "animations: " << scene.animations.size() << " (" << channels << " channels, " << fmt(scene.duration())
        << " s at " << fmt(scene.fps) << " fps)\n";
    const Bounds b = scene.bounds(0.0);
    if (b.empty()) out << "bounds: empty\n";
    else out << "bounds: min " << fmt(b.min.x) << "," << fmt(b.min.y) << "," << fmt(b.min.z) << " max " << fmt(b.max.x) << ","
             << fmt(b.max.y) << "," << fmt(b.max.z) << " (radius " << fmt(b.radius()) << ")\n";
    out << "not modelled: ";
    if (scene.unsupported.empty()) out << "none\n";
    else {
        std::string names;
        for (const std::string& name : scene.unsupported) names += (names.empty() ? "" : ", ") + name;
        out << names << "\n";
    }
    for (const std::string& warning : scene.warnings) out << "warning: " << warning << "\n";
    return kExitOk;
}

}  // namespace frugal
