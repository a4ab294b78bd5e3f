// Stage 3 of the glTF loader (internal, not installed): the structure, on JSON that passed
// checkSchema (GltfSchema.h), still before tinygltf reads it: every index in range, the node
// hierarchy a forest, buffers present with their declared sizes, cameras and the asset version
// usable, since tinygltf leaves most references unchecked. Failures go through load::fail
// (GltfCheck.h).
//
// Every function here requires a root that checkSchema accepted: it reads fields with the types
// the schema guarantees (on other JSON, nlohmann throws type_error or worse).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "scene/GltfCheck.h"
#include "scene/GltfContainer.h"

namespace frugal::gltf {

// References, the node forest, scenes listing only roots, cameras.
void checkStructure(const Json& root);

// Decodes a "data:" URI into bytes; false when it cannot. Passed in so that tinygltf's decoder,
// which loadGltf relies on later, decides, while tinygltf stays in one .cpp.
using DataUriDecoder = bool (*)(const std::string& uri, std::vector<unsigned char>& bytes);

// Every buffer present with exactly its byteLength: a data URI, a file next to the .gltf (`dir`),
// or buffer 0 of a .glb (`glb`, null for a .gltf) in the BIN chunk. Checked before tinygltf runs,
// for messages that say which buffer and by how much; tinygltf then finds every buffer whole.
// `placeholders` are left out: EXT_meshopt_compression's buffers without data
// (Compression::fallbackBuffers, GltfCompression.h), which the loader fills by decoding.
void checkBuffers(const Json& root, const std::filesystem::path& dir, const GlbParts* glb, DataUriDecoder decodeDataUri,
                  const std::vector<std::size_t>& placeholders);

// Extension names the file declares ("extensionsUsed", "extensionsRequired") or uses anywhere
// outside "extras", each once, in order of first appearance.
std::vector<std::string> usedExtensions(const Json& root);

}  // namespace frugal::gltf
