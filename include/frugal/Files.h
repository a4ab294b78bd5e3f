// Image files, top row first as every viewer expects, written all or nothing: to a temporary file in
// the same folder, then renamed (an interrupted program never leaves a half-written image).
//   colour: 8-bit RGBA PNG;
//   depth:  16-bit grey PNG, 0 near, 65535 far (d24: the top 16 of its 24 bits; d32f: (1 − window z)
//           · 65535 rounded), with the format and the planes it was drawn with in tEXt chunks
//           (depth_format, depth_znear, depth_zfar, depth_projection, depth_encoding); or PFM, the
//           window z as float32, exact (d32f: reversed, 1 near, 0 far);
//   ids:    8-bit RGBA PNG whose bytes are the 32-bit id, little-endian (R = bits 0-7); 0 is the
//           background.
// Errors (ErrorKind::Io): "<path>: <why>", e.g. "out.png: write failed after 4096 of 9120 bytes:
// File too large", with nothing left behind.
#pragma once

#include <string>

#include <frugal/Image.h>
#include <frugal/Result.h>

namespace frugal {

Result<bool> writePng(const std::string& path, const ColorImage& image);
Result<bool> writePng(const std::string& path, const DepthImage& image);
Result<bool> writePfm(const std::string& path, const DepthImage& image);
Result<bool> writePng(const std::string& path, const IdImage& image);

// A frame's files as `frugal render` writes them, as one set: each to a temporary name, then all
// renamed together (a set is never half renamed, and on an error none of it is left). An empty path
// is not written; depth is PFM when its path ends in .pfm (any case), else the 16-bit PNG. Error for
// ids asked of a frame without them: "ids <path>: the frame has no ids (Settings::ids)" (BadInput).
struct FramePaths {
    std::string color, depth, ids;
};
struct Frame;
Result<bool> writeFrame(const FramePaths& paths, const Frame& frame);

}  // namespace frugal
