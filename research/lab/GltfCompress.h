// Compressed copies of glTF files (frugal-lab compress): the inputs of the loader's decompression
// tests and fuzz seeds, and of the measurements that compare a compressed file's render with its
// original's. Written with the encoders of the libraries the loader decodes with: Debian's libdraco
// (KHR_draco_mesh_compression) and meshoptimizer (EXT_meshopt_compression).
#pragma once

#include <string>

#include <frugal/Result.h>

namespace frugal {

struct CompressOptions {
    enum class Method { Draco, Meshopt } method = Method::Meshopt;
    // Draco: bits of position quantization (0: none, the positions decode exactly); normals and
    // texture coordinates get the same with at least 10 bits, 0 likewise keeping them exact.
    int dracoBits = 0;
    // Draco: the sequential encoder (faces and points keep their order) instead of Edgebreaker
    // (smaller; reorders both, so triangle ids follow the decoded order).
    bool dracoSequential = false;
    // meshopt: index lists of TRIANGLES primitives in the TRIANGLES codec (smaller; it may rotate a
    // triangle's vertices, keeping its winding) instead of INDICES (the order kept exactly).
    bool meshoptTriangles = false;
    // meshopt: the lossy filters too: normals octahedral in 16-bit (KHR_mesh_quantization's SHORT,
    // stride 8), positions exponential with a 15-bit mantissa.
    bool meshoptFilters = false;
};

// `path` (a .gltf whose buffers are files beside it or data URIs) compressed: a self-contained
// .gltf text (its one data buffer a data URI). Every TRIANGLES primitive is compressed (Draco), or
// every bufferView whose layout the codecs take (meshopt: vertex data of strides that are multiples
// of 4 up to 256, index lists of 2 or 4 bytes); the rest is copied.
Result<std::string> compressGltf(const std::string& path, const CompressOptions& options);

}  // namespace frugal
