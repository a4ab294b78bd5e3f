// `frugal info`: what a scene holds, or the backend's state-change costs (lab/SceneInfo.h).
#include <ostream>

#include <frugal/Files.h>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "lab/SceneInfo.h"

namespace frugal {

const char* infoHelp() {
    return R"(usage: frugal info SCENE [--cull-backfaces]
       frugal info --state-costs [--backend NAME] [--threads N] [--json FILE]

Prints what SCENE holds: nodes, meshes, instances, triangles, materials (with their maps), the
shading variants its meshes need (what each variant reads: maps, vertex colours; frugal compiles
one program a variant), textures, cameras, animations, bounds at time 0, and every feature of the
file that frugal does not model, by name.

For each camera (the automatic view when the scene has none): where the scene lies along its view,
and the smallest difference in distance the depth buffer separates at the scene's far side, with
each format (d24, d32f) and each depth range (fit, the default; file, the camera's own planes);
with a warning where that is coarser than the scene's own detail (1 % of its triangle edges are
shorter), since surfaces that close together may then z-fight.

--state-costs measures, on the backend that runs (--backend, default auto), what changing each kind
of render state between two draws costs (paper 004's C(s); src/gl/StateCosts.h): program (shader
variant), mesh, texture, material, face culling and depth test, in microseconds per change over a
plain draw (median and range of 9 rounds of 400 draws), and once each: a new 256x256 texture's
upload and first draw against a resident one, and a draw in a state combination not drawn before
against the same draw again. About a second. --json FILE writes the figures as JSON.
)";
}

int runInfo(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    RenderOptions options;
    bool sceneGiven = false, stateCosts = false;
    std::string jsonPath;
    CommandLine command{"info", infoHelp()};
    FlagGroup shared = someFlags(renderFlags(options), {"--cull-backfaces", "--backend", "--threads"});
    shared.flags.push_back(flag::on("--state-costs", "measure the backend's state-change costs instead of a scene",
                                    stateCosts));
    shared.flags.push_back(flag::text("--json", "FILE", "with --state-costs: the figures as JSON", jsonPath));
    command.flags = {shared};
    command.positional = sceneArgument(options, &sceneGiven);
    command.finish = [&](ArgCursor& cursor) {
        if (stateCosts && sceneGiven)
            cursor.fail("--state-costs measures the backend, not a scene: give one or the other");
        else if (!stateCosts && !sceneGiven)
            cursor.fail("info needs a SCENE (a file or builtin:NAME), or --state-costs");
        else if (!stateCosts && (!jsonPath.empty() || options.gave("backend") || options.gave("threads")))
            cursor.fail("--backend, --threads and --json go with --state-costs");
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;
    if (stateCosts) {
        Result<StateCostsOutput> report = stateCostsReport(options.settings);
        if (!report) return fail(err, report.error());
        out << report->text;
        if (!jsonPath.empty())
            if (Result<bool> written = writeFile(jsonPath, report->json);
                !written)
                return fail(err, written.error());
        return kExitOk;
    }
    Result<Scene> loaded = loadScene(options.scene, options.load);
    if (!loaded) return fail(err, loaded.error());
    out << sceneInfoText(*loaded, kLongSide);
    return kExitOk;
}

}  // namespace frugal
