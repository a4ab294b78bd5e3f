// Image comparison: a render (or a decoded PNG) against a reference, pixel by pixel, with a stated
// per-channel tolerance. Used by `frugal compare`, `frugal diff` and image regression tests.
//
// Conventions:
// - Inputs are Buffers (pipeline/Buffers.h): RGBA8 colour, optional triangle ids and 24-bit depth, rows
//   bottom-up. PNGs are brought into that form by buffersFromPng (rows flipped once).
// - A pixel FAILS when any of its four channels (alpha included) differs by more than `tolerance`
//   8-bit steps. The verdict is colour only: a comparison passes when no pixel fails. Ids and depth
//   are diagnostics that say why colours differ (a rasterization rule, a depth tie), since an id or
//   depth difference that leaves the colour alike is not visible in the image.
// - Coverage (is a pixel background or geometry?): from the ids when both sides have them (id 0 is
//   background); otherwise, when a background colour is given, a pixel is background when each of
//   its four channels is within `tolerance` of that colour, so that the same tolerance that lets a
//   colour pass also lets a near-background pixel count as background; otherwise not computed.
// - Triangle-id mismatches count pixels covered on both sides whose ids differ; pixels covered on
//   one side only are coverage mismatches, not id mismatches.
// - Depth (both sides have depth): the largest |difference| in 24-bit LSB over pixels covered on
//   both sides (over every pixel when coverage is not computed). Background depth is the clear
//   value, so a coverage mismatch would otherwise hide every real depth difference.
// - PSNR = 10·log10(255² / MSE), MSE over all four channels of every pixel; +inf when identical.
// - Positions are reported as image (file) coordinates: x right, y down from the top row.
// - Error mask (as dEQP's image comparisons write one): red (255,0,0,255) where a pixel fails, the
//   reference in grey elsewhere (luma 0.299R + 0.587G + 0.114B, alpha 255), rows as the inputs.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include <frugal/Image.h>
#include <frugal/Result.h>

#include "renderer/Research.h"

namespace frugal {

struct CompareOptions {
    int tolerance = 0;  // per channel, in 8-bit steps, 0..255
    // Colour of the background, for coverage when the ids are missing on either side.
    std::optional<std::array<std::uint8_t, 4>> background;
};

struct PixelPosition {
    int x = 0, y = 0;  // image coordinates, y = 0 is the top row
};

struct ImageComparison {
    int width = 0, height = 0;
    int tolerance = 0;
    std::size_t pixels = 0;
    std::size_t failingPixels = 0;         // some channel differs by more than the tolerance
    int maxChannelDifference = 0;          // 0..255, over all channels
    std::optional<PixelPosition> worstPixel;  // where maxChannelDifference first occurs (when > 0)
    double psnr = 0.0;                     // dB; +inf when identical

    enum class CoverageSource { None, Ids, BackgroundColor };
    CoverageSource coverageSource = CoverageSource::None;
    std::size_t coveredOnlyInActual = 0;      // geometry in actual, background in reference
    std::size_t coveredOnlyInReference = 0;   // background in actual, geometry in reference
    std::size_t coverageMismatches() const { return coveredOnlyInActual + coveredOnlyInReference; }

    std::optional<std::size_t> idMismatches;  // when both sides have ids

    struct Depth {
        DepthFormat format = DepthFormat::D24;
        // D24: 24-bit steps (LSB). D32F: floats between the two values (ULP; Buffers' depth bits).
        std::uint32_t maxDifference = 0;
        std::size_t differingPixels = 0;   // pixels compared whose depth differs at all
        std::size_t comparedPixels = 0;
        std::optional<PixelPosition> worstPixel;
    };
    std::optional<Depth> depth;  // when both sides have depth

    Buffers mask;  // RGBA only: see the error mask rule above

    bool passed() const { return failingPixels == 0; }
    bool identical() const { return maxChannelDifference == 0; }
};

// Compares `actual` with `reference`. Ids and depth are compared when both sides have them (a
// vector is either empty or holds one value a pixel). Errors: a size mismatch ("size differs:
// actual 64x48, reference 32x24"), a tolerance outside 0..255, or a vector of the wrong length.
Result<ImageComparison> compareBuffers(const Buffers& actual, const Buffers& reference,
                                       const CompareOptions& options = {});

// A decoded colour PNG (8-bit, 1 to 4 channels: grey is copied to RGB, a missing alpha is 255)
// and optionally frugal's triangle-id PNG (8-bit RGBA, the bytes are the id, little-endian) as
// Buffers. Errors say what is wrong without the file name; the caller names the file.
Result<Buffers> buffersFromPng(const DecodedImage& color);
Result<bool> addIdsFromPng(Buffers& buffers, const DecodedImage& ids);

// Reads a colour PNG and, when `idsPath` is not empty, its id PNG. Error "<file>: <why>".
Result<Buffers> readRenderPngs(const std::string& colorPath, const std::string& idsPath = {});

// Pixels whose RGBA bytes differ at all, over the pixels both images have (the quick count of the
// benches; compareBuffers gives the full metrics).
std::size_t differingColorPixels(const Buffers& a, const Buffers& b);

// The error mask as a PNG (rows flipped to top first, like every frugal image file).
Result<Bytes> encodeMaskPng(const ImageComparison& comparison);

// The metrics as a JSON object (keys: size, pixels, tolerance, passed, failing_pixels,
// failing_fraction, max_channel_difference, worst_pixel, identical, psnr_db (null when infinite),
// coverage {source, mismatches, covered_only_in_actual, covered_only_in_reference},
// id_mismatches, depth {format, max_difference_lsb (ULP for d32f), differing_pixels, compared_pixels, worst_pixel};
// absent measurements are null).
std::string comparisonJson(const ImageComparison& comparison);

// The metrics for people, a few lines each indented by `indent`, ending in a newline. `actual` and
// `reference` name the two sides ("a.png", "egl-surfaceless", ...).
std::string comparisonSummary(const ImageComparison& comparison, const std::string& actual,
                              const std::string& reference, const std::string& indent = "  ");

// PSNR as people read it: "inf" or "38.21 dB".
std::string formatPsnr(double psnr);

}  // namespace frugal
