// `frugal report`'s page (lab/TradePage.h) on a report made by hand: what it shows is what the
// report holds, a mask for each inexact method, nothing from elsewhere; and its small parts.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <regex>
#include <string>

#include "lab/TradePage.h"
#include "lab/ImageCompare.h"

namespace frugal {
namespace {

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
    return n;
}

Bytes bytesOf(const std::string& s) { return Bytes(s.begin(), s.end()); }

TEST(TradePageTest, Base64IsRfc4648) {
    EXPECT_EQ(base64(bytesOf("")), "");
    EXPECT_EQ(base64(bytesOf("f")), "Zg==");
    EXPECT_EQ(base64(bytesOf("fo")), "Zm8=");
    EXPECT_EQ(base64(bytesOf("foo")), "Zm9v");
    EXPECT_EQ(base64(bytesOf("foobar")), "Zm9vYmFy");
    EXPECT_EQ(base64(Bytes{0xff, 0xfe, 0x00}), "//4A");
}

TEST(TradePageTest, SlugsAreFileNames) {
    EXPECT_EQ(methodSlug("cull conservative + reuse"), "cull-conservative-reuse");
    EXPECT_EQ(methodSlug("hsr depthsort"), "hsr-depthsort");
    EXPECT_EQ(methodSlug("../A B/"), "a-b");
    EXPECT_EQ(methodSlug("+++"), "method");
}

// A mask as compareBuffers writes it: grey `g` everywhere, red at the pixels given.
Buffers mask(int w, int h, std::uint8_t g, const std::vector<std::pair<int, int>>& red) {
    Buffers b;
    b.width = w;
    b.height = h;
    b.rgba.assign(b.pixelCount() * 4, g);
    for (std::size_t i = 3; i < b.rgba.size(); i += 4) b.rgba[i] = 255;
    for (const auto& [x, y] : red) {
        std::uint8_t* p = &b.rgba[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4];
        p[0] = 255;
        p[1] = p[2] = 0;
    }
    return b;
}

TEST(TradePageTest, AThumbnailKeepsASingleDifferingPixelRed) {
    const Buffers full = mask(801, 600, 100, {{800, 599}});
    const Buffers t = maskThumbnail(full, 200);
    EXPECT_EQ(t.width, 161) << "factor 5: 801 / 5 rounded up";
    EXPECT_EQ(t.height, 120);
    std::size_t red = 0;
    for (std::size_t i = 0; i < t.pixelCount(); ++i) {
        const std::uint8_t* p = &t.rgba[i * 4];
        if (p[0] == 255 && p[1] == 0) {
            ++red;
            EXPECT_EQ(i, t.pixelCount() - 1) << "the last block holds it";
        } else {
            EXPECT_EQ(p[0], 100);
            EXPECT_EQ(p[1], 100);
        }
        EXPECT_EQ(p[3], 255);
    }
    EXPECT_EQ(red, 1u);
    const Buffers same = maskThumbnail(mask(120, 90, 7, {}), 200);
    EXPECT_EQ(same.width, 120) << "a mask narrower than the thumbnail is kept";
    EXPECT_EQ(same.rgba, mask(120, 90, 7, {}).rgba);
}

TradeRow row(const std::string& name, const std::string& family, double ms, std::uint64_t px, bool floor = false) {
    TradeRow r;
    r.candidate.name = name;
    r.candidate.family = family;
    r.candidate.floor = floor;
    r.candidate.settings.width = 40;
    r.candidate.settings.height = 30;
    r.medianMs = ms;
    r.differingPx = px;
    r.worstFramePx = px;
    r.misses = px / 100;
    r.worstPsnr = px ? 31.5 : std::numeric_limits<double>::infinity();
    if (px) {
        r.worstMask = mask(40, 30, 80, {{1, 2}});
        r.worstShot = "view 1 (partial)";
    }
    return r;
}

TEST(TradePageTest, ThePageShowsTheReportAndAMaskForEachInexactMethod) {
    TradeReport report;
    report.backend = "software (test)";
    report.rows = {row("plain", "plain", 10.0, 0),          row("cull paper", "cull", 4.25, 1234),
                   row("cull oracle", "floor", 3.0, 0, true), row("order key", "order", 9.0, 0),
                   row("hsr depthsort", "hsr", 12.0, 56),     row("order greedy", "order", 9.5, 0),
                   row("cull conservative + order key", "combination", 9.1, 0)};
    report.rows[0].paired = {1.0, 1.0, 1.0, 64};
    report.rows[1].paired = {0.43, 0.41, 0.452, 64};
    report.rows[3].paired = {0.9, 0.88, 0.925, 64};
    report.rows[4].paired = {1.2, 1.1, 1.3, 64};
    report.rows[5].paired = {0.95, 0.93, 0.96, 64};
    report.rows[5].sameDrawsAs = 0;
    report.rows[6].paired = {0.91, 0.89, 0.93, 64};
    report.rows[6].sameDrawsAs = 3;
    report.bestExact = 3;
    report.pareto = {1, 3};
    TradeSettings settings;
    settings.scene = "a<b>&\"c\".obj";
    settings.shots.resize(2);
    Result<TradePageFiles> page = tradePage(report, settings);
    ASSERT_TRUE(page) << page.error().message;
    const std::string& html = page->html;

    EXPECT_EQ(html.find("a<b>"), std::string::npos) << "the scene's name is escaped";
    EXPECT_NE(html.find("a&lt;b&gt;&amp;&quot;c&quot;.obj"), std::string::npos);
    EXPECT_EQ(count(html, "<script"), 0u) << "no script: nothing to fail, nothing from elsewhere";
    EXPECT_EQ(std::regex_search(html, std::regex(R"((src|href)="(https?:)?//)")), false) << "nothing from the network";
    EXPECT_EQ(count(html, "<svg id=\"pareto\""), 1u);
    EXPECT_EQ(count(html, "<circle cx="), report.rows.size() + 6) << "a point per row and a legend dot per family";
    EXPECT_EQ(count(html, "<table id=\"methods\">"), 1u);
    EXPECT_EQ(count(html, "<table id=\"papers\">"), 1u);

    // Each inexact row: a thumbnail inline, linked to its full mask.
    EXPECT_EQ(count(html, "<img class=\"mask\" src=\"data:image/png;base64,"), 2u);
    ASSERT_EQ(page->masks.size(), 2u);
    EXPECT_EQ(page->masks[0].first, "masks/cull-paper.png");
    EXPECT_EQ(page->masks[1].first, "masks/hsr-depthsort.png");
    EXPECT_NE(html.find("<a href=\"masks/cull-paper.png\">"), std::string::npos);
    Result<DecodedImage> full = decodePng(page->masks[0].second, "mask");
    ASSERT_TRUE(full) << full.error().message;
    EXPECT_EQ(full->width, 40);
    EXPECT_EQ(full->height, 30);

    // The figures are the report's.
    EXPECT_NE(html.find("<td>cull paper</td><td>cull</td><td>4.250</td><td>0.425</td><td class=\"pays\">0.430 "
                        "<small>[0.410, 0.452]</small></td><td>1.42</td><td>1,234</td><td>1,234</td><td>12</td>"),
              std::string::npos)
        << "the paired ratio and its interval beside the ratio of medians";
    EXPECT_NE(html.find("<td>hsr depthsort</td><td>hsr</td><td>12.000</td><td>1.200</td><td>1.200 "
                        "<small>[1.100, 1.300]</small></td>"),
              std::string::npos)
        << "an interval above the line does not pay";
    EXPECT_NE(html.find("<td>0.950 <small>[0.930, 0.960]</small><br><small>no-op: draws the plain render's "
                        "draws</small></td>"),
              std::string::npos)
        << "a no-op says so, and does not pay though its interval is below the line";
    EXPECT_EQ(count(html, "no-op: draws the plain render's draws</small>"), 1u);
    EXPECT_NE(html.find("<td>0.910 <small>[0.890, 0.930]</small><br><small>adds nothing to order key: draws its "
                        "draws</small></td>"),
              std::string::npos)
        << "a combination whose cull changed nothing";
    EXPECT_NE(html.find("<b>Fastest exact:</b> <code>order key</code>, 9.00 ms a frame, 0.90&times; the plain "
                        "render's 10.00 ms; paired with it shot by shot, 0.900&times; (95 % interval "
                        "0.880&ndash;0.925); 0 pixels differ."),
              std::string::npos);
    EXPECT_NE(html.find("no method is surely at least 3 % faster"), std::string::npos) << "no pick within the budget";
    EXPECT_NE(html.find("2000 resamples, seed 20261203"), std::string::npos) << "how the intervals were drawn";
    EXPECT_NE(html.find("view 1 (partial): 1,234 px"), std::string::npos);

    // The papers' figures only for the methods measured: no reuse row here.
    EXPECT_EQ(page->papersCsv.find("\nreuse,"), std::string::npos);
    EXPECT_EQ(count(page->papersCsv, "\ncull paper,002,"), 2u);
    EXPECT_EQ(count(page->papersCsv, "\nhsr depthsort,003,"), 1u);
    EXPECT_NE(page->papersCsv.find(",0.425,1234\n"), std::string::npos) << "this run's × plain and pixels beside";
    EXPECT_NE(page->gnuplot.find("'report.csv'"), std::string::npos);
}

}  // namespace
}  // namespace frugal
