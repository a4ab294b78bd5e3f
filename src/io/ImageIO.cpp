#include "io/ImageIO.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <stb_image.h>
#include <libdeflate.h>

#include <frugal/Files.h>
#include <frugal/Renderer.h>

#include "base/Format.h"
#include "io/Interrupt.h"
#include "io/RunDeflate.h"
#include "scene/ImageCheck.h"

namespace frugal {

namespace {

void put32(std::uint8_t* at, std::uint32_t v) {
    for (int k = 0; k < 4; ++k) at[k] = std::uint8_t(v >> (24 - 8 * k));
}

// Appends a chunk: length, type, data, and the CRC of type and data.
void chunk(Bytes& out, const char type[4], const std::uint8_t* data, std::size_t size) {
    const std::size_t start = out.size();
    out.resize(start + 12 + size);
    put32(&out[start], std::uint32_t(size));
    std::memcpy(&out[start + 4], type, 4);
    if (size > 0) std::memcpy(&out[start + 8], data, size);
    put32(&out[start + 8 + size], std::uint32_t(libdeflate_crc32(0, &out[start + 4], 4 + size)));
}

// One compressor per level and thread, made when first used: a compressor holds up to a few
// megabytes of tables, and one may not be used by two threads at once.
libdeflate_compressor* compressorFor(int level) {
    struct Compressors {
        std::array<libdeflate_compressor*, kMaxPngLevel + 1> byLevel{};
        ~Compressors() {
            for (libdeflate_compressor* c : byLevel)
                if (c != nullptr) libdeflate_free_compressor(c);
        }
    };
    thread_local Compressors compressors;
    libdeflate_compressor*& slot = compressors.byLevel[std::size_t(level)];
    if (slot == nullptr) slot = libdeflate_alloc_compressor(level);
    return slot;
}


// The PNG of `height` rows of `stride` bytes each, already in PNG sample order (16-bit samples
// big-endian); rowOf(y, scratch) gives row y counting from the top, either a pointer into the
// caller's pixels or `scratch` (stride bytes) filled. Two scratch rows alternate, so the row above
// stays readable for the Up filter.
// Each kind of image's level under kAutoPngLevel and its filter at each level, as measured
// (docs/writing.md: `frugal-lab write-bench` on the bunny, the engine and the dominoes at 1080p).
// Up suits colour and depth at every level (a rendered image's rows are alike); ids gain from it
// only at the levels that find few matches (1 to 3): from 4 on, unfiltered ids, whose runs repeat
// along a row, compress better.
enum class Plane : std::uint8_t { Color, Depth, Ids };

PngOptions resolved(Plane plane, const PngOptions& given) {
    PngOptions options = given;
    if (options.level == kAutoPngLevel) options.level = plane == Plane::Color ? 3 : plane == Plane::Depth ? 1 : 6;
    if (!options.filter)
        options.filter = plane == Plane::Ids && options.level >= 4 ? PngFilter::None : PngFilter::Up;
    return options;
}

// PNG's filters (the PNG specification, section 9): each byte minus a prediction from the byte to
// its left (a, `step` bytes back), above (b) and above-left (c), each 0 outside the image. `above`
// is null on the first row.
void filterRow(PngFilter filter, const std::uint8_t* row, const std::uint8_t* above, std::size_t size,
               std::size_t step, std::uint8_t* out) {
    const std::size_t lead = std::min(step, size);
    switch (filter) {
        case PngFilter::None:
            std::memcpy(out, row, size);
            return;
        case PngFilter::Sub:
            std::memcpy(out, row, lead);
            for (std::size_t i = lead; i < size; ++i) out[i] = std::uint8_t(row[i] - row[i - step]);
            return;
        case PngFilter::Up:
            if (above == nullptr) {
                std::memcpy(out, row, size);
            } else {
                for (std::size_t i = 0; i < size; ++i) out[i] = std::uint8_t(row[i] - above[i]);
            }
            return;
        case PngFilter::Paeth:
            for (std::size_t i = 0; i < size; ++i) {
                const int a = i >= step ? row[i - step] : 0, b = above ? above[i] : 0,
                          c = (above && i >= step) ? above[i - step] : 0;
                const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
                const int predicted = (pa <= pb && pa <= pc) ? a : (pb <= pc ? b : c);
                out[i] = std::uint8_t(row[i] - predicted);
            }
            return;
    }
}

// Buffers kept per thread from one image to the next: the filtered rows and the compressor's
// output. A 1080p frame's 8 MB, taken fresh (and zeroed) each time, cost more in page faults than
// the filter itself. Images beyond 64 MB give their memory back.
class ThreadBuffer {
public:
    ThreadBuffer(Bytes& kept, std::size_t size) : kept_(kept), bytes_(std::move(kept)) {
        if (bytes_.size() < size) bytes_.resize(size);  // never shrunk: only grown, and then once
    }
    ~ThreadBuffer() {
        if (bytes_.capacity() <= kKeep) kept_ = std::move(bytes_);
    }
    ThreadBuffer(const ThreadBuffer&) = delete;
    ThreadBuffer& operator=(const ThreadBuffer&) = delete;
    std::uint8_t* data() { return bytes_.data(); }

private:
    static constexpr std::size_t kKeep = std::size_t(64) << 20;
    Bytes& kept_;
    Bytes bytes_;
};
thread_local Bytes tRows, tPacked;

// Appends the zlib stream of `rows` to `out`: the caller's compressor, the run-length encoder
// (level 1: io/RunDeflate.h) or libdeflate's.
Result<bool> compressRows(std::span<const std::uint8_t> rows, std::size_t pixelBytes, const PngOptions& options,
                          Bytes& out) {
    if (options.compress) {
        Result<Bytes> packed = options.compress(rows);
        if (!packed) return packed.error();
        out.insert(out.end(), packed->begin(), packed->end());
        return true;
    }
    if (options.level == kRunLengthPngLevel) {
        ThreadBuffer packed(tPacked, runDeflateBound(rows.size()));
        const std::size_t size = runDeflateZlib(rows, pixelBytes, packed.data());
        out.insert(out.end(), packed.data(), packed.data() + size);
        return true;
    }
    libdeflate_compressor* compressor = compressorFor(options.level);
    if (compressor == nullptr)
        return Error{"PNG encoder: out of memory for libdeflate's level " + std::to_string(options.level) + " tables",
                     ErrorKind::OutOfMemory};
    const std::size_t bound = libdeflate_zlib_compress_bound(compressor, rows.size());
    ThreadBuffer packed(tPacked, bound);
    const std::size_t size = libdeflate_zlib_compress(compressor, rows.data(), rows.size(), packed.data(), bound);
    if (size == 0)  // cannot happen with a buffer of the bound's size
        return Error{"PNG encoder: libdeflate could not compress " + std::to_string(rows.size()) + " bytes"};
    out.insert(out.end(), packed.data(), packed.data() + size);
    return true;
}

// `gamma`: a gAMA chunk's value (100000 = 1.0: linear light) when not 0.
template <class RowOf>
Result<Bytes> encodeRows(int width, int height, int channels, int bitDepth, PngFilter filter, const PngOptions& options,
                         const PngText& text, RowOf rowOf, std::uint32_t gamma = 0) {
    const int level = options.level;
    if (channels < 1 || channels > 4) return Error{"PNG encoder: channels must be 1 to 4, got " + std::to_string(channels)};
    if (bitDepth != 8 && bitDepth != 16) return Error{"PNG encoder: bit depth must be 8 or 16, got " + std::to_string(bitDepth)};
    if (width < 1 || height < 1)
        return Error{"PNG encoder: width and height must be at least 1, got " + std::to_string(width) + "x" +
                     std::to_string(height)};
    if (level < 0 || level > kMaxPngLevel)
        return Error{"PNG encoder: the level must be 0 to " + std::to_string(kMaxPngLevel) + " (or -1: auto), got " +
                     std::to_string(level)};
    for (const auto& [keyword, value] : text) {
        const bool printable = std::all_of(keyword.begin(), keyword.end(), [](char c) { return c >= 32 && c <= 126; });
        if (keyword.empty() || keyword.size() > 79 || !printable || keyword.front() == ' ' || keyword.back() == ' ')
            return Error{"PNG encoder: a tEXt keyword is 1 to 79 printable characters, got '" + keyword + "'"};
    }
    const std::size_t pixelBytes = std::size_t(channels) * std::size_t(bitDepth / 8);
    const std::size_t stride = std::size_t(width) * pixelBytes;
    const std::size_t rawSize = (stride + 1) * std::size_t(height);
    ThreadBuffer raw(tRows, rawSize);
    std::vector<std::uint8_t> scratch(2 * stride);
    const std::uint8_t* above = nullptr;
    for (int y = 0; y < height; ++y) {
        std::uint8_t* out = raw.data() + (stride + 1) * std::size_t(y);
        const std::uint8_t* row = rowOf(y, &scratch[stride * std::size_t(y & 1)]);
        out[0] = std::uint8_t(filter);
        filterRow(filter, row, above, stride, pixelBytes, out + 1);
        above = row;
    }

    static const std::uint8_t kColorType[5] = {0, 0, 4, 2, 6};  // by channels: grey, grey+alpha, RGB, RGBA
    Bytes out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    std::uint8_t header[13];
    put32(header, std::uint32_t(width));
    put32(header + 4, std::uint32_t(height));
    header[8] = std::uint8_t(bitDepth);
    header[9] = kColorType[channels];
    header[10] = 0;  // deflate
    header[11] = 0;  // adaptive filtering (a filter type per row)
    header[12] = 0;  // no interlace
    chunk(out, "IHDR", header, sizeof header);
    if (gamma != 0) {
        std::uint8_t value[4];
        put32(value, gamma);
        chunk(out, "gAMA", value, sizeof value);
    }
    for (const auto& [keyword, value] : text) {
        Bytes data(keyword.begin(), keyword.end());
        data.push_back(0);
        data.insert(data.end(), value.begin(), value.end());
        chunk(out, "tEXt", data.data(), data.size());
    }
    // The zlib stream goes straight into the file's bytes, after room for the IDAT chunk's length
    // and type; a stream over 1 GiB (a huge image at level 0) is cut into several chunks.
    const std::size_t idat = out.size();
    out.resize(idat + 8);
    if (Result<bool> packed = compressRows({raw.data(), rawSize}, pixelBytes, options, out); !packed) return packed.error();
    const std::size_t packedSize = out.size() - idat - 8;
    constexpr std::size_t kMaxIdat = std::size_t(1) << 30;  // a chunk holds at most 2^31 - 1 bytes
    if (packedSize <= kMaxIdat) {
        put32(&out[idat], std::uint32_t(packedSize));
        std::memcpy(&out[idat + 4], "IDAT", 4);
        const std::uint32_t crc = std::uint32_t(libdeflate_crc32(0, &out[idat + 4], 4 + packedSize));
        out.resize(out.size() + 4);
        put32(&out[out.size() - 4], crc);
    } else {
        const Bytes packed(out.begin() + std::ptrdiff_t(idat + 8), out.end());
        out.resize(idat);
        for (std::size_t at = 0; at < packedSize; at += kMaxIdat)
            chunk(out, "IDAT", packed.data() + at, std::min(kMaxIdat, packedSize - at));
    }
    chunk(out, "IEND", nullptr, 0);
    return out;
}

}  // namespace

std::vector<std::uint8_t> flipRows(const std::uint8_t* rows, int width, int height, int bytesPerPixel) {
    const std::size_t stride = std::size_t(width) * bytesPerPixel;
    std::vector<std::uint8_t> out(stride * height);
    for (int y = 0; y < height; ++y) std::memcpy(&out[stride * (height - 1 - y)], rows + stride * y, stride);
    return out;
}

Result<Bytes> encodePng(int width, int height, int channels, int bitDepth, const void* rowsTopFirst,
                        const PngText& text, const PngOptions& options) {
    const auto* pixels = static_cast<const std::uint8_t*>(rowsTopFirst);
    const std::size_t stride = std::size_t(std::max(width, 0)) * std::size_t(std::clamp(channels, 0, 4)) * 2;
    const PngOptions resolvedOptions = resolved(Plane::Color, options);
    return encodeRows(width, height, channels, bitDepth, *resolvedOptions.filter, resolvedOptions, text,
                      [&](int y, std::uint8_t* scratch) -> const std::uint8_t* {
                          const std::size_t rowBytes = bitDepth == 8 ? stride / 2 : stride;
                          const std::uint8_t* in = pixels + rowBytes * std::size_t(y);
                          if (bitDepth == 8) return in;
                          for (std::size_t i = 0; i < rowBytes; i += 2) {  // host order to big-endian
                              std::uint16_t v;
                              std::memcpy(&v, in + i, 2);
                              scratch[i] = std::uint8_t(v >> 8);
                              scratch[i + 1] = std::uint8_t(v & 0xFF);
                          }
                          return scratch;
                      });
}

namespace {

// The encoders on one plane each (rows bottom-up, as the buffers hold them), for Buffers and for
// the images alike, at the level and filter resolved() gives.
Result<Bytes> colorPng(int width, int height, const std::uint8_t* rgba, const PngOptions& given) {
    const std::size_t stride = std::size_t(width) * 4;
    const PngOptions options = resolved(Plane::Color, given);
    return encodeRows(width, height, 4, 8, *options.filter, options, {}, [&](int y, std::uint8_t*) {
        return rgba + stride * std::size_t(height - 1 - y);
    });
}

Result<Bytes> depthPng(int width, int height, const std::uint32_t* values, DepthFormat format,
                       const std::optional<DepthInfo>& info, const PngOptions& given) {
    const PngOptions options = resolved(Plane::Depth, given);
    PngText text;
    const bool reversed = format == DepthFormat::D32F;
    if (info) {
        const auto number = [](float v) {
            char s[32];
            std::snprintf(s, sizeof s, "%.9g", double(v));
            return std::string(s);
        };
        text = {
            {"depth_format", depthFormatName(format)},
            {"depth_znear", number(info->znear)},
            {"depth_zfar", info->zfar > 0.0f ? number(info->zfar) : std::string("inf")},
            {"depth_projection", info->perspective ? "perspective" : "orthographic"},
            {"depth_encoding", reversed ? "(1 - window z) * 65535, rounded: 0 near, 65535 far (window z 1 near, 0 far)"
                                        : "the top 16 bits of the 24-bit window z: 0 near, 65535 far"}};
    }
    return encodeRows(width, height, 1, 16, *options.filter, options, text, [&](int y, std::uint8_t* scratch) {
        const std::uint32_t* in = values + std::size_t(width) * std::size_t(height - 1 - y);
        for (int x = 0; x < width; ++x) {
            const std::uint16_t v = reversed
                                        ? std::uint16_t(std::lround((1.0 - double(windowDepth(format, in[x]))) * 65535.0))
                                        : std::uint16_t(in[x] >> 8);
            scratch[2 * x] = std::uint8_t(v >> 8);
            scratch[2 * x + 1] = std::uint8_t(v & 0xFF);
        }
        return static_cast<const std::uint8_t*>(scratch);
    });
}

// PFM: "Pf" (one channel) or "PF" (rgb), float32, little-endian (scale −1), rows bottom-up as PFM
// stores them already; value(i, c) is channel c of pixel i.
template <class Value>
Bytes pfm(int width, int height, int channels, Value value) {
    const std::string header = std::string(channels == 1 ? "Pf\n" : "PF\n") + std::to_string(width) + " " +
                               std::to_string(height) + "\n-1.0\n";
    const std::size_t pixels = std::size_t(width) * std::size_t(height), values = std::size_t(channels);
    Bytes out(header.begin(), header.end());
    const std::size_t start = out.size();
    out.resize(start + pixels * values * 4);
    for (std::size_t i = 0; i < pixels; ++i)
        for (std::size_t c = 0; c < values; ++c) {
            const float v = value(i, c);
            std::memcpy(out.data() + start + (i * values + c) * 4, &v, 4);
        }
    return out;
}

// Depth as window z; linear colour as its rgb (alpha left out).
Bytes depthPfm(int width, int height, const std::uint32_t* values, DepthFormat format) {
    return pfm(width, height, 1, [&](std::size_t i, std::size_t) { return windowDepth(format, values[i]); });
}
Bytes linearPfm(int width, int height, const float* rgba) {
    return pfm(width, height, 3, [&](std::size_t i, std::size_t c) { return rgba[i * 4 + c]; });
}

// The same as 16-bit RGBA PNG: each channel clamped to [0, 1] and rounded to 65535 steps, with a
// gAMA chunk of 1.0 so that a viewer knows the values are linear.
Result<Bytes> linearPng(int width, int height, const float* rgba, const PngOptions& given) {
    const PngOptions options = resolved(Plane::Color, given);
    const PngText text = {{"color_encoding", "linear light, each channel clamped to [0, 1] in 65535 steps"}};
    return encodeRows(
        width, height, 4, 16, *options.filter, options, text,
        [&](int y, std::uint8_t* scratch) {
            const float* in = rgba + std::size_t(width) * 4 * std::size_t(height - 1 - y);
            for (std::size_t i = 0; i < std::size_t(width) * 4; ++i) {
                const float v = in[i];
                const auto level = std::uint16_t(!(v > 0.0f) ? 0.0
                                                 : v >= 1.0f ? 65535.0
                                                             : std::nearbyint(double(v) * 65535.0));
                scratch[2 * i] = std::uint8_t(level >> 8);
                scratch[2 * i + 1] = std::uint8_t(level & 0xFF);
            }
            return static_cast<const std::uint8_t*>(scratch);
        },
        100000u);
}

Result<Bytes> idPng(int width, int height, const std::uint32_t* ids, const PngOptions& given) {
    const PngOptions options = resolved(Plane::Ids, given);
    return encodeRows(width, height, 4, 8, *options.filter, options, {}, [&](int y, std::uint8_t* scratch) {
        const std::uint32_t* in = ids + std::size_t(width) * std::size_t(height - 1 - y);
        if constexpr (std::endian::native == std::endian::little) {
            return reinterpret_cast<const std::uint8_t*>(in);  // the bytes are the id, little-endian already
        } else {
            for (int x = 0; x < width; ++x)
                for (int k = 0; k < 4; ++k) scratch[4 * x + k] = std::uint8_t(in[x] >> (8 * k));
            return static_cast<const std::uint8_t*>(scratch);
        }
    });
}

}  // namespace

namespace {

// An image whose vector does not hold its width x height values (a caller's mistake, or a plane
// not read back): an error instead of a read past its end.
std::optional<Error> sizeProblem(const char* what, int width, int height, std::size_t values, std::size_t perPixel) {
    if (width <= 0 || height <= 0) return std::nullopt;  // the encoder's own error
    const std::size_t needed = std::size_t(width) * std::size_t(height) * perPixel;
    if (values == needed) return std::nullopt;
    return Error{std::string("PNG encoder: the ") + what + " image holds " + std::to_string(values) + " values, " +
                 std::to_string(width) + "x" + std::to_string(height) + " needs " + std::to_string(needed)};
}

}  // namespace

Result<Bytes> encodeColorPng(const Buffers& b, const PngOptions& options) {
    if (std::optional<Error> problem = sizeProblem("colour", b.width, b.height, b.rgba.size(), 4)) return *problem;
    return colorPng(b.width, b.height, b.rgba.data(), options);
}
Result<Bytes> encodeDepthPng(const Buffers& b, const std::optional<DepthInfo>& info, const PngOptions& options) {
    if (std::optional<Error> problem = sizeProblem("depth", b.width, b.height, b.depth.size(), 1)) return *problem;
    return depthPng(b.width, b.height, b.depth.data(), b.depthFormat, info, options);
}
Bytes encodeDepthPfm(const Buffers& b) { return depthPfm(b.width, b.height, b.depth.data(), b.depthFormat); }
Result<Bytes> encodeIdPng(const Buffers& b, const PngOptions& options) {
    if (std::optional<Error> problem = sizeProblem("id", b.width, b.height, b.ids.size(), 1)) return *problem;
    return idPng(b.width, b.height, b.ids.data(), options);
}

Result<Bytes> encodeColorPng(const ColorImage& image, const PngOptions& options) {
    if (std::optional<Error> problem = sizeProblem("colour", image.width, image.height, image.rgba.size(), 4))
        return *problem;
    return colorPng(image.width, image.height, image.rgba.data(), options);
}
Result<Bytes> encodeDepthPng(const DepthImage& image, const PngOptions& options) {
    if (std::optional<Error> problem = sizeProblem("depth", image.width, image.height, image.values.size(), 1))
        return *problem;
    return depthPng(image.width, image.height, image.values.data(), image.format,
                    DepthInfo{image.znear, image.zfar, image.perspective}, options);
}
Result<Bytes> encodeDepthPfm(const DepthImage& image) {
    if (std::optional<Error> problem = sizeProblem("depth", image.width, image.height, image.values.size(), 1))
        return Error{"PFM encoder: " + problem->message.substr(std::string("PNG encoder: ").size())};
    return depthPfm(image.width, image.height, image.values.data(), image.format);
}
Result<Bytes> encodeIdPng(const IdImage& image, const PngOptions& options) {
    if (std::optional<Error> problem = sizeProblem("id", image.width, image.height, image.ids.size(), 1))
        return *problem;
    return idPng(image.width, image.height, image.ids.data(), options);
}

Result<Bytes> encodeLinearPfm(const LinearImage& image) {
    if (std::optional<Error> problem = sizeProblem("linear colour", image.width, image.height, image.rgba.size(), 4))
        return Error{"PFM encoder: " + problem->message.substr(std::string("PNG encoder: ").size())};
    return linearPfm(image.width, image.height, image.rgba.data());
}
Result<Bytes> encodeLinearPng(const LinearImage& image, const PngOptions& options) {
    if (std::optional<Error> problem = sizeProblem("linear colour", image.width, image.height, image.rgba.size(), 4))
        return *problem;
    return linearPng(image.width, image.height, image.rgba.data(), options);
}

bool hasExtension(const std::string& path, const std::string& extension) {
    std::string e = std::filesystem::path(path).extension().string();
    for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e == extension;
}

std::string linearPathProblem(const std::string& path) {
    if (hasExtension(path, ".pfm") || hasExtension(path, ".png")) return {};
    return "name it .pfm (float32) or .png (16-bit)";
}

Result<bool> writePng(const std::string& path, const ColorImage& image, int level) {
    return writeFileAtomic(path, encodeColorPng(image, PngOptions::atLevel(level)));
}
Result<bool> writePng(const std::string& path, const DepthImage& image, int level) {
    return writeFileAtomic(path, encodeDepthPng(image, PngOptions::atLevel(level)));
}
Result<bool> writePfm(const std::string& path, const DepthImage& image) {
    return writeFileAtomic(path, Result<Content>(encodeDepthPfm(image)));
}
Result<bool> writePfm(const std::string& path, const LinearImage& image) {
    return writeFileAtomic(path, Result<Content>(encodeLinearPfm(image)));
}
Result<bool> writePng(const std::string& path, const LinearImage& image, int level) {
    return writeFileAtomic(path, encodeLinearPng(image, PngOptions::atLevel(level)));
}
Result<bool> writePng(const std::string& path, const IdImage& image, int level) {
    return writeFileAtomic(path, encodeIdPng(image, PngOptions::atLevel(level)));
}

namespace {

// Writes all of `content` to `fd` and closes it: "" or why not, with how far it got.
std::string writeAndClose(int fd, const Content& content) {
    std::uint64_t done = 0;
    const std::uint64_t total = content.size();
    const auto failed = [&](int error) {
        ::close(fd);
        return "write failed after " + std::to_string(done) + " of " + std::to_string(total) +
               " bytes: " + std::strerror(error);
    };
    const auto put = [&](const std::uint8_t* data, std::size_t size) -> std::string {
        std::size_t at = 0;
        while (at < size) {
            // At most 1 GiB a call: Linux writes at most 0x7ffff000 bytes at once anyway.
            const std::size_t chunk = std::min<std::size_t>(size - at, std::size_t(1) << 30);
            const ssize_t n = ::write(fd, data + at, chunk);
            if (n > 0) {
                at += std::size_t(n);
                done += std::uint64_t(n);
            } else if (!(n < 0 && errno == EINTR)) {
                return failed(n < 0 ? errno : EIO);
            }
        }
        return {};
    };
    if (std::string why = put(content.head.data(), content.head.size()); !why.empty()) return why;
    if (content.body) {
        // The body in pieces of 1 MiB, read from its start.
        std::vector<std::uint8_t> piece(std::size_t(1) << 20);
        for (std::uint64_t offset = 0; offset < content.body->size();) {
            const ssize_t n = ::pread(content.body->fd(), piece.data(),
                                      std::size_t(std::min<std::uint64_t>(piece.size(), content.body->size() - offset)),
                                      off_t(offset));
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) return failed(n < 0 ? errno : EIO);
            if (std::string why = put(piece.data(), std::size_t(n)); !why.empty()) return why;
            offset += std::uint64_t(n);
        }
    }
    if (std::string why = put(content.tail.data(), content.tail.size()); !why.empty()) return why;
    if (::close(fd) != 0) {  // where a file system reports a full disk late (NFS)
        const int error = errno;
        return "write failed when closing after " + std::to_string(total) + " bytes: " + std::strerror(error);
    }
    return {};
}

// Where `path` is replaced by a renamed file: `path` itself, or, when it is a link, the file the link
// leads to, so that the link stays (/dev/stdout when stdout is a file: /proc/self/fd/1 there).
// Nothing when `path` is, or leads to, a device or a pipe (/dev/null, /dev/full, a terminal, a
// FIFO): that is written in place, since renaming a file over it would replace the device node.
std::optional<std::string> replacedPath(const std::string& path) {
    struct stat status {};
    if (::stat(path.c_str(), &status) == 0 && !S_ISREG(status.st_mode) && !S_ISDIR(status.st_mode)) return std::nullopt;
    // Link by link (a dangling link's file is made where it points), at most as many as the kernel follows.
    std::filesystem::path target = path;
    for (int hop = 0; hop < 40 && ::lstat(target.c_str(), &status) == 0 && S_ISLNK(status.st_mode); ++hop) {
        std::error_code error;
        const std::filesystem::path next = std::filesystem::read_symlink(target, error);
        if (error) break;
        target = next.is_absolute() ? next : target.parent_path() / next;
    }
    return target.string();
}

Result<bool> writeInPlace(const std::string& path, const Content& bytes) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    if (fd < 0) return Error{path + ": cannot write: " + std::strerror(errno), ErrorKind::Io};
    if (std::string why = writeAndClose(fd, bytes); !why.empty()) return Error{path + ": " + why, ErrorKind::Io};
    return true;
}

// Writes `bytes` to a new file beside `target`, named in `temp` before it is created (the caller
// removes it); errors name `path`. O_EXCL: no other writer, in this process or another (even one
// with the same pid in another pid namespace), can share the file, and no link planted at that name
// is followed.
Result<bool> writeTemporary(const std::string& path, const std::string& target, const Content& bytes,
                            std::string& temp) {
    const std::string base = target + ".tmp-" + std::to_string(::getpid());
    constexpr int kNames = 100;
    for (int attempt = 0; attempt < kNames; ++attempt) {
        temp = attempt == 0 ? base : base + "-" + std::to_string(attempt);
        const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0) {
            const int error = errno;
            temp.clear();  // not ours to remove
            if (error == EEXIST) continue;
            return Error{path + ": cannot write: " + std::strerror(error), ErrorKind::Io};
        }
        if (std::string why = writeAndClose(fd, bytes); !why.empty()) return Error{path + ": " + why, ErrorKind::Io};
        return true;
    }
    return Error{
        path + ": cannot write: " + std::to_string(kNames) + " temporary names beside it are taken (" + base + ", ...)",
        ErrorKind::Io};
}

}  // namespace

std::optional<std::string> readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

Result<bool> writeFileAtomic(const std::string& path, Result<Content> bytes) {
    OutputSet set;
    set.add(path, std::move(bytes));
    return set.commit();
}

Result<bool> writeFile(const std::string& path, std::string_view bytes) {
    return writeFileAtomic(path, Bytes(bytes.begin(), bytes.end()));
}

void FileSet::add(std::string path, Result<std::vector<std::uint8_t>> bytes) {
    files_.emplace_back(std::move(path), std::move(bytes));
}

void FileSet::add(std::string path, std::string_view text) {
    files_.emplace_back(std::move(path), std::vector<std::uint8_t>(text.begin(), text.end()));
}

Result<bool> FileSet::commit() {
    OutputSet set;
    for (auto& [path, bytes] : files_)
        set.add(path, bytes ? Result<Content>(Content(std::move(*bytes))) : Result<Content>(bytes.error()));
    files_.clear();
    return set.commit();
}

void OutputSet::add(std::string path, Result<Content> content) {
    files_.emplace_back(std::move(path), std::move(content));
}

Result<bool> OutputSet::commit() {
    for (const auto& [path, bytes] : files_)
        if (!bytes) return Error{path + ": cannot encode: " + bytes.error().message, bytes.error().kind};

    // Devices and pipes first: what they took cannot be taken back.
    struct Replaced {
        std::size_t file;    // index into files_
        std::string target;  // replacedPath
    };
    std::vector<Replaced> replaced;
    for (std::size_t i = 0; i < files_.size(); ++i) {
        if (std::optional<std::string> target = replacedPath(files_[i].first))
            replaced.push_back({i, std::move(*target)});
        else if (Result<bool> written = writeInPlace(files_[i].first, *files_[i].second); !written) return written;
    }

    // From the first temporary file to the last rename no signal is handled (io/Interrupt.h), and
    // however this returns (an error, an exception), the temporary and backup files it still holds
    // are removed.
    const SignalsHeld held;
    const WriteWindow window;
    if (!window.open())
        return Error{files_[replaced.front().file].first + ": not written: the process is ending by a signal",
                     ErrorKind::Interrupted};
    struct Scratch {
        std::vector<std::string> temps, backups;  // by position in `replaced`; "" when there is none
        ~Scratch() {
            for (const std::vector<std::string>* names : {&temps, &backups})
                for (const std::string& name : *names)
                    if (!name.empty()) ::unlink(name.c_str());
        }
    } scratch;
    scratch.temps.resize(replaced.size());
    scratch.backups.resize(replaced.size());
    for (std::size_t k = 0; k < replaced.size(); ++k) {
        const auto& [path, bytes] = files_[replaced[k].file];
        if (Result<bool> written = writeTemporary(path, replaced[k].target, *bytes, scratch.temps[k]); !written)
            return written;
    }

    // Before a file is replaced its old contents get a second name (a hard link: the file itself
    // never disappears), so a later failed rename can put them back. link() fails with ENOENT when
    // another process renames a file over the name meanwhile: then the newer file is the one kept.
    for (std::size_t k = 0; k < replaced.size(); ++k) {
        const std::string& target = replaced[k].target;
        std::string backup = target + ".old-" + std::to_string(::getpid());
        ::unlink(backup.c_str());
        for (int attempt = 0;; ++attempt) {
            struct stat status {};
            if (::lstat(target.c_str(), &status) != 0 || S_ISDIR(status.st_mode)) break;  // nothing to keep
            if (::link(target.c_str(), backup.c_str()) == 0) {
                scratch.backups[k] = std::move(backup);
                break;
            }
            const int error = errno;
            if (error != ENOENT || attempt == 100)
                return Error{files_[replaced[k].file].first +
                                 ": cannot keep the old file while replacing it: " + std::strerror(error),
                             ErrorKind::Io};
        }
    }
    for (std::size_t k = 0; k < replaced.size(); ++k) {
        if (std::rename(scratch.temps[k].c_str(), replaced[k].target.c_str()) == 0) {
            scratch.temps[k].clear();
            continue;
        }
        const int error = errno;
        for (std::size_t j = 0; j < k; ++j) {  // take back what was renamed
            const std::string& earlier = replaced[j].target;
            if (scratch.backups[j].empty()) ::unlink(earlier.c_str());
            else if (std::rename(scratch.backups[j].c_str(), earlier.c_str()) == 0) scratch.backups[j].clear();
        }
        return Error{
            files_[replaced[k].file].first + ": cannot rename the finished file into place: " + std::strerror(error),
            ErrorKind::Io};
    }
    files_.clear();
    return true;
}

namespace {

// stb_image's reason for a failure, for a one-line message. It can quote the file's bytes (an unknown
// chunk's type), which can be control characters or a NUL that ends the text at once.
std::string stbReason() {
    const char* reason = stbi_failure_reason();
    const std::string text = reason ? oneLine(reason) : std::string();
    return text.empty() ? "corrupt data (stb_image gives no readable reason)" : text;
}

}  // namespace

Result<DecodedImage> readPng(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return Error{path + ": cannot open", ErrorKind::Io};
    const std::vector<std::uint8_t> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return decodePng(data, path);
}

Result<DecodedImage> decodePng(std::span<const std::uint8_t> data, const std::string& path) {
    DecodedImage image;
    if (data.size() > std::size_t(INT32_MAX)) return Error{path + ": file too large"};
    const int size = int(data.size());
    int w = 0, h = 0, n = 0;
    if (const Result<ImageSize> checked = checkPng(data); !checked) return Error{path + ": " + checked.error().message};
    if (!stbi_info_from_memory(data.data(), size, &w, &h, &n))
        return Error{path + ": not a PNG: " + stbReason()};
    image.width = w;
    image.height = h;
    image.channels = n;
    if (stbi_is_16_bit_from_memory(data.data(), size)) {
        image.bitDepth = 16;
        stbi_us* pixels = stbi_load_16_from_memory(data.data(), size, &w, &h, &n, 0);
        if (!pixels) return Error{path + ": cannot decode: " + stbReason()};
        image.pixels16.assign(pixels, pixels + std::size_t(w) * h * n);
        stbi_image_free(pixels);
    } else {
        stbi_uc* pixels = stbi_load_from_memory(data.data(), size, &w, &h, &n, 0);
        if (!pixels) return Error{path + ": cannot decode: " + stbReason()};
        image.pixels8.assign(pixels, pixels + std::size_t(w) * h * n);
        stbi_image_free(pixels);
    }
    return image;
}

Result<Spool> Spool::create(const std::string& near) {
    std::string folder = std::filesystem::path(near).parent_path().string();
    if (folder.empty()) folder = ".";
    int fd = ::open(folder.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
    if (fd < 0) {  // a file system or a folder without O_TMPFILE: the system's temporary folder
        if (FILE* file = std::tmpfile()) {
            fd = ::dup(::fileno(file));
            std::fclose(file);
        }
    }
    if (fd < 0) return Error{near + ": cannot keep a temporary file: " + std::strerror(errno), ErrorKind::Io};
    return Spool(fd, near);
}

Spool::Spool(Spool&& other) noexcept : fd_(other.fd_), near_(std::move(other.near_)), size_(other.size_) {
    other.fd_ = -1;
}
Spool& Spool::operator=(Spool&& other) noexcept {
    if (this != &other) {
        if (fd_ >= 0) ::close(fd_);
        fd_ = other.fd_;
        near_ = std::move(other.near_);
        size_ = other.size_;
        other.fd_ = -1;
    }
    return *this;
}
Spool::~Spool() {
    if (fd_ >= 0) ::close(fd_);
}

Result<bool> Spool::append(std::string_view bytes) {
    std::size_t at = 0;
    while (at < bytes.size()) {
        const ssize_t n = ::pwrite(fd_, bytes.data() + at, bytes.size() - at, off_t(size_ + at));
        if (n > 0) {
            at += std::size_t(n);
        } else if (!(n < 0 && errno == EINTR)) {
            const int error = n < 0 ? errno : EIO;
            return Error{near_ + ": write failed after " + std::to_string(size_ + at) +
                             " bytes of its temporary file: " + std::strerror(error),
                         ErrorKind::Io};
        }
    }
    size_ += bytes.size();
    return true;
}

}  // namespace frugal
