// What the glTF checks share (internal to src/scene/, not installed): the JSON type, the failure
// mechanism and the wording of paths and values in messages.
//
// A check fails through load::fail, which throws load::Failure with the message; loadGltf runs every
// stage inside load::guard, which turns it into Error{"<path>: <message>"}, so no exception leaves
// loadGltf. A test or fuzz target that calls a stage directly catches load::Failure itself.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "scene/LoadSupport.h"

namespace frugal::gltf {

using Json = nlohmann::json;
using load::cat;
using load::fail;
using load::Failure;

std::string plural(std::size_t n, const char* singular, const char* pluralForm);

// Member `key` of a JSON object, or null when it has none.
const Json& member(const Json& object, const char* key);

// A value as messages quote it: null, true, string "...", an object, an array, or the number.
std::string describe(const Json& v);

// Paths into the JSON: child("", "scene") = "scene", child("nodes[2]", "mesh") = "nodes[2].mesh",
// element("nodes", 2) = "nodes[2]".
std::string child(const std::string& where, std::string_view key);
std::string element(const std::string& where, std::size_t i);

}  // namespace frugal::gltf
