// `frugal report`'s page: DIR/index.html, one self-contained file that works offline (no script, no
// font, no image from elsewhere: the chart is inline SVG, the masks are data: URIs). From the top:
// the recommendation, the Pareto chart of median time against differing pixels, the per-method
// table with an error-mask thumbnail beside each method whose colour differs (linked to the full-size mask in
// DIR/masks/), and the seed papers' published figures beside this run's for the methods that come
// from one. Every figure but the papers' columns comes from the report it is given.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <frugal/Result.h>

#include "renderer/Research.h"
#include "lab/Trades.h"

namespace frugal {

struct TradePageFiles {
    std::string html;                                  // index.html
    std::vector<std::pair<std::string, Bytes>> masks;  // "masks/<method>.png": full-size error masks
    std::string papersCsv;                             // papers.csv: the page's second table
    std::string gnuplot;                               // pareto.gp: the chart from report.csv, by gnuplot
};

// The thumbnails are at most this many pixels wide; a block of the mask with any differing pixel
// stays red, so a single differing pixel is still seen.
inline constexpr int kMaskThumbnailWidth = 200;

// The page and the files it links to. Errors: a mask PNG that cannot be encoded.
Result<TradePageFiles> tradePage(const TradeReport& report, const TradeSettings& settings);

// The mask shrunk by an integer factor to at most `maxWidth` pixels wide: red where any pixel of the
// block is red (differs), else the block's mean grey. Rows stay bottom-up, as Buffers' are.
Buffers maskThumbnail(const Buffers& mask, int maxWidth);

// A file name for a method's name: lower case letters, digits and '-' ("cull conservative + reuse"
// -> "cull-conservative-reuse").
std::string methodSlug(const std::string& name);

// papers.csv: each published figure (lab/PaperFigures.h) of a method this report measured, beside
// this run's figures for it.
std::string paperFiguresCsv(const TradeReport& report);

// Standard base64 (RFC 4648, with padding), for data: URIs.
std::string base64(const Bytes& bytes);

}  // namespace frugal
