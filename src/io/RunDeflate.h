// A deflate encoder for PNG rows that looks for one kind of match only: the `step` bytes before a
// position repeated (distance = step: the pixel to the left, or for PNG's filtered rows, a run of
// zero residuals). Rendered images are mostly such runs (background, flat faces, the zeros the Up
// filter leaves where a row repeats the one above) and small residuals (smooth shading), so this
// keeps most of what a general LZ77 search finds at a fraction of its cost: no hash table, one
// comparison per byte, eight bytes at a time inside a run (measured at 1080p, docs/writing.md:
// 3x faster than libdeflate at level 2 or 3; files 0.85-1.07x zlib level 6's on the bunny and the
// dominoes, 1.40x on an engine whose repeats lie elsewhere). Each block of input gets its own
// Huffman codes (dynamic blocks, RFC 1951 section 3.2.7), or is stored when that is smaller.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace frugal {

// The zlib stream (RFC 1950: header, deflate blocks, Adler-32) of `data`, written at `out`, which
// holds at least runDeflateBound(data.size()) bytes; returns its size. Matches repeat the bytes
// `step` back: 1 to 8, a pixel's bytes.
std::size_t runDeflateZlib(std::span<const std::uint8_t> data, std::size_t step, std::uint8_t* out);
// The most that runDeflateZlib writes for `size` bytes (no block is larger than storing it).
std::size_t runDeflateBound(std::size_t size);

}  // namespace frugal
