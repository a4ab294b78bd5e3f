// `--interp MODE` on the command line: parsed with the shared render options, refused with one line
// for a mode it does not know or a GL backend, and rendering through the software backend's slow
// path when asked (src/software/InterpRaster.h).
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "TestSupport.h"
#include "io/ImageIO.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::runFrugal;  // the frugal binary in a child process

TEST(InterpCliTest, UnknownModeIsOneUsageError) {
    const fs::path dir = test::freshDir("InterpCliUnknown");
    const CliRun run = runFrugal(dir, {"render", "builtin:cubes", "--interp", "wat", "--backend", "software"});
    EXPECT_NE(run.status, 0);
    ASSERT_EQ(run.errLines().size(), 1u) << run.err;
    EXPECT_EQ(run.errLines()[0], "error: --interp: 'wat' is not an interpolation mode (exact, span, dda)");
}

TEST(InterpCliTest, GlBackendIsRefused) {
    const fs::path dir = test::freshDir("InterpCliGl");
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"render", "builtin:cubes", "--interp", "span", "--backend", "egl"},
          std::vector<std::string>{"render", "builtin:cubes", "--backend", "egl", "--interp=span"},
          std::vector<std::string>{"bench", "render", "builtin:cubes", "--interp", "span"}}) {
        const CliRun run = runFrugal(dir, args);
        EXPECT_NE(run.status, 0) << args.back();
        ASSERT_EQ(run.errLines().size(), 1u) << run.err;
        // The settings named are those the command line gave.
        EXPECT_EQ(run.errLines()[0], std::string("error: --interp span") +
                                         (args[0] == "bench" ? "" : " with --backend egl") +
                                         ": only the software backend models the span interpolator");
    }
}

TEST(InterpCliTest, RendersWithEachModeOnTheSoftwareBackend) {
    const fs::path dir = test::freshDir("InterpCliRender");
    const CliRun help = runFrugal(dir, {"render", "--help"});
    EXPECT_NE(help.out.find("--interp MODE"), std::string::npos);
    for (const char* mode : {"exact", "span", "dda"}) {
        const std::string out = std::string(mode) + ".png";
        const CliRun run = runFrugal(dir, {"render", "builtin:cubes", "--size", "48x32", "--backend", "software", "--interp",
                                           mode, "-o", out});
        ASSERT_EQ(run.status, 0) << run.err;
        EXPECT_EQ(run.err.find(" depth interpolation") != std::string::npos, std::string(mode) != "exact") << run.err;
        Result<DecodedImage> image = readPng((dir / out).string());
        ASSERT_TRUE(image) << image.error().message;
        EXPECT_EQ(image->width, 48);
    }
}

}  // namespace
}  // namespace frugal
