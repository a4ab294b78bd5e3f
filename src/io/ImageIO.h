// Image files. Buffers hold rows bottom-up (GL window origin); every encoder here flips once, so
// files are top row first as every viewer expects.
//
// - colour: 8-bit RGBA PNG;
// - depth: 16-bit greyscale PNG holding the top 16 bits of the 24-bit depth (0 near, 65535 far), or
//   PFM (portable float map, window z as float32) for the exact values;
// - triangle ids: 8-bit RGBA PNG whose bytes are the 32-bit id, little-endian (R = bits 0-7,
//   G = 8-15, B = 16-23, A = 24-31); 0 is the background.
// Files are written atomically: to a temporary file in the same folder, then renamed, so an
// interrupted run never leaves a half-written image (io/Interrupt.h: no signal is handled meanwhile).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "render/Image.h"
#include "base/Result.h"

namespace frugal {

using Bytes = std::vector<std::uint8_t>;

// PNG encoder (zlib). `channels` 1..4, `bitDepth` 8 or 16 (16-bit samples given as uint16 in host
// order), rows given top row first, 1 to 2^31 − 1 pixels a side (the PNG limit). Errors:
// "PNG encoder: <what>, got <value>" for a format PNG cannot hold, or zlib's failure.
Result<Bytes> encodePng(int width, int height, int channels, int bitDepth, const void* rowsTopFirst);

Result<Bytes> encodeColorPng(const Buffers& buffers);
Result<Bytes> encodeDepthPng(const Buffers& buffers);
Bytes encodeDepthPfm(const Buffers& buffers);
Result<Bytes> encodeIdPng(const Buffers& buffers);

// Writes `bytes` to `path` atomically. Error: "<path>: <why>" (also when `bytes` is an encoder's
// error: then nothing is written), e.g. "out.png: write failed after 4096 of 9120 bytes: File too
// large", "/sys/x.png: cannot write: Permission denied".
Result<bool> writeFileAtomic(const std::string& path, Result<Bytes> bytes);

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
    void add(std::string path, Result<Bytes> bytes);
    Result<bool> commit();
    bool empty() const { return files_.empty(); }

private:
    std::vector<std::pair<std::string, Result<Bytes>>> files_;
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
