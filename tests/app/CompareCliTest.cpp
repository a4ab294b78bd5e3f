// `frugal compare` and `frugal diff`, end to end: the real binary in a child process (exit status,
// stdout, stderr, JSON, files left behind). Compare runs on images built here, whose answers are
// known by hand; diff runs a built-in scene on GL and on the software reference.
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestSupport.h"
#include "io/ImageIO.h"
#include "lab/ImageCompare.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::filesIn;
using test::readAll;
using test::runFrugal;

// A 4×3 grey image with one pixel, (1, 0) in file coordinates, raised by `delta` in green.
void writeGrey(const fs::path& path, int delta) {
    std::vector<std::uint8_t> rgba(4 * 3 * 4, 100);
    for (std::size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 255;
    rgba[4 * 1 + 1] = std::uint8_t(100 + delta);
    ASSERT_TRUE(writeFileAtomic(path.string(), encodePng(4, 3, 4, 8, rgba.data())));
}

// frugal's id PNG of a 4×3 image: ids[i] for pixel i, file order.
void writeIds(const fs::path& path, const std::vector<std::uint32_t>& ids) {
    std::vector<std::uint8_t> bytes;
    for (std::uint32_t id : ids)
        for (int k = 0; k < 4; ++k) bytes.push_back(std::uint8_t(id >> (8 * k)));
    ASSERT_TRUE(writeFileAtomic(path.string(), encodePng(4, 3, 4, 8, bytes.data())));
}

nlohmann::json readJson(const fs::path& path) { return nlohmann::json::parse(readAll(path)); }

TEST(CompareCliTest, ExitStatusFollowsTheTolerance) {
    const fs::path dir = test::freshDir("CompareTolerance");
    writeGrey(dir / "a.png", 3);
    writeGrey(dir / "b.png", 0);

    CliRun run = runFrugal(dir, {"compare", "a.png", "b.png", "--tolerance", "2", "--json", "c.json", "--mask", "m.png"});
    EXPECT_EQ(run.status, 1) << run.err;
    EXPECT_EQ(run.err, "");
    EXPECT_EQ(run.out.rfind("a.png vs b.png (reference), 4x3: FAIL\n", 0), 0u) << run.out;
    EXPECT_NE(run.out.find("pixels beyond tolerance 2: 1 of 12 (8.33%)"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("largest channel difference: 3 at (1, 0)"), std::string::npos) << run.out;
    const nlohmann::json j = readJson(dir / "c.json");
    EXPECT_EQ(j["command"], "compare");
    EXPECT_EQ(j["actual"]["file"], "a.png");
    EXPECT_EQ(j["reference"]["file"], "b.png");
    EXPECT_EQ(j["tolerance"], 2);
    EXPECT_EQ(j["passed"], false);
    EXPECT_EQ(j["failing_pixels"], 1);
    EXPECT_EQ(j["max_channel_difference"], 3);
    EXPECT_EQ(j["worst_pixel"]["x"], 1);
    EXPECT_EQ(j["worst_pixel"]["y"], 0);
    EXPECT_GT(j["psnr_db"].get<double>(), 40.0);
    EXPECT_EQ(j["coverage"]["source"], "background_colour");
    EXPECT_TRUE(j["id_mismatches"].is_null());

    // The mask: red at the failing pixel, the reference's grey elsewhere.
    Result<DecodedImage> mask = readPng((dir / "m.png").string());
    ASSERT_TRUE(mask) << mask.error().message;
    ASSERT_EQ(mask->channels, 4);
    const std::vector<std::uint8_t>& m = mask->pixels8;
    EXPECT_EQ(std::vector<std::uint8_t>(m.begin() + 4, m.begin() + 8), (std::vector<std::uint8_t>{255, 0, 0, 255}));
    EXPECT_EQ(std::vector<std::uint8_t>(m.begin(), m.begin() + 4), (std::vector<std::uint8_t>{100, 100, 100, 255}));

    run = runFrugal(dir, {"compare", "a.png", "b.png", "--tolerance", "3"});
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.out.rfind("a.png vs b.png (reference), 4x3: PASS\n", 0), 0u) << run.out;
}

TEST(CompareCliTest, IdenticalImagesHaveInfinitePsnr) {
    const fs::path dir = test::freshDir("CompareIdentical");
    writeGrey(dir / "a.png", 0);
    const CliRun run = runFrugal(dir, {"compare", "a.png", "a.png", "--json", "c.json"});
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.out.find("largest channel difference: 0; PSNR inf"), std::string::npos) << run.out;
    const nlohmann::json j = readJson(dir / "c.json");
    EXPECT_TRUE(j["psnr_db"].is_null());
    EXPECT_EQ(j["identical"], true);
    EXPECT_EQ(j["passed"], true);
}

TEST(CompareCliTest, IdsGiveCoverageAndTriangleMismatches) {
    const fs::path dir = test::freshDir("CompareIds");
    writeGrey(dir / "a.png", 0);
    writeGrey(dir / "b.png", 0);
    // Pixel 0 covered in A only, pixel 1 in B only, pixel 2 by different triangles, pixel 3 alike.
    writeIds(dir / "a_ids.png", {7, 0, 0x01020304, 9, 0, 0, 0, 0, 0, 0, 0, 0});
    writeIds(dir / "b_ids.png", {0, 8, 0x01020305, 9, 0, 0, 0, 0, 0, 0, 0, 0});
    const CliRun run = runFrugal(dir, {"compare", "a.png", "b.png", "--ids", "a_ids.png", "b_ids.png", "--json", "c.json"});
    EXPECT_EQ(run.status, 0) << "colours are identical; ids do not decide the verdict\n" << run.err;
    EXPECT_NE(run.out.find("coverage mismatches (from ids): 2 (geometry only in a.png: 1, only in b.png: 1)"),
              std::string::npos) << run.out;
    EXPECT_NE(run.out.find("triangle-id mismatches: 1"), std::string::npos) << run.out;
    const nlohmann::json j = readJson(dir / "c.json");
    EXPECT_EQ(j["coverage"]["source"], "ids");
    EXPECT_EQ(j["coverage"]["mismatches"], 2);
    EXPECT_EQ(j["id_mismatches"], 1);
    EXPECT_EQ(j["actual"]["ids"], "a_ids.png");
}

struct BadCase {
    std::vector<std::string> args;
    int status;
    std::string message;  // the whole of stderr, one line
};

TEST(CompareCliTest, BadFilesAndCommandLinesGetOneLineAndNoFile) {
    const fs::path dir = test::freshDir("CompareBad");
    fs::create_directories(dir / "in");
    writeGrey(dir / "in" / "a.png", 0);
    std::vector<std::uint8_t> small(4 * 2 * 2, 255);
    ASSERT_TRUE(writeFileAtomic((dir / "in" / "small.png").string(), encodePng(2, 2, 4, 8, small.data())));
    const std::uint16_t deep[12] = {};
    ASSERT_TRUE(writeFileAtomic((dir / "in" / "deep.png").string(), encodePng(4, 3, 1, 16, deep)));
    test::writeFile(dir / "in" / "text.png", "not a png\n");
    const BadCase cases[] = {
        {{"compare", "in/a.png", "in/missing.png"}, 1, "error: in/missing.png: cannot open"},
        {{"compare", "in/text.png", "in/a.png"}, 1,
         "error: in/text.png: not a PNG: the file does not start with the PNG signature"},
        {{"compare", "in/a.png", "in/small.png"}, 1, "error: in/small.png: 2x2, but in/a.png is 4x3"},
        {{"compare", "in/a.png", "in/deep.png"}, 1, "error: in/deep.png: 16-bit PNG; colour images are compared as 8-bit"},
        {{"compare", "in/a.png", "in/a.png", "--ids", "in/a.png", "in/small.png"}, 1,
         "error: in/small.png: id image is 2x2 but its colour image is 4x3"},
        {{"compare", "in/a.png"}, 2, "error: compare: expected two images, A.png B.png (see 'frugal help compare')"},
        {{"compare", "in/a.png", "in/a.png", "in/a.png"}, 2, "error: unexpected argument 'in/a.png' (two images only: A.png B.png)"},
        {{"compare", "in/a.png", "in/a.png", "--tolerance", "256"}, 2, "error: --tolerance: '256' is not a whole number from 0 to 255"},
        {{"compare", "in/a.png", "in/a.png", "--tolerance", "x"}, 2, "error: --tolerance: 'x' is not a whole number from 0 to 255"},
        {{"compare", "in/a.png", "in/a.png", "--mask", "m.jpg"}, 2, "error: --mask: 'm.jpg' is not a .png name (the mask is written as PNG)"},
        {{"compare", "in/a.png", "in/a.png", "--ids", "in/a.png"}, 2, "error: --ids: expected two id images, A_ids.png B_ids.png"},
        {{"compare", "in/a.png", "in/a.png", "--wat"}, 2, "error: --wat: unknown option (see 'frugal help compare')"},
        {{"diff", "--backend", "software"}, 2,
         "error: --backend software: diff compares a GL backend with the software reference; choose auto, egl, "
         "egl-device, egl-surfaceless or osmesa"},
        {{"diff", "--tolerance", "-1"}, 2, "error: --tolerance: '-1' is not a whole number from 0 to 255"},
        {{"diff", "missing.glb"}, 1, "error: missing.glb: no such file"},
    };
    for (const BadCase& c : cases) {
        std::string joined;
        for (const std::string& a : c.args) joined += a + " ";
        SCOPED_TRACE(joined);
        std::vector<std::string> args = c.args;
        // Outputs asked for, to check that none is written on an error.
        if (args[0] == "compare") args.insert(args.end(), {"--json", "c.json", "--mask", "m.png"});
        const CliRun run = runFrugal(dir, args);
        EXPECT_EQ(run.status, c.status);
        EXPECT_EQ(run.err, c.message + "\n");
        EXPECT_EQ(run.out, "");
        EXPECT_EQ(filesIn(dir), std::vector<std::string>{"in"}) << "no output file may be left behind";
    }
}

TEST(CompareCliTest, HelpNamesTheOptions) {
    const fs::path dir = test::freshDir("CompareHelp");
    const CliRun compare = runFrugal(dir, {"help", "compare"});
    EXPECT_EQ(compare.status, 0);
    for (const char* text : {"--ids", "--tolerance", "--mask", "--json", "--background", "reference"})
        EXPECT_NE(compare.out.find(text), std::string::npos) << text;
    const CliRun diff = runFrugal(dir, {"diff", "--help"});
    EXPECT_EQ(diff.status, 0);
    for (const char* text : {"--tolerance", "--out", "--json", "--frames", "--backend", "software"})
        EXPECT_NE(diff.out.find(text), std::string::npos) << text;
}

// The GL backend and the software reference agree on builtin:cubes within the default tolerance;
// a passing run writes no image unless --out asks for them.
TEST(CompareCliTest, DiffOfTheCubesPassesWithTheDefaultTolerance) {
    const fs::path dir = test::freshDir("DiffCubes");
    CliRun run = runFrugal(dir, {"diff", "builtin:cubes", "--size", "64x48", "--json", "d.json", "-q"});
    EXPECT_EQ(run.status, 0) << run.out << run.err;
    EXPECT_NE(run.out.find("frame 0 (t=0 s): PASS"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("diff builtin:cubes: 1 of 1 frame within tolerance"), std::string::npos) << run.out;
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{"d.json"}) << "nothing but the JSON when every frame passes";
    const nlohmann::json j = readJson(dir / "d.json");
    EXPECT_EQ(j["command"], "diff");
    EXPECT_EQ(j["passed"], true);
    EXPECT_EQ(j["reference"]["backend"], "software");
    ASSERT_EQ(j["frames"].size(), 1u);
    const nlohmann::json& frame = j["frames"][0];
    EXPECT_EQ(frame["coverage"]["source"], "ids");
    EXPECT_FALSE(frame["depth"].is_null());
    EXPECT_TRUE(frame["files"].is_null());
    if (!j["passed"].get<bool>()) std::cout << run.out;

    // --out writes actual, reference and mask of every frame.
    run = runFrugal(dir, {"diff", "builtin:cubes?count=4", "--size", "32x24", "--frames", "1:2", "--out", "out", "-q"});
    EXPECT_EQ(run.status, 0) << run.out << run.err;
    EXPECT_EQ(filesIn(dir / "out"), (std::vector<std::string>{"actual_0001.png", "actual_0002.png", "mask_0001.png",
                                                              "mask_0002.png", "reference_0001.png",
                                                              "reference_0002.png"}));
}

}  // namespace
}  // namespace frugal
