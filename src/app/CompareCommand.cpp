// `frugal compare A.png B.png`: an image against a reference, with the metrics of
// lab/ImageCompare.h. A is the image under test ("actual"), B the reference.
#include <filesystem>
#include <ostream>

#include <nlohmann/json.hpp>

#include <frugal/Files.h>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "lab/ImageCompare.h"

namespace frugal {

const char* compareHelp() {
    return R"(usage: frugal compare A.png B.png [--ids A_ids.png B_ids.png] [--tolerance N]
                      [--mask FILE.png] [--json FILE] [--background R,G,B[,A]]

Compares A (the image under test) with B (the reference), pixel by pixel, and prints how far they
differ. A pixel fails when any channel, alpha included, differs by more than N 8-bit steps; the
exit status is 0 when no pixel fails, 1 otherwise. Images are 8-bit PNGs (grey, grey+alpha, RGB or
RGBA), of the same size.

Reported: pixels beyond tolerance, largest channel difference and where, PSNR (inf when
identical), coverage mismatches (geometry in one image, background in the other) and, with --ids,
pixels covered in both whose triangle ids differ.
)";
}

namespace {

// The two renders read (colour PNGs, with their id PNGs when given) and compared; errors name the file.
Result<ImageComparison> compareFiles(const std::string& actualPath, const std::string& actualIds,
                                     const std::string& referencePath, const std::string& referenceIds,
                                     const CompareOptions& options) {
    Result<Buffers> actual = readRenderPngs(actualPath, actualIds);
    if (!actual) return actual.error();
    Result<Buffers> reference = readRenderPngs(referencePath, referenceIds);
    if (!reference) return reference.error();
    if (actual->width != reference->width || actual->height != reference->height)
        return Error{referencePath + ": " + std::to_string(reference->width) + "x" + std::to_string(reference->height) +
                     ", but " + actualPath + " is " + std::to_string(actual->width) + "x" +
                     std::to_string(actual->height)};
    Result<ImageComparison> compared = compareBuffers(*actual, *reference, options);
    if (!compared) return Error{referencePath + ": " + compared.error().message};
    return compared;
}

}  // namespace

int runCompare(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    std::vector<std::string> images;
    std::string actualIds, referenceIds, maskPath, jsonPath;
    RenderOptions colors;  // only --background is read into it
    CompareOptions options;
    CommandLine command{"compare", compareHelp()};
    FlagGroup background = someFlags(renderFlags(colors), {"--background"});
    background.flags[0].help = "without --ids, a pixel is background when every channel is within N of this colour, "
                               "in [0,1] (default frugal's, 0.12,0.13,0.15)";
    command.flags = {{"", {
        flag::whole("--tolerance", "N", "per-channel tolerance in 8-bit steps, 0 to 255 (default 0: identical)",
                    options.tolerance, 0, 255),
        flag::two("--ids", "A_ids B_ids", "frugal triangle-id PNGs of A and B (render --ids): coverage (id 0 is the "
                  "background) and triangle-id mismatches are measured from them", actualIds, referenceIds,
                  "expected two id images, A_ids.png B_ids.png"),
        background.flags[0],
        {"--mask", "FILE.png", "error mask: red where a pixel fails, B in grey elsewhere",
         [&maskPath](const std::string& path) -> std::string {
             if (!hasExtension(path, ".png")) return "is not a .png name (the mask is written as PNG)";
             maskPath = path;
             return {};
         }},
        flag::text("--json", "FILE", "the metrics as JSON (psnr_db is null when the images are identical)", jsonPath),
    }}};
    command.positional = [&images](const std::string& argument, ArgCursor& cursor) {
        if (images.size() < 2) images.push_back(argument);
        else cursor.fail("unexpected argument '" + argument + "' (two images only: A.png B.png)");
    };
    command.finish = [&](ArgCursor& cursor) {
        if (images.size() != 2) cursor.fail("compare: expected two images, A.png B.png (see 'frugal help compare')");
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;
    options.background = colorBytes(colors.settings.background);
    const std::string& actualPath = images[0];
    const std::string& referencePath = images[1];

    Result<ImageComparison> compared = compareFiles(actualPath, actualIds, referencePath, referenceIds, options);
    if (!compared) return fail(err, compared.error());
    const ImageComparison& c = *compared;

    // The mask and the JSON appear together or not at all.
    FileSet files;
    if (!maskPath.empty()) files.add(maskPath, encodeMaskPng(c));
    if (!jsonPath.empty()) {
        nlohmann::ordered_json j = {{"command", "compare"},
                                    {"actual", {{"file", actualPath}, {"ids", actualIds.empty() ? nullptr : nlohmann::ordered_json(actualIds)}}},
                                    {"reference", {{"file", referencePath}, {"ids", referenceIds.empty() ? nullptr : nlohmann::ordered_json(referenceIds)}}},
                                    {"mask", maskPath.empty() ? nullptr : nlohmann::ordered_json(maskPath)}};
        j.update(nlohmann::ordered_json::parse(comparisonJson(c)));
        const std::string text = j.dump(2) + "\n";
        files.add(jsonPath, text);
    }
    if (Result<bool> written = files.commit(); !written) return fail(err, written.error());

    out << actualPath << " vs " << referencePath << " (reference), " << c.width << "x" << c.height << ": "
        << (c.passed() ? "PASS" : "FAIL") << "\n"
        << comparisonSummary(c, actualPath, referencePath);
    return c.passed() ? kExitOk : kExitError;
}

}  // namespace frugal
