// Compressed glTF geometry (internal to src/scene/, not installed): KHR_draco_mesh_compression
// (Debian's libdraco) and EXT_meshopt_compression (meshoptimizer's decoders). KHR_mesh_quantization
// needs nothing here: it only widens the accessor types the loader reads.
//
// The loader decompresses before it converts anything, so that every later stage reads plain
// accessors as it reads an uncompressed file's:
//   1. findCompression, on the JSON that checkStructure accepted: every extension object checked
//      (types, ranges, references), what is compressed listed;
//   2. forTinygltf: the JSON tinygltf is given, which cannot read a compressed file as it is (it
//      refuses an index accessor without a bufferView, which a Draco primitive has, and a buffer
//      without a uri, which meshopt's fallback buffer is);
//   3. decodeMeshopt and decodeDraco, on bytes, called by the loader (GltfLoader.cpp) to rewrite
//      tinygltf's model: a meshopt bufferView then points at its decoded bytes, a Draco primitive
//      at new accessors holding its decoded attributes and indices.
// A corrupt stream fails as any broken file does (load::fail, one line naming where).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "scene/GltfCheck.h"

namespace frugal::gltf {

// glTF's accessor component types (the GL enums).
enum ComponentType : int {
    kByte = 5120,
    kUnsignedByte = 5121,
    kShort = 5122,
    kUnsignedShort = 5123,
    kUnsignedInt = 5125,
    kFloat = 5126
};

// A primitive with KHR_draco_mesh_compression.
struct DracoPrimitive {
    std::size_t mesh = 0, primitive = 0;
    std::size_t bufferView = 0;  // the compressed stream
    int mode = 4;                // the primitive's (TRIANGLES by default)
    int indices = -1;            // the primitive's index accessor, -1 = none
    struct Attribute {
        std::string name;  // "POSITION", "TEXCOORD_0", ...
        std::uint32_t uniqueId = 0;
    };
    std::vector<Attribute> attributes;  // the extension's, each also one of the primitive's
};

// A bufferView with EXT_meshopt_compression.
struct MeshoptView {
    enum class Mode : std::uint8_t { Attributes, Triangles, Indices };
    enum class Filter : std::uint8_t { None, Octahedral, Quaternion, Exponential };
    std::size_t view = 0;
    std::size_t buffer = 0, byteOffset = 0, byteLength = 0;  // the compressed stream
    std::size_t byteStride = 0, count = 0;                   // what it decodes to: count × byteStride bytes
    Mode mode = Mode::Attributes;
    Filter filter = Filter::None;
};

struct Compression {
    std::vector<DracoPrimitive> draco;
    std::vector<MeshoptView> meshopt;
    std::vector<std::size_t> fallbackBuffers;  // meshopt's buffers without data (no uri)
    bool any() const { return !draco.empty() || !meshopt.empty() || !fallbackBuffers.empty(); }
};

// Stage 1. On JSON that checkStructure accepted. Fails naming the value: an extension object of
// the wrong shape, a stride meshopt cannot decode, a bufferView of a fallback buffer that is not
// compressed itself (it has no bytes to read), an attribute the primitive does not have. `glb`:
// the file is a .glb, whose buffer 0 without a uri is its BIN chunk.
Compression findCompression(const Json& root, bool glb);

// Stage 2. The JSON to hand tinygltf: a Draco primitive without "indices" (the loader restores
// them from DracoPrimitive::indices) and every fallback buffer one byte of a data URI.
Json forTinygltf(const Json& root, const Compression& compression);

// Stage 3. The count × byteStride bytes `view` decodes to from `stream`, its filter applied.
// `where` names the bufferView in messages.
std::vector<unsigned char> decodeMeshopt(const MeshoptView& view, std::span<const unsigned char> stream,
                                         const std::string& where);

// What a Draco attribute is decoded to: the type of the accessor that declares it.
struct DracoRequest {
    std::uint32_t uniqueId = 0;
    int componentType = kFloat;
    int components = 3;
    std::string name;  // for messages
};

struct DracoDecoded {
    std::size_t points = 0;
    std::vector<std::uint32_t> indices;            // 3 per face, each below `points`
    std::vector<std::vector<unsigned char>> data;  // per request: points × components, packed
};

// The mesh `stream` holds, each requested attribute converted to its accessor's component type (a
// value that does not fit fails). `where` names the primitive in messages.
DracoDecoded decodeDraco(std::span<const unsigned char> stream, std::span<const DracoRequest> requests,
                         const std::string& where);

// The decoded size the loader accepts from `compressed` bytes (meshopt codecs compress at most
// about 64:1; Draco is checked against its own point and face counts): guards the allocation a
// crafted count would make.
inline constexpr std::size_t kMaxDecodedBytes = std::size_t(1) << 30;

}  // namespace frugal::gltf
