// Stage 1 of the glTF loader (internal, not installed): the container. What reaches the later
// stages is a JSON object, and for a .glb its JSON and BIN chunks with every length checked.
// tinygltf's own GLB reader trusts the chunk lengths (it can read 8 bytes past the end), and it
// converts "extras" recursively, so the chunks and the nesting depth are checked here first.
// The checks fail through load::fail (GltfCheck.h).
#pragma once

#include <string>
#include <string_view>

#include "scene/GltfCheck.h"

namespace frugal::gltf {

// Views into the file the parts were split from.
struct GlbParts {
    std::string_view json;
    std::string_view bin;
    bool hasBin = false;
    bool canonical = false;  // exactly header + JSON + BIN, 4-byte aligned: tinygltf can take it as is
};

// A .glb, or any file that starts with the GLB magic, is read as binary glTF.
bool isBinary(const std::string& path, std::string_view bytes);

// The chunks of a GLB file: header, lengths, chunk order; other chunk types are skipped.
GlbParts splitGlb(std::string_view file);

// tinygltf wants 4-byte aligned chunks and a BIN chunk right after the JSON one; the spec is looser
// about padding and extra chunks, so such files are re-packed before handing them over.
std::string canonicalGlb(const GlbParts& parts);

// nlohmann parses iteratively, but tinygltf converts "extras" recursively: the depth is bounded first.
inline constexpr int kMaxJsonDepth = 256;

// The JSON text as an object: nesting within kMaxJsonDepth, valid syntax, an object at the root.
Json parseJson(std::string_view text);

}  // namespace frugal::gltf
