// Stage 2 of the glTF loader (internal, not installed): the raw JSON against the glTF 2.0 schema
// (types, required properties, enums, array lengths), checked before tinygltf reads the file,
// because tinygltf silently substitutes a default for a wrong-typed field.
#pragma once

#include "scene/GltfCheck.h"

namespace frugal::gltf {

// Fails through load::fail (GltfCheck.h) with "<JSON path>: <what>", e.g.
// "nodes[0].mesh: expected a non-negative integer below 2^31, got -1". Wrong types are reported
// before missing properties. The structure checks (GltfStructure.h) rely on a root that passed.
// `root` as nlohmann parses text: a non-negative integer must be stored as unsigned to count as an
// index (a Json built in code from the literal 0 holds a signed integer and is refused).
void checkSchema(const Json& root);

}  // namespace frugal::gltf
