#include "lab/ImageCompare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include <nlohmann/json.hpp>

namespace frugal {

namespace {

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

// Vectors are empty (absent) or one value a pixel; anything else is a caller's mistake that would
// read out of bounds, so it is reported rather than asserted: Buffers may come from files.
std::string checkLengths(const Buffers& b, const char* side) {
    const std::size_t n = b.pixelCount();
    if (b.rgba.size() != 4 * n)
        return std::string(side) + ": " + std::to_string(b.rgba.size()) + " colour bytes for " + std::to_string(n) +
               " pixels (" + sizeText(b.width, b.height) + ", 4 bytes a pixel)";
    if (!b.ids.empty() && b.ids.size() != n)
        return std::string(side) + ": " + std::to_string(b.ids.size()) + " ids for " + std::to_string(n) + " pixels";
    if (!b.depth.empty() && b.depth.size() != n)
        return std::string(side) + ": " + std::to_string(b.depth.size()) + " depth values for " + std::to_string(n) +
               " pixels";
    return {};
}

// Buffers rows are bottom-up; reports speak in file coordinates (top row is y = 0).
PixelPosition imagePosition(std::size_t index, int width, int height) {
    const int x = int(index % std::size_t(width));
    const int row = int(index / std::size_t(width));
    return {x, height - 1 - row};
}

nlohmann::ordered_json positionJson(const std::optional<PixelPosition>& p) {
    if (!p) return nullptr;
    return {{"x", p->x}, {"y", p->y}};
}

std::string percent(std::size_t part, std::size_t whole) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f%%", whole ? 100.0 * double(part) / double(whole) : 0.0);
    return buf;
}

const char* coverageName(ImageComparison::CoverageSource source) {
    switch (source) {
        case ImageComparison::CoverageSource::Ids: return "ids";
        case ImageComparison::CoverageSource::BackgroundColor: return "background colour";
        case ImageComparison::CoverageSource::None: break;
    }
    return "none";
}

}  // namespace

Result<ImageComparison> compareBuffers(const Buffers& actual, const Buffers& reference, const CompareOptions& options) {
    if (options.tolerance < 0 || options.tolerance > 255)
        return Error{"tolerance " + std::to_string(options.tolerance) + " is outside 0..255 (8-bit steps)"};
    if (actual.width != reference.width || actual.height != reference.height)
        return Error{"size differs: actual " + sizeText(actual.width, actual.height) + ", reference " +
                     sizeText(reference.width, reference.height)};
    for (const std::string& problem : {checkLengths(actual, "actual"), checkLengths(reference, "reference")})
        if (!problem.empty()) return Error{problem};
    if (!actual.depth.empty() && !reference.depth.empty() && actual.depthFormat != reference.depthFormat)
        return Error{std::string("depth formats differ: actual ") + depthFormatName(actual.depthFormat) +
                     ", reference " + depthFormatName(reference.depthFormat)};

    const std::size_t n = actual.pixelCount();
    const int tolerance = options.tolerance;
    ImageComparison c;
    c.width = actual.width;
    c.height = actual.height;
    c.tolerance = tolerance;
    c.pixels = n;
    c.mask.width = actual.width;
    c.mask.height = actual.height;
    c.mask.rgba.resize(4 * n);

    const bool ids = !actual.ids.empty() && !reference.ids.empty();
    const bool depth = !actual.depth.empty() && !reference.depth.empty();
    if (ids) {
        c.coverageSource = ImageComparison::CoverageSource::Ids;
        c.idMismatches = 0;
    } else if (options.background) {
        c.coverageSource = ImageComparison::CoverageSource::BackgroundColor;
    }
    if (depth) {
        c.depth = ImageComparison::Depth{};
        c.depth->format = actual.depthFormat;
    }

    const std::uint8_t* bg = options.background ? options.background->data() : nullptr;
    auto isBackgroundColor = [&](const std::uint8_t* p) {
        for (int k = 0; k < 4; ++k)
            if (std::abs(int(p[k]) - int(bg[k])) > tolerance) return false;
        return true;
    };

    double squaredError = 0.0;  // exact in a double up to 2^53 / 255² ≈ 1.4e11 channel values
    std::size_t worstIndex = 0, worstDepthIndex = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint8_t* a = &actual.rgba[4 * i];
        const std::uint8_t* r = &reference.rgba[4 * i];
        int pixelMax = 0;
        for (int k = 0; k < 4; ++k) {
            const int d = std::abs(int(a[k]) - int(r[k]));
            squaredError += double(d * d);
            pixelMax = std::max(pixelMax, d);
        }
        const bool fails = pixelMax > tolerance;
        if (fails) ++c.failingPixels;
        if (pixelMax > c.maxChannelDifference) {
            c.maxChannelDifference = pixelMax;
            worstIndex = i;
        }

        std::uint8_t* m = &c.mask.rgba[4 * i];
        if (fails) {
            m[0] = 255, m[1] = 0, m[2] = 0;
        } else {
            // Rec. 601 luma in 8.8 fixed point: 77 + 150 + 29 = 256, so white stays 255.
            const std::uint8_t grey = std::uint8_t((77 * r[0] + 150 * r[1] + 29 * r[2] + 128) >> 8);
            m[0] = m[1] = m[2] = grey;
        }
        m[3] = 255;

        bool coveredA = true, coveredR = true;
        if (ids) {
            coveredA = actual.ids[i] != 0;
            coveredR = reference.ids[i] != 0;
            if (coveredA && coveredR && actual.ids[i] != reference.ids[i]) ++*c.idMismatches;
        } else if (bg) {
            coveredA = !isBackgroundColor(a);
            coveredR = !isBackgroundColor(r);
        }
        if (coveredA && !coveredR) ++c.coveredOnlyInActual;
        if (!coveredA && coveredR) ++c.coveredOnlyInReference;

        if (depth && coveredA && coveredR) {
            const std::uint32_t da = actual.depth[i], dr = reference.depth[i];
            const std::uint32_t d = da > dr ? da - dr : dr - da;
            ++c.depth->comparedPixels;
            if (d != 0) ++c.depth->differingPixels;
            if (d > c.depth->maxDifference) {
                c.depth->maxDifference = d;
                worstDepthIndex = i;
            }
        }
    }
    if (c.maxChannelDifference > 0) c.worstPixel = imagePosition(worstIndex, c.width, c.height);
    if (depth && c.depth->maxDifference > 0) c.depth->worstPixel = imagePosition(worstDepthIndex, c.width, c.height);
    const double channels = 4.0 * double(n);
    c.psnr = squaredError == 0.0 || n == 0 ? std::numeric_limits<double>::infinity()
                                           : 10.0 * std::log10(255.0 * 255.0 / (squaredError / channels));
    return c;
}

Result<Buffers> buffersFromPng(const DecodedImage& image) {
    if (image.bitDepth != 8)
        return Error{std::to_string(image.bitDepth) + "-bit PNG; colour images are compared as 8-bit"};
    if (image.channels < 1 || image.channels > 4)
        return Error{std::to_string(image.channels) + " channels; expected 1 to 4"};
    Buffers b;
    b.width = image.width;
    b.height = image.height;
    const std::size_t n = b.pixelCount();
    const int channels = image.channels;
    if (image.pixels8.size() != n * std::size_t(channels))
        return Error{"decoded " + std::to_string(image.pixels8.size()) + " bytes for " + sizeText(b.width, b.height) +
                     " with " + std::to_string(channels) + " channels"};
    b.rgba.resize(4 * n);
    for (int y = 0; y < b.height; ++y) {
        // File row y (top first) becomes Buffers row height-1-y (bottom first).
        const std::uint8_t* in = &image.pixels8[std::size_t(y) * b.width * channels];
        std::uint8_t* out = &b.rgba[std::size_t(b.height - 1 - y) * b.width * 4];
        for (int x = 0; x < b.width; ++x, in += channels, out += 4) {
            const bool grey = channels <= 2;
            out[0] = in[0];
            out[1] = grey ? in[0] : in[1];
            out[2] = grey ? in[0] : in[2];
            out[3] = channels == 2 ? in[1] : channels == 4 ? in[3] : 255;
        }
    }
    return b;
}

Result<bool> addIdsFromPng(Buffers& buffers, const DecodedImage& image) {
    if (image.bitDepth != 8 || image.channels != 4)
        return Error{"not a triangle-id image: " + std::to_string(image.bitDepth) + "-bit with " +
                     std::to_string(image.channels) + " channels, expected 8-bit RGBA"};
    if (image.width != buffers.width || image.height != buffers.height)
        return Error{"id image is " + sizeText(image.width, image.height) + " but its colour image is " +
                     sizeText(buffers.width, buffers.height)};
    const std::size_t n = buffers.pixelCount();
    if (image.pixels8.size() != 4 * n)
        return Error{"decoded " + std::to_string(image.pixels8.size()) + " bytes for " +
                     sizeText(image.width, image.height) + " RGBA"};
    buffers.ids.assign(n, 0);
    for (int y = 0; y < buffers.height; ++y) {
        const std::uint8_t* in = &image.pixels8[std::size_t(y) * buffers.width * 4];
        std::uint32_t* out = &buffers.ids[std::size_t(buffers.height - 1 - y) * buffers.width];
        for (int x = 0; x < buffers.width; ++x, in += 4)
            out[x] = std::uint32_t(in[0]) | std::uint32_t(in[1]) << 8 | std::uint32_t(in[2]) << 16 |
                     std::uint32_t(in[3]) << 24;
    }
    return true;
}

Result<Buffers> readRenderPngs(const std::string& colorPath, const std::string& idsPath) {
    Result<DecodedImage> color = readPng(colorPath);
    if (!color) return Error{color.error().message};
    Result<Buffers> buffers = buffersFromPng(*color);
    if (!buffers) return Error{colorPath + ": " + buffers.error().message};
    if (!idsPath.empty()) {
        Result<DecodedImage> ids = readPng(idsPath);
        if (!ids) return Error{ids.error().message};
        Result<bool> added = addIdsFromPng(*buffers, *ids);
        if (!added) return Error{idsPath + ": " + added.error().message};
    }
    return buffers;
}

Result<Bytes> encodeMaskPng(const ImageComparison& comparison) { return encodeColorPng(comparison.mask); }

std::string comparisonJson(const ImageComparison& c) {
    nlohmann::ordered_json coverage = nullptr;
    if (c.coverageSource != ImageComparison::CoverageSource::None) {
        coverage = {{"source", c.coverageSource == ImageComparison::CoverageSource::Ids ? "ids" : "background_colour"},
                    {"mismatches", c.coverageMismatches()},
                    {"covered_only_in_actual", c.coveredOnlyInActual},
                    {"covered_only_in_reference", c.coveredOnlyInReference}};
    }
    nlohmann::ordered_json depth = nullptr;
    if (c.depth) {
        depth = {{"format", depthFormatName(c.depth->format)},
                 {"max_difference_lsb", c.depth->maxDifference},
                 {"differing_pixels", c.depth->differingPixels},
                 {"compared_pixels", c.depth->comparedPixels},
                 {"worst_pixel", positionJson(c.depth->worstPixel)}};
    }
    const nlohmann::ordered_json j = {
        {"size", {c.width, c.height}},
        {"pixels", c.pixels},
        {"tolerance", c.tolerance},
        {"passed", c.passed()},
        {"failing_pixels", c.failingPixels},
        {"failing_fraction", c.pixels ? double(c.failingPixels) / double(c.pixels) : 0.0},
        {"max_channel_difference", c.maxChannelDifference},
        {"worst_pixel", positionJson(c.worstPixel)},
        {"identical", c.identical()},
        // JSON has no infinity: identical images have "psnr_db": null (and "identical": true).
        {"psnr_db", std::isinf(c.psnr) ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(c.psnr)},
        {"coverage", coverage},
        {"id_mismatches", c.idMismatches ? nlohmann::ordered_json(*c.idMismatches) : nlohmann::ordered_json(nullptr)},
        {"depth", depth},
    };
    return j.dump();
}

std::string formatPsnr(double psnr) {
    if (std::isinf(psnr)) return "inf";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f dB", psnr);
    return buf;
}

std::string comparisonSummary(const ImageComparison& c, const std::string& actual, const std::string& reference,
                              const std::string& indent) {
    std::string s;
    s += indent + "pixels beyond tolerance " + std::to_string(c.tolerance) + ": " + std::to_string(c.failingPixels) +
         " of " + std::to_string(c.pixels) + " (" + percent(c.failingPixels, c.pixels) + ")\n";
    s += indent + "largest channel difference: " + std::to_string(c.maxChannelDifference);
    if (c.worstPixel) s += " at (" + std::to_string(c.worstPixel->x) + ", " + std::to_string(c.worstPixel->y) + ")";
    s += "; PSNR " + formatPsnr(c.psnr) + "\n";
    if (c.coverageSource != ImageComparison::CoverageSource::None) {
        s += indent + "coverage mismatches (from " + coverageName(c.coverageSource) +
             "): " + std::to_string(c.coverageMismatches());
        if (c.coverageMismatches())
            s += " (geometry only in " + actual + ": " + std::to_string(c.coveredOnlyInActual) + ", only in " +
                 reference + ": " + std::to_string(c.coveredOnlyInReference) + ")";
        s += "\n";
    }
    if (c.idMismatches) s += indent + "triangle-id mismatches: " + std::to_string(*c.idMismatches) + "\n";
    if (c.depth) {
        s += indent + "depth: largest difference " + std::to_string(c.depth->maxDifference) +
             (c.depth->format == DepthFormat::D32F ? " ULP (32-bit float), " : " LSB (24-bit), ") +
             std::to_string(c.depth->differingPixels) + " of " + std::to_string(c.depth->comparedPixels) +
             " pixels differ";
        if (c.depth->worstPixel)
            s += ", worst at (" + std::to_string(c.depth->worstPixel->x) + ", " +
                 std::to_string(c.depth->worstPixel->y) + ")";
        s += "\n";
    }
    return s;
}

std::size_t differingColorPixels(const Buffers& a, const Buffers& b) {
    std::size_t count = 0;
    for (std::size_t i = 0; i + 3 < a.rgba.size() && i + 3 < b.rgba.size(); i += 4)
        count += std::equal(a.rgba.begin() + std::ptrdiff_t(i), a.rgba.begin() + std::ptrdiff_t(i + 4),
                            b.rgba.begin() + std::ptrdiff_t(i)) ? 0 : 1;
    return count;
}

}  // namespace frugal
