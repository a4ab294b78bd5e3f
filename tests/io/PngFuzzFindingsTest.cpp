// Every input the PNG reader's fuzzer (fuzz/fuzz_png.cpp) found a problem with, minimised (or made
// small by hand), and inputs made by hand for the checks those findings led to, in
// tests/data/fuzz/png/: each must end in the outcome listed here, and the list names exactly the
// files of that folder (docs/fuzz/README.md tells them).
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "io/ImageIO.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

struct Finding {
    const char* file;   // in tests/data/fuzz/png/
    const char* error;  // the message after "<path>: ", or nullptr when the image decodes
};

const std::vector<Finding>& findings() {
    static const std::vector<Finding> cases = {
        // stb's reason for an unknown chunk quoted its type, here a line break: now the truncated
        // chunk is refused before stb reads it.
        {.file = "chunk-type-with-newline.png", .error = "truncated PNG: the data ends at byte 38 before IEND"},
        // The same reason made by hand in a whole PNG: a chunk type of a NUL and a line break (stb's
        // reason ends at once), and of letters and line breaks.
        {.file = "unknown-chunk-nul.png", .error = "cannot decode: corrupt data (stb_image gives no readable reason)"},
        {.file = "unknown-chunk-newline.png", .error = "cannot decode: A B PNG chunk not known"},
        // stb grew its buffer to an IDAT chunk's declared length (2 GB) before reading it (an OOM;
        // made small by hand).
        {.file = "idat-claims-2gb.png",
         .error = "truncated PNG: chunk 1 ('IDAT') at byte 33 declares 2147483632 bytes and a CRC, 2 bytes follow"},
        // Found reading stb after that: it sizes its first buffer from the declared image, 1 GB here
        // for a file of 142 bytes; and an image over frugal's limit.
        {.file = "size-beyond-data.png",
         .error = "corrupt PNG: 16384x16384 pixels of 32 bits need 1073741824 bytes, which its 85 bytes of image "
                  "data cannot hold (deflate expands at most 1032:1)"},
        // stb copied a first, empty IDAT into a null buffer (UBSan: memcpy's argument is null).
        {.file = "empty-first-idat.png", .error = "unsupported PNG: chunk 1 is an empty IDAT before the image data"},
        {.file = "size-beyond-limit.png",
         .error = "PNG of 20000x20000 pixels, more than frugal's limit of 268435456 (16384x16384)"},
    };
    return cases;
}

const fs::path kDir = fs::path(FRUGAL_TEST_DATA_DIR) / "fuzz" / "png";

TEST(PngFuzzFindingsTest, TheTableListsExactlyTheFilesOfTheFolder) {
    std::set<std::string> onDisk, listed;
    for (const auto& entry : fs::directory_iterator(kDir)) onDisk.insert(entry.path().filename().string());
    for (const Finding& finding : findings()) EXPECT_TRUE(listed.insert(finding.file).second) << finding.file;
    EXPECT_EQ(onDisk, listed);
}

class PngFuzzFinding : public testing::TestWithParam<Finding> {};

TEST_P(PngFuzzFinding, EndsInItsOutcome) {
    const Finding& finding = GetParam();
    const std::string path = (kDir / finding.file).string();
    const Result<DecodedImage> image = readPng(path);
    if (!finding.error) {
        ASSERT_TRUE(image.ok()) << image.error().message;
        const std::size_t samples =
            std::size_t(image->width) * std::size_t(image->height) * std::size_t(image->channels);
        EXPECT_EQ(image->bitDepth == 16 ? image->pixels16.size() : image->pixels8.size(), samples);
        return;
    }
    ASSERT_FALSE(image.ok()) << path << " decoded";
    EXPECT_EQ(image.error().message, path + ": " + finding.error);
}

void PrintTo(const Finding& finding, std::ostream* out) { *out << finding.file; }

INSTANTIATE_TEST_SUITE_P(Inputs, PngFuzzFinding, testing::ValuesIn(findings()),
                         [](const testing::TestParamInfo<Finding>& param) {
                             std::string name = param.param.file;
                             for (char& ch : name)
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             return name;
                         });

}  // namespace
}  // namespace frugal
