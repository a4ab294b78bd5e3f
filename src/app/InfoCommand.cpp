#include <cstdio>
#include <ostream>

#include <nlohmann/json.hpp>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "gl/StateCosts.h"
#include "io/ImageIO.h"

namespace frugal {

const char* infoHelp() {
    return R"(usage: frugal info SCENE [--cull-backfaces]
       frugal info --state-costs [--backend NAME] [--threads N] [--json FILE]

Prints what SCENE holds: nodes, meshes, instances, triangles, materials, textures, cameras,
animations, bounds at time 0, and every feature of the file that frugal does not model, by name.

--state-costs measures, on the backend that runs (--backend, default auto), what changing each kind
of render state between two draws costs (paper 004's C(s); src/gl/StateCosts.h): program (shader
variant), mesh, texture, material, face culling and depth test, in microseconds per change over a
plain draw (median and range of 9 rounds of 400 draws), and once each: a new 256x256 texture's
upload and first draw against a resident one, and a draw in a state combination not drawn before
against the same draw again. About a second. --json FILE writes the figures as JSON.
)";
}

namespace {

int runStateCosts(const RenderOptions& options, const std::string& jsonPath, std::ostream& out, std::ostream& err) {
    Result<Session> session = openSession(options.backend, options);
    if (!session) {
        err << "error: --backend " << options.backendName << ": " << session.error() << "\n";
        return kExitNoBackend;
    }
    Result<StateCostReport> measured = measureStateCosts(*session->backend);
    if (!measured) {
        err << "error: " << measured.error() << "\n";
        return kExitError;
    }
    const StateCostReport& r = *measured;
    out << "state costs on " << r.backend << " (" << r.renderer << "), " << r.rounds << " rounds of " << r.draws
        << " draws\n";
    char line[160];
    std::snprintf(line, sizeof line, "  %-10s %10.3f us a draw with no change\n", "draw", r.drawUs);
    out << line;
    nlohmann::json costs = nlohmann::json::object();
    for (const StateCost& c : r.costs) {
        std::snprintf(line, sizeof line, "  %-10s %10.3f us a change (%.3f to %.3f)\n", c.kind.c_str(), c.us, c.minUs, c.maxUs);
        out << line;
        costs[c.kind] = {{"us", c.us}, {"min_us", c.minUs}, {"max_us", c.maxUs}};
    }
    std::snprintf(line, sizeof line,
                  "  texture 256x256: upload %.3f ms, first draw %.3f ms, resident draw %.3f ms\n"
                  "  new state combination: first draw %.3f ms, again %.3f ms\n",
                  r.textureUploadMs, r.textureFirstDrawMs, r.textureResidentDrawMs, r.newCombinationMs, r.seenCombinationMs);
    out << line;
    if (jsonPath.empty()) return kExitOk;
    const nlohmann::json json = {
        {"backend", r.backend}, {"renderer", r.renderer}, {"rounds", r.rounds}, {"draws", r.draws}, {"draw_us", r.drawUs},
        {"costs", costs},
        {"texture", {{"upload_ms", r.textureUploadMs}, {"first_draw_ms", r.textureFirstDrawMs},
                     {"resident_draw_ms", r.textureResidentDrawMs}}},
        {"new_combination", {{"first_ms", r.newCombinationMs}, {"again_ms", r.seenCombinationMs}}}};
    const std::string text = json.dump(2) + "\n";
    if (Result<bool> written = writeFileAtomic(jsonPath, Bytes(text.begin(), text.end())); !written) {
        err << "error: " << written.error() << "\n";
        return kExitError;
    }
    return kExitOk;
}

}  // namespace

int runInfo(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    RenderOptions options;
    bool sceneGiven = false, stateCosts = false;
    std::string jsonPath;
    CommandLine command{"info", infoHelp()};
    command.option = [&](const std::string& flag, ArgCursor& cursor) {
        if (flag == "--cull-backfaces") {
            options.load.objDoubleSided = false;
        } else if (flag == "--state-costs") {
            stateCosts = true;
        } else if (flag == "--backend" || flag == "--threads") {
            return parseSharedOption(flag, cursor, options);
        } else if (flag == "--json") {
            const std::optional<std::string> path = cursor.value(flag);
            if (path && path->empty()) cursor.fail("--json: empty file name");
            else if (path) jsonPath = *path;
        } else {
            return false;
        }
        return true;
    };
    command.positional = sceneArgument(options, &sceneGiven);
    command.finish = [&](ArgCursor& cursor) {
        if (stateCosts && sceneGiven)
            cursor.fail("--state-costs measures the backend, not a scene: give one or the other");
        else if (!stateCosts && !sceneGiven)
            cursor.fail("info needs a SCENE (a file or builtin:NAME), or --state-costs");
        else if (!stateCosts && (!jsonPath.empty() || options.backendName != "auto" || options.threads != 0))
            cursor.fail("--backend, --threads and --json go with --state-costs");
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;
    if (stateCosts) return runStateCosts(options, jsonPath, out, err);
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
