// `frugal-lab compress`: a compressed copy of a glTF file (lab/GltfCompress.h), to test and measure
// the loader's decoders on the files a user would bring.
#include <ostream>

#include <frugal/Files.h>

#include "app/Cli.h"
#include "app/Command.h"
#include "commands/LabCommands.h"
#include "lab/GltfCompress.h"

namespace frugal {

const char* compressHelp() {
    return R"(usage: frugal-lab compress IN.gltf OUT.gltf (--draco | --meshopt) [options]

Writes IN compressed as OUT, one self-contained .gltf (its data in a data URI): with --draco every
TRIANGLES primitive in a KHR_draco_mesh_compression stream (libdraco), with --meshopt every
bufferView whose layout meshoptimizer's codecs take in an EXT_meshopt_compression stream, decoded
into a fallback buffer without data. IN is a .gltf whose buffers are files beside it or data URIs.
Without --bits and --filters nothing is lost: OUT renders as IN does (Edgebreaker, Draco's default
encoder, reorders points and faces, so triangle ids follow the decoded order).
)";
}

int runCompress(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    CompressOptions options;
    bool draco = false, meshopt = false;
    std::vector<std::string> files;
    CommandLine command{"compress", compressHelp()};
    command.flags = {{"", {
        flag::on("--draco", "KHR_draco_mesh_compression", draco),
        flag::on("--meshopt", "EXT_meshopt_compression", meshopt),
        flag::whole("--bits", "N", "Draco: quantize positions to N bits, normals, texture coordinates and colours to "
                    "at least 10 (default 0: exact)", options.dracoBits, 0, 30),
        flag::on("--sequential", "Draco: the sequential encoder, which keeps the order of points and faces (triangle ids "
           "stay the file's)", options.dracoSequential),
        flag::on("--triangles", "meshopt: triangle lists in the TRIANGLES codec, which may rotate a triangle's vertices "
           "(its winding kept), instead of INDICES", options.meshoptTriangles),
        flag::on("--filters", "meshopt: normals in 16-bit octahedral (KHR_mesh_quantization), positions with a 15-bit "
           "mantissa (exponential): lossy", options.meshoptFilters),
    }}};
    command.positional = [&](const std::string& argument, ArgCursor& cursor) {
        if (files.size() == 2) cursor.fail("unexpected argument '" + argument + "' (IN.gltf OUT.gltf only)");
        else files.push_back(argument);
    };
    command.finish = [&](ArgCursor& cursor) {
        if (files.size() != 2) cursor.fail("give IN.gltf and OUT.gltf");
        else if (draco == meshopt) cursor.fail("give one of --draco and --meshopt");
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;
    options.method = draco ? CompressOptions::Method::Draco : CompressOptions::Method::Meshopt;
    const Result<std::string> text = compressGltf(files[0], options);
    if (!text) return fail(err, text.error());
    if (const Result<bool> written = writeFile(files[1], *text); !written) return fail(err, written.error());
    out << files[1] << ": " << text->size() << " bytes\n";
    return kExitOk;
}

}  // namespace frugal
