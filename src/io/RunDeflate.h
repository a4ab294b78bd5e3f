// A deflate encoder for PNG rows that looks for one kind of match only: the `step` bytes before a
// position repeated (distance = step: the pixel to the left, or for PNG's filtered rows, a run of
// zero residuals). Rendered images are mostly runs (background, flat faces, the zeros the Up filter
// leaves where a row repeats the one above) and small residuals (smooth shading), so this finds
// nearly every match a general LZ77 search would, at a fraction of its cost: no hash table, one
// comparison per byte, eight bytes at a time inside a run. Each block of input gets its own
// Huffman codes (dynamic blocks, RFC 1951 section 3.2.7), or is stored when that is smaller.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace frugal {

// The zlib stream (RFC 1950: header, deflate blocks, Adler-32) of `data`, written at `out`, which
// holds at least runDeflateBound(data.size()) bytes; returns its size. Matches repeat the bytes
// `step` back: 1 to 8, a pixel's bytes.
std::size_t runDeflateZlib(std::span<const std::uint8_t> data, std::size_t step, std::uint8_t* out);
// The most that runDeflateZlib writes for `size` bytes (no block is larger than storing it).
std::size_t runDeflateBound(std::size_t size);

}  // namespace frugal
