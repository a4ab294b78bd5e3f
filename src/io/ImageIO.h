// Image files. Buffers hold rows bottom-up (GL window origin); every encoder here flips once, so
// files are top row first as every viewer expects.
//
// - colour: 8-bit RGBA PNG;
// - depth: 16-bit greyscale PNG, 0 near and 65535 far (D24: the top 16 bits of the 24-bit value;
//   D32F: (1 − window z) · 65535 rounded, its window z being reversed), with what it was drawn with
//   in tEXt chunks (DepthInfo); or PFM (portable float map, window z as float32) for the exact values:
//   D24's value / 16777215, D32F's stored float (reversed: 1 near, 0 far). PFM has no room for text:
//   the render JSON says which planes and format a sequence used;
// - triangle ids: 8-bit RGBA PNG whose bytes are the 32-bit id, little-endian (R = bits 0-7,
//   G = 8-15, B = 16-23, A = 24-31); 0 is the background.
// Files are written atomically: to a temporary file in the same folder, then renamed, so an
// interrupted run never leaves a half-written image (io/Interrupt.h: no signal is handled meanwhile).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <frugal/Files.h>
#include <frugal/Image.h>
#include <frugal/Result.h>

#include "pipeline/Buffers.h"

namespace frugal {

using Bytes = std::vector<std::uint8_t>;

// A PNG tEXt chunk: keyword (1–79 printable Latin-1 characters) and text.
using PngText = std::vector<std::pair<std::string, std::string>>;

// PNG's row filters (the specification's section 9): each byte stored as its difference from a
// prediction. Each kind of image has the filter measured best for it at each level
// (docs/writing.md): Up for colour and depth, for ids Up at levels 1 to 3 and None from 4.
enum class PngFilter : std::uint8_t { None = 0, Sub = 1, Up = 2, Paeth = 4 };

// How a PNG is compressed: the level (frugal/Files.h: kAutoPngLevel, 0 stored, 1 run-length, 2-12
// libdeflate) and, when given, a filter other than the one measured best for the image's kind.
struct PngOptions {
    int level = kDefaultPngLevel;
    std::optional<PngFilter> filter;
    // When given, makes the zlib stream of the filtered rows instead of libdeflate (`level` unread):
    // the lab's baseline, the zlib encoder frugal had before (lab/WriteBench.h).
    std::function<Result<Bytes>(std::span<const std::uint8_t> rows)> compress;

    static PngOptions atLevel(int level) {
        PngOptions options;
        options.level = level;
        return options;
    }
};

// PNG encoder. `channels` 1..4, `bitDepth` 8 or 16 (16-bit samples given as uint16 in host order),
// rows given top row first, 1 to 2^31 − 1 pixels a side (the PNG limit), `text` as tEXt chunks
// after the header; compressed as a colour image (auto: level 3, filter Up) unless `options` says
// otherwise. Errors: "PNG encoder: <what>,
// got <value>" for a format PNG cannot hold, a keyword PNG does not allow or a level out of range.
Result<Bytes> encodePng(int width, int height, int channels, int bitDepth, const void* rowsTopFirst,
                        const PngText& text = {}, const PngOptions& options = {});

// How a depth image was drawn: its format, planes (zfar 0 = infinite) and projection. A depth PNG
// carries them as the tEXt chunks depth_format ("d24", "d32f"), depth_znear, depth_zfar ("inf" when
// infinite), depth_projection ("perspective", "orthographic") and depth_encoding (the line above).
struct DepthInfo {
    float znear = 0.0f, zfar = 0.0f;
    bool perspective = true;
};

// Whether `path` ends in `extension` (".png"), in any case.

Result<Bytes> encodeColorPng(const Buffers& buffers, const PngOptions& options = {});
Result<Bytes> encodeDepthPng(const Buffers& buffers, const std::optional<DepthInfo>& info = std::nullopt,
                             const PngOptions& options = {});
Bytes encodeDepthPfm(const Buffers& buffers);
Result<Bytes> encodeIdPng(const Buffers& buffers, const PngOptions& options = {});
// The same for one image each (a depth PNG with the image's planes as its text).
Result<Bytes> encodeColorPng(const ColorImage& image, const PngOptions& options = {});
Result<Bytes> encodeDepthPng(const DepthImage& image, const PngOptions& options = {});
Result<Bytes> encodeDepthPfm(const DepthImage& image);  // an error when its values do not fill it
Result<Bytes> encodeIdPng(const IdImage& image, const PngOptions& options = {});
// A linear colour image (Settings::linear): PFM "PF", its rgb as float32, exact (alpha left out); or
// 16-bit RGBA PNG, each channel clamped to [0, 1] and rounded to 65535 steps, with gAMA 1.0.
Result<Bytes> encodeLinearPfm(const LinearImage& image);
Result<Bytes> encodeLinearPng(const LinearImage& image, const PngOptions& options = {});

// A file's bytes held outside memory while a long run writes them piece by piece (the frames of a
// render JSON): an anonymous file in the folder of `near` (O_TMPFILE: no name, gone when the process
// ends, however it ends), or in the system's temporary folder where that is not possible.
class Spool {
public:
    // Error (Io): "<near>: cannot keep a temporary file: <why>".
    static Result<Spool> create(const std::string& near);
    Spool(Spool&& other) noexcept;
    Spool& operator=(Spool&& other) noexcept;
    Spool(const Spool&) = delete;
    Spool& operator=(const Spool&) = delete;
    ~Spool();

    // Appends; error (Io): "<near>: <why, with the bytes written>".
    Result<bool> append(std::string_view bytes);
    std::uint64_t size() const { return size_; }
    int fd() const { return fd_; }

private:
    Spool(int fd, std::string near) : fd_(fd), near_(std::move(near)) {}
    int fd_ = -1;
    std::string near_;
    std::uint64_t size_ = 0;
};

// What a file is made of: `head`, then the whole of `body` when given (read in pieces, never all
// in memory), then `tail`.
struct Content {
    Bytes head;
    const Spool* body = nullptr;
    Bytes tail;
    Content(Bytes bytes = {}) : head(std::move(bytes)) {}  // NOLINT: implicit, a file of bytes
    Content(Bytes head_, const Spool& body_, Bytes tail_)
        : head(std::move(head_)), body(&body_), tail(std::move(tail_)) {}
    std::uint64_t size() const { return head.size() + (body ? body->size() : 0) + tail.size(); }
};


// Writes `bytes` to `path` atomically. Error: "<path>: <why>" (also when `bytes` is an encoder's
// error: then nothing is written), e.g. "out.png: write failed after 4096 of 9120 bytes: File too
// large", "/sys/x.png: cannot write: Permission denied".
Result<bool> writeFileAtomic(const std::string& path, Result<Content> bytes);
inline Result<bool> writeFileAtomic(const std::string& path, Bytes bytes) {
    return writeFileAtomic(path, Result<Content>(Content(std::move(bytes))));
}

// Several files that appear together or not at all. commit() writes each to a temporary name in
// its folder ("<path>.tmp-<pid>", created exclusively, so two processes writing into one folder,
// even the same file, never share one: the last rename wins, each file whole); only when every
// write succeeded are they renamed into place, and if a rename fails, the files already renamed are
// taken back: a file that existed before gets its old contents back, a new one is removed. A file
// given as an encoder's error fails the commit before anything is written. SIGINT, SIGTERM and
// SIGHUP wait while commit() runs on this thread (io/Interrupt.h). A link is followed: the file it
// leads to is replaced and the link stays (/dev/stdout when stdout is a file). A device or a pipe
// (/dev/null, /dev/full, a terminal, a FIFO), named or linked to, is written in place, before the
// others, and cannot be taken back. (A crash between two renames can still leave the first; nothing
// short of a journal prevents that.)
class OutputSet {
public:
    void add(std::string path, Result<Content> content);
    void add(std::string path, Bytes bytes) { add(std::move(path), Result<Content>(Content(std::move(bytes)))); }
    Result<bool> commit();
    bool empty() const { return files_.empty(); }

private:
    std::vector<std::pair<std::string, Result<Content>>> files_;
};

struct DecodedImage {
    int width = 0, height = 0, channels = 0, bitDepth = 8;
    std::vector<std::uint8_t> pixels8;    // when bitDepth == 8, top row first
    std::vector<std::uint16_t> pixels16;  // when bitDepth == 16, top row first
};
// Reads a PNG (stb_image), keeping its channel count and bit depth. Its chunks and declared size are
// checked first (scene/ImageCheck.h): at most 16384x16384 pixels, and only what its data can fill.
Result<DecodedImage> readPng(const std::string& path);
// The same on a file's bytes in memory; `name` stands for the file in messages.
Result<DecodedImage> decodePng(std::span<const std::uint8_t> bytes, const std::string& name);

// Buffers ⇄ images in file order.
std::vector<std::uint8_t> flipRows(const std::uint8_t* rows, int width, int height, int bytesPerPixel);

}  // namespace frugal
