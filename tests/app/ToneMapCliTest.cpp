// --tonemap through the command line (the real binary): none is the image without the flag, byte for
// byte; each operator changes the lit pixels and leaves the background as it is; GL and the software
// reference agree under each (frugal diff); a bad operator is one line.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "CliSupport.h"
#include "TestSupport.h"
#include "io/ImageIO.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::readAll;
using test::runFrugal;

TEST(ToneMapCliTest, EachOperatorMapsTheLitPixelsOnly) {
    const fs::path dir = test::freshDir("ToneMapCli");
    const auto render = [&](const std::string& name, std::vector<std::string> extra) {
        std::vector<std::string> args = {"render", "builtin:materials", "--size", "160x120"};
        args.insert(args.end(), extra.begin(), extra.end());
        return test::renderedPixels(dir, name, args);
    };
    const std::vector<std::uint8_t> plain = render("plain", {});
    render("none", {"--tonemap", "none"});
    EXPECT_EQ(readAll(dir / "plain.png"), readAll(dir / "none.png"));
    for (const char* op : {"pbr-neutral", "aces"}) {
        const std::vector<std::uint8_t> mapped = render(op, {"--tonemap", op});
        ASSERT_EQ(mapped.size(), plain.size());
        std::size_t changed = 0, background = 0, backgroundKept = 0;
        for (std::size_t i = 0; i < plain.size(); i += 4) {
            const bool isBackground = plain[i] == 31 && plain[i + 1] == 33 && plain[i + 2] == 38;
            background += isBackground;
            backgroundKept += isBackground && mapped[i] == 31 && mapped[i + 1] == 33 && mapped[i + 2] == 38;
            changed += !isBackground && (plain[i] != mapped[i] || plain[i + 1] != mapped[i + 1]);
        }
        EXPECT_GT(background, 1000u) << op;
        EXPECT_EQ(backgroundKept, background) << op << ": the clear colour is not tone-mapped";
        EXPECT_GT(changed, 1000u) << op;
        const CliRun diff = runFrugal(dir, {"diff", "builtin:materials", "--size", "160x120", "--tonemap", op,
                                            "--tolerance", "1", "--out", std::string("diff-") + op});
        EXPECT_EQ(diff.status, 0) << op << ": " << diff.out << diff.err;
    }
    test::expectOneErrorLine(test::freshDir("ToneMapCliBad"),
                             {{{"render", "--tonemap", "filmic"},
                               "error: --tonemap: 'filmic' is not a tone-mapping operator (none, pbr-neutral, aces)"}});
}

}  // namespace
}  // namespace frugal
