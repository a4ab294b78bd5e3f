// glTF 2.0 loader (.gltf and .glb) on top of tinygltf, the one file of the project that includes it.
//
// tinygltf (Debian 2.7) parses the JSON and loads buffers and images, but it accepts invalid files:
// it replaces wrong-typed fields by defaults, leaves most references unchecked, lets accessors run
// past their buffers, and its GLB reader trusts chunk lengths (it can read 8 bytes past the end).
// So this loader checks, in this order:
//   1. the container: file readable, GLB header and chunks, JSON syntax and nesting depth;
//   2. the raw JSON (nlohmann) against the glTF 2.0 schema: types, required properties, enums,
//      array lengths, before tinygltf can substitute a default for a wrong-typed field;
//   3. the structure, still on the JSON: every index in range, the node hierarchy a forest,
//      buffers present with the declared sizes, cameras and transforms usable;
//   4. the data, while it is read from tinygltf's model: bufferView and accessor ranges, index
//      values, animation key times and counts.
// A fatal problem becomes Error{"<path>: <what, where, with the numbers>"} on one line; no exception
// leaves loadGltf. NaN/Inf positions are not fatal: finalizeMesh drops their triangles.
//
// Which scene is loaded: the file's default scene ("scene"), else scene 0, else (a file without
// scenes) every root node, so that a bare node list still renders. Nodes outside that scene are kept,
// so node indices match the file and animation targets stay valid, but they get no meshes and so
// no instances.
#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "scene/Load.h"
#include "scene/LoadSupport.h"
#include "scene/MeshBuild.h"

namespace frugal {

namespace {

using namespace load;
using Json = nlohmann::json;

std::string plural(std::size_t n, const char* singular, const char* pluralForm) {
    return cat(n, " ", n == 1 ? singular : pluralForm);
}

// ---------------------------------------------------------------------------------------------
// 1. Container: the file, the GLB chunks, the JSON text.

constexpr std::uint32_t kGlbMagic = 0x46546C67;   // "glTF", little-endian
constexpr std::uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;   // "BIN\0"

// GLB fields are little-endian; assembled byte by byte so the host's order does not matter.
std::uint32_t readU32(std::string_view bytes, std::size_t offset) {
    std::uint32_t value = 0;
    for (std::size_t k = 0; k < 4; ++k)
        value |= std::uint32_t(static_cast<unsigned char>(bytes[offset + k])) << (8 * k);
    return value;
}

struct GlbParts {
    std::string_view json;
    std::string_view bin;
    bool hasBin = false;
    bool canonical = false;  // exactly header + JSON + BIN, 4-byte aligned: tinygltf can take it as is
};

GlbParts splitGlb(std::string_view file) {
    if (file.size() < 12) fail("truncated GLB: ", file.size(), " bytes, the header alone needs 12");
    if (readU32(file, 0) != kGlbMagic) fail("not a binary glTF file (the first 4 bytes are not 'glTF')");
    const std::uint32_t version = readU32(file, 4);
    if (version != 2) fail("GLB container version ", version, ", frugal reads version 2");
    const std::uint32_t length = readU32(file, 8);
    if (length > file.size()) fail("truncated GLB: the header declares ", length, " bytes, the file has ", file.size());
    if (length < file.size()) fail("GLB header declares ", length, " bytes but the file has ", file.size());

    GlbParts parts;
    std::size_t offset = 12;
    int chunk = 0;
    for (; offset < length; ++chunk) {
        if (length - offset < 8)
            fail("truncated GLB: chunk ", chunk, " at byte ", offset, " needs an 8-byte header, ", length - offset,
                 " bytes remain");
        const std::uint32_t chunkLength = readU32(file, offset);
        const std::uint32_t type = readU32(file, offset + 4);
        if (chunkLength > length - offset - 8)
            fail("truncated GLB: chunk ", chunk, " at byte ", offset, " declares ", chunkLength, " bytes, ",
                 length - offset - 8, " remain");
        const std::string_view data = file.substr(offset + 8, chunkLength);
        if (chunk == 0) {
            if (type != kChunkJson) fail("GLB chunk 0 is not the JSON chunk (type 0x", std::hex, type, ")");
            parts.json = data;
        } else if (chunk == 1 && type == kChunkBin) {
            parts.bin = data;
            parts.hasBin = true;
        }
        // Other chunk types are allowed by the spec and ignored.
        offset += 8 + std::size_t(chunkLength);
    }
    if (chunk == 0) fail("GLB has no JSON chunk");
    parts.canonical = parts.json.size() % 4 == 0 && chunk == (parts.hasBin ? 2 : 1) &&
                      (!parts.hasBin || (parts.bin.size() % 4 == 0 && parts.bin.size() >= 4));
    return parts;
}

// tinygltf wants 4-byte aligned chunks and a BIN chunk right after the JSON one; the spec is looser
// about padding and extra chunks, so such files are re-packed before handing them over.
std::string canonicalGlb(const GlbParts& parts) {
    auto put32 = [](std::string& out, std::size_t v) {
        for (int k = 0; k < 4; ++k) out += char((v >> (8 * k)) & 0xFF);
    };
    const std::size_t jsonLength = (parts.json.size() + 3) / 4 * 4;
    const bool bin = parts.hasBin && !parts.bin.empty();
    const std::size_t binLength = bin ? (parts.bin.size() + 3) / 4 * 4 : 0;
    std::string out;
    out.reserve(12 + 8 + jsonLength + (bin ? 8 + binLength : 0));
    put32(out, kGlbMagic);
    put32(out, 2);
    put32(out, 12 + 8 + jsonLength + (bin ? 8 + binLength : 0));
    put32(out, jsonLength);
    put32(out, kChunkJson);
    out.append(parts.json);
    out.append(jsonLength - parts.json.size(), ' ');
    if (bin) {
        put32(out, binLength);
        put32(out, kChunkBin);
        out.append(parts.bin);
        out.append(binLength - parts.bin.size(), '\0');
    }
    return out;
}

// nlohmann parses iteratively, but tinygltf converts "extras" recursively: bound the depth first.
constexpr int kMaxJsonDepth = 256;

void checkNesting(std::string_view text) {
    int depth = 0;
    bool inString = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (c == '\\')
                ++i;
            else if (c == '"')
                inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '{' || c == '[') {
            if (++depth > kMaxJsonDepth) fail("JSON nested deeper than ", kMaxJsonDepth, " levels (at byte ", i, ")");
        } else if (c == '}' || c == ']') {
            --depth;
        }
    }
}

std::string describe(const Json& v) {
    switch (v.type()) {
        case Json::value_t::null:
            return "null";
        case Json::value_t::boolean:
            return v.get<bool>() ? "true" : "false";
        case Json::value_t::string:
            return cat("string \"", oneLine(v.get_ref<const std::string&>(), 40), "\"");
        case Json::value_t::object:
            return "an object";
        case Json::value_t::array:
            return "an array";
        case Json::value_t::number_integer:
        case Json::value_t::number_unsigned:
        case Json::value_t::number_float:
            return v.dump();
        default:
            return "an unexpected value";
    }
}

Json parseJson(std::string_view text) {
    checkNesting(text);
    Json root;
    try {
        root = Json::parse(text.begin(), text.end());
    } catch (const Json::exception& e) {
        std::string what = e.what();
        // "[json.exception.parse_error.101] parse error at line 1, ..." → "parse error at line 1, ..."
        const std::size_t close = what.find("] ");
        if (what.rfind("[json.exception.", 0) == 0 && close != std::string::npos) what.erase(0, close + 2);
        fail("invalid JSON: ", oneLine(what));
    }
    if (!root.is_object()) fail("the JSON root is ", describe(root), ", expected an object");
    return root;
}

// ---------------------------------------------------------------------------------------------
// 2. Schema: the glTF 2.0 JSON schema, as far as this loader or tinygltf reads it. Properties not
// listed are allowed and ignored, as the spec allows. Every object may also carry "name" (string),
// "extensions" (an object of objects) and "extras" (anything).

enum class Kind : std::uint8_t {
    Index,    // integer in [0, 2^31): tinygltf stores indices as int
    Count,    // non-negative integer
    Integer,  // integer that fits an int
    Number,
    Boolean,
    String,
    Object,
    ObjectArray,
    IndexArray,
    NumberArray,
    StringArray,
    IndexMap,      // object whose values are indices (primitive attributes)
    IndexMapArray  // array of those (morph targets)
};

struct Schema;

struct Field {
    const char* name;
    Kind kind;
    const Schema* schema = nullptr;  // for Object and ObjectArray
    bool required = false;
    std::size_t length = 0;  // arrays: exact length, 0 = any
    std::span<const std::int64_t> ints = {};
    std::span<const std::string_view> strings = {};
};

struct Schema {
    std::span<const Field> fields;
};

constexpr std::int64_t kComponentTypes[] = {5120, 5121, 5122, 5123, 5125, 5126};
constexpr std::int64_t kIndexComponentTypes[] = {5121, 5123, 5125};
constexpr std::int64_t kModes[] = {0, 1, 2, 3, 4, 5, 6};
constexpr std::int64_t kMagFilters[] = {9728, 9729};
constexpr std::int64_t kMinFilters[] = {9728, 9729, 9984, 9985, 9986, 9987};
constexpr std::int64_t kWraps[] = {33071, 33648, 10497};
constexpr std::string_view kAccessorTypes[] = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
constexpr std::string_view kAlphaModes[] = {"OPAQUE", "MASK", "BLEND"};
constexpr std::string_view kCameraTypes[] = {"perspective", "orthographic"};
constexpr std::string_view kPaths[] = {"translation", "rotation", "scale", "weights"};
constexpr std::string_view kInterpolations[] = {"LINEAR", "STEP", "CUBICSPLINE"};

constexpr Field kTextureInfoFields[] = {
    {.name = "index", .kind = Kind::Index, .required = true},
    {.name = "texCoord", .kind = Kind::Count},
};
constexpr Schema kTextureInfo{kTextureInfoFields};
constexpr Field kNormalTextureInfoFields[] = {
    {.name = "index", .kind = Kind::Index, .required = true},
    {.name = "texCoord", .kind = Kind::Count},
    {.name = "scale", .kind = Kind::Number},
};
constexpr Schema kNormalTextureInfo{kNormalTextureInfoFields};
constexpr Field kOcclusionTextureInfoFields[] = {
    {.name = "index", .kind = Kind::Index, .required = true},
    {.name = "texCoord", .kind = Kind::Count},
    {.name = "strength", .kind = Kind::Number},
};
constexpr Schema kOcclusionTextureInfo{kOcclusionTextureInfoFields};
constexpr Field kPbrFields[] = {
    {.name = "baseColorFactor", .kind = Kind::NumberArray, .length = 4},
    {.name = "baseColorTexture", .kind = Kind::Object, .schema = &kTextureInfo},
    {.name = "metallicFactor", .kind = Kind::Number},
    {.name = "roughnessFactor", .kind = Kind::Number},
    {.name = "metallicRoughnessTexture", .kind = Kind::Object, .schema = &kTextureInfo},
};
constexpr Schema kPbr{kPbrFields};
constexpr Field kMaterialFields[] = {
    {.name = "pbrMetallicRoughness", .kind = Kind::Object, .schema = &kPbr},
    {.name = "normalTexture", .kind = Kind::Object, .schema = &kNormalTextureInfo},
    {.name = "occlusionTexture", .kind = Kind::Object, .schema = &kOcclusionTextureInfo},
    {.name = "emissiveTexture", .kind = Kind::Object, .schema = &kTextureInfo},
    {.name = "emissiveFactor", .kind = Kind::NumberArray, .length = 3},
    {.name = "alphaMode", .kind = Kind::String, .strings = kAlphaModes},
    {.name = "alphaCutoff", .kind = Kind::Number},
    {.name = "doubleSided", .kind = Kind::Boolean},
};
constexpr Schema kMaterial{kMaterialFields};

constexpr Field kSparseIndicesFields[] = {
    {.name = "bufferView", .kind = Kind::Index, .required = true},
    {.name = "byteOffset", .kind = Kind::Index},  // tinygltf keeps it in an int
    {.name = "componentType", .kind = Kind::Integer, .required = true, .ints = kIndexComponentTypes},
};
constexpr Schema kSparseIndices{kSparseIndicesFields};
constexpr Field kSparseValuesFields[] = {
    {.name = "bufferView", .kind = Kind::Index, .required = true},
    {.name = "byteOffset", .kind = Kind::Index},
};
constexpr Schema kSparseValues{kSparseValuesFields};
constexpr Field kSparseFields[] = {
    {.name = "count", .kind = Kind::Index, .required = true},
    {.name = "indices", .kind = Kind::Object, .schema = &kSparseIndices, .required = true},
    {.name = "values", .kind = Kind::Object, .schema = &kSparseValues, .required = true},
};
constexpr Schema kSparse{kSparseFields};
constexpr Field kAccessorFields[] = {
    {.name = "bufferView", .kind = Kind::Index},
    {.name = "byteOffset", .kind = Kind::Count},
    {.name = "componentType", .kind = Kind::Integer, .required = true, .ints = kComponentTypes},
    {.name = "normalized", .kind = Kind::Boolean},
    {.name = "count", .kind = Kind::Count, .required = true},
    {.name = "type", .kind = Kind::String, .required = true, .strings = kAccessorTypes},
    {.name = "max", .kind = Kind::NumberArray},
    {.name = "min", .kind = Kind::NumberArray},
    {.name = "sparse", .kind = Kind::Object, .schema = &kSparse},
};
constexpr Schema kAccessor{kAccessorFields};

constexpr Field kAnimTargetFields[] = {
    {.name = "node", .kind = Kind::Index},
    {.name = "path", .kind = Kind::String, .required = true, .strings = kPaths},
};
constexpr Schema kAnimTarget{kAnimTargetFields};
constexpr Field kAnimChannelFields[] = {
    {.name = "sampler", .kind = Kind::Index, .required = true},
    {.name = "target", .kind = Kind::Object, .schema = &kAnimTarget, .required = true},
};
constexpr Schema kAnimChannel{kAnimChannelFields};
constexpr Field kAnimSamplerFields[] = {
    {.name = "input", .kind = Kind::Index, .required = true},
    {.name = "interpolation", .kind = Kind::String, .strings = kInterpolations},
    {.name = "output", .kind = Kind::Index, .required = true},
};
constexpr Schema kAnimSampler{kAnimSamplerFields};
constexpr Field kAnimationFields[] = {
    {.name = "channels", .kind = Kind::ObjectArray, .schema = &kAnimChannel, .required = true},
    {.name = "samplers", .kind = Kind::ObjectArray, .schema = &kAnimSampler, .required = true},
};
constexpr Schema kAnimation{kAnimationFields};

constexpr Field kAssetFields[] = {
    {.name = "copyright", .kind = Kind::String},
    {.name = "generator", .kind = Kind::String},
    {.name = "version", .kind = Kind::String, .required = true},
    {.name = "minVersion", .kind = Kind::String},
};
constexpr Schema kAsset{kAssetFields};
constexpr Field kBufferFields[] = {
    {.name = "uri", .kind = Kind::String},
    {.name = "byteLength", .kind = Kind::Count, .required = true},
};
constexpr Schema kBuffer{kBufferFields};
constexpr Field kBufferViewFields[] = {
    {.name = "buffer", .kind = Kind::Index, .required = true},
    {.name = "byteOffset", .kind = Kind::Count},
    {.name = "byteLength", .kind = Kind::Count, .required = true},
    {.name = "byteStride", .kind = Kind::Count},
    {.name = "target", .kind = Kind::Integer},
};
constexpr Schema kBufferView{kBufferViewFields};

constexpr Field kOrthographicFields[] = {
    {.name = "xmag", .kind = Kind::Number, .required = true},
    {.name = "ymag", .kind = Kind::Number, .required = true},
    {.name = "zfar", .kind = Kind::Number, .required = true},
    {.name = "znear", .kind = Kind::Number, .required = true},
};
constexpr Schema kOrthographic{kOrthographicFields};
constexpr Field kPerspectiveFields[] = {
    {.name = "aspectRatio", .kind = Kind::Number},
    {.name = "yfov", .kind = Kind::Number, .required = true},
    {.name = "zfar", .kind = Kind::Number},
    {.name = "znear", .kind = Kind::Number, .required = true},
};
constexpr Schema kPerspective{kPerspectiveFields};
constexpr Field kCameraFields[] = {
    {.name = "orthographic", .kind = Kind::Object, .schema = &kOrthographic},
    {.name = "perspective", .kind = Kind::Object, .schema = &kPerspective},
    {.name = "type", .kind = Kind::String, .required = true, .strings = kCameraTypes},
};
constexpr Schema kCamera{kCameraFields};

constexpr Field kImageFields[] = {
    {.name = "uri", .kind = Kind::String},
    {.name = "mimeType", .kind = Kind::String},
    {.name = "bufferView", .kind = Kind::Index},
};
constexpr Schema kImage{kImageFields};
constexpr Field kPrimitiveFields[] = {
    {.name = "attributes", .kind = Kind::IndexMap, .required = true},
    {.name = "indices", .kind = Kind::Index},
    {.name = "material", .kind = Kind::Index},
    {.name = "mode", .kind = Kind::Integer, .ints = kModes},
    {.name = "targets", .kind = Kind::IndexMapArray},
};
constexpr Schema kPrimitive{kPrimitiveFields};
constexpr Field kMeshFields[] = {
    {.name = "primitives", .kind = Kind::ObjectArray, .schema = &kPrimitive, .required = true},
    {.name = "weights", .kind = Kind::NumberArray},
};
constexpr Schema kMesh{kMeshFields};
constexpr Field kNodeFields[] = {
    {.name = "camera", .kind = Kind::Index},
    {.name = "children", .kind = Kind::IndexArray},
    {.name = "skin", .kind = Kind::Index},
    {.name = "matrix", .kind = Kind::NumberArray, .length = 16},
    {.name = "mesh", .kind = Kind::Index},
    {.name = "rotation", .kind = Kind::NumberArray, .length = 4},
    {.name = "scale", .kind = Kind::NumberArray, .length = 3},
    {.name = "translation", .kind = Kind::NumberArray, .length = 3},
    {.name = "weights", .kind = Kind::NumberArray},
};
constexpr Schema kNode{kNodeFields};
constexpr Field kSamplerFields[] = {
    {.name = "magFilter", .kind = Kind::Integer, .ints = kMagFilters},
    {.name = "minFilter", .kind = Kind::Integer, .ints = kMinFilters},
    {.name = "wrapS", .kind = Kind::Integer, .ints = kWraps},
    {.name = "wrapT", .kind = Kind::Integer, .ints = kWraps},
};
constexpr Schema kSampler{kSamplerFields};
constexpr Field kSceneFields[] = {
    {.name = "nodes", .kind = Kind::IndexArray},
};
constexpr Schema kScene{kSceneFields};
constexpr Field kSkinFields[] = {
    {.name = "inverseBindMatrices", .kind = Kind::Index},
    {.name = "skeleton", .kind = Kind::Index},
    {.name = "joints", .kind = Kind::IndexArray, .required = true},
};
constexpr Schema kSkin{kSkinFields};
constexpr Field kTextureFields[] = {
    {.name = "sampler", .kind = Kind::Index},
    {.name = "source", .kind = Kind::Index},
};
constexpr Schema kTexture{kTextureFields};

constexpr Field kRootFields[] = {
    {.name = "extensionsUsed", .kind = Kind::StringArray},
    {.name = "extensionsRequired", .kind = Kind::StringArray},
    {.name = "accessors", .kind = Kind::ObjectArray, .schema = &kAccessor},
    {.name = "animations", .kind = Kind::ObjectArray, .schema = &kAnimation},
    {.name = "asset", .kind = Kind::Object, .schema = &kAsset, .required = true},
    {.name = "buffers", .kind = Kind::ObjectArray, .schema = &kBuffer},
    {.name = "bufferViews", .kind = Kind::ObjectArray, .schema = &kBufferView},
    {.name = "cameras", .kind = Kind::ObjectArray, .schema = &kCamera},
    {.name = "images", .kind = Kind::ObjectArray, .schema = &kImage},
    {.name = "materials", .kind = Kind::ObjectArray, .schema = &kMaterial},
    {.name = "meshes", .kind = Kind::ObjectArray, .schema = &kMesh},
    {.name = "nodes", .kind = Kind::ObjectArray, .schema = &kNode},
    {.name = "samplers", .kind = Kind::ObjectArray, .schema = &kSampler},
    {.name = "scene", .kind = Kind::Index},
    {.name = "scenes", .kind = Kind::ObjectArray, .schema = &kScene},
    {.name = "skins", .kind = Kind::ObjectArray, .schema = &kSkin},
    {.name = "textures", .kind = Kind::ObjectArray, .schema = &kTexture},
};
constexpr Schema kRoot{kRootFields};

// nlohmann stores non-negative integers as unsigned and negative ones as signed.
bool isIndex(const Json& v) { return v.is_number_unsigned() && v.get<std::uint64_t>() <= std::uint64_t(INT_MAX); }
bool isInt(const Json& v) {
    if (v.is_number_unsigned()) return v.get<std::uint64_t>() <= std::uint64_t(INT_MAX);
    return v.is_number_integer() && v.get<std::int64_t>() >= INT_MIN;
}

std::string child(const std::string& where, std::string_view key) {
    return where.empty() ? std::string(key) : cat(where, ".", key);
}
std::string element(const std::string& where, std::size_t i) { return cat(where, "[", i, "]"); }

[[noreturn]] void wrongType(const std::string& where, const char* expected, const Json& got) {
    fail(where, ": expected ", expected, ", got ", describe(got));
}

void checkObject(const Json& object, const Schema& schema, const std::string& where);

void checkArray(const Json& v, const std::string& where) {
    if (!v.is_array()) wrongType(where, "an array", v);
}

void checkIndexMap(const Json& v, const std::string& where) {
    if (!v.is_object()) wrongType(where, "an object", v);
    for (const auto& [key, value] : v.items())
        if (!isIndex(value)) wrongType(child(where, key), "a non-negative integer below 2^31", value);
}

void checkEnums(const Json& v, const Field& field, const std::string& where) {
    if (!field.ints.empty()) {
        const std::int64_t value = v.get<std::int64_t>();
        if (std::find(field.ints.begin(), field.ints.end(), value) == field.ints.end()) {
            std::string allowed;
            for (std::int64_t a : field.ints) allowed += cat(allowed.empty() ? "" : ", ", a);
            fail(where, ": ", value, " is not one of ", allowed);
        }
    }
    if (!field.strings.empty()) {
        const std::string& value = v.get_ref<const std::string&>();
        if (std::find(field.strings.begin(), field.strings.end(), value) == field.strings.end()) {
            std::string allowed;
            for (std::string_view a : field.strings) allowed += cat(allowed.empty() ? "" : ", ", a);
            fail(where, ": \"", oneLine(value, 40), "\" is not one of ", allowed);
        }
    }
}

void checkValue(const Json& v, const Field& field, const std::string& where) {
    switch (field.kind) {
        case Kind::Index:
            if (!isIndex(v)) wrongType(where, "a non-negative integer below 2^31", v);
            break;
        case Kind::Count:
            if (!v.is_number_unsigned()) wrongType(where, "a non-negative integer", v);
            break;
        case Kind::Integer:
            if (!isInt(v)) wrongType(where, "an integer", v);
            break;
        case Kind::Number:
            if (!v.is_number()) wrongType(where, "a number", v);
            break;
        case Kind::Boolean:
            if (!v.is_boolean()) wrongType(where, "true or false", v);
            break;
        case Kind::String:
            if (!v.is_string()) wrongType(where, "a string", v);
            break;
        case Kind::Object:
            if (!v.is_object()) wrongType(where, "an object", v);
            checkObject(v, *field.schema, where);
            break;
        case Kind::ObjectArray:
            checkArray(v, where);
            for (std::size_t i = 0; i < v.size(); ++i) {
                if (!v[i].is_object()) wrongType(element(where, i), "an object", v[i]);
                checkObject(v[i], *field.schema, element(where, i));
            }
            break;
        case Kind::IndexArray:
            checkArray(v, where);
            for (std::size_t i = 0; i < v.size(); ++i)
                if (!isIndex(v[i])) wrongType(element(where, i), "a non-negative integer below 2^31", v[i]);
            break;
        case Kind::NumberArray:
            checkArray(v, where);
            for (std::size_t i = 0; i < v.size(); ++i)
                if (!v[i].is_number()) wrongType(element(where, i), "a number", v[i]);
            if (field.length != 0 && v.size() != field.length)
                fail(where, ": expected ", field.length, " numbers, got ", v.size());
            break;
        case Kind::StringArray:
            checkArray(v, where);
            for (std::size_t i = 0; i < v.size(); ++i)
                if (!v[i].is_string()) wrongType(element(where, i), "a string", v[i]);
            break;
        case Kind::IndexMap:
            checkIndexMap(v, where);
            break;
        case Kind::IndexMapArray:
            checkArray(v, where);
            for (std::size_t i = 0; i < v.size(); ++i) checkIndexMap(v[i], element(where, i));
            break;
    }
    checkEnums(v, field, where);
}

void checkObject(const Json& object, const Schema& schema, const std::string& where) {
    // Wrong types first: a wrong-typed field says more about the file than a missing one.
    for (const Field& field : schema.fields)
        if (const auto it = object.find(field.name); it != object.end())
            checkValue(*it, field, child(where, field.name));
    for (const Field& field : schema.fields)
        if (field.required && !object.contains(field.name))
            fail(where.empty() ? "glTF root" : where, ": missing required property '", field.name, "'");
    if (const auto it = object.find("name"); it != object.end() && !it->is_string())
        wrongType(child(where, "name"), "a string", *it);
    if (const auto it = object.find("extensions"); it != object.end()) {
        if (!it->is_object()) wrongType(child(where, "extensions"), "an object", *it);
        for (const auto& [name, extension] : it->items())
            if (!extension.is_object()) wrongType(child(child(where, "extensions"), name), "an object", extension);
    }
}

void addUnique(std::vector<std::string>& names, const std::string& name) {
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
}

// Extension names used anywhere (outside "extras"), in order of first appearance.
void collectExtensions(const Json& v, std::vector<std::string>& names) {
    if (v.is_object()) {
        for (const auto& [key, value] : v.items()) {
            if (key == "extras") continue;
            if (key == "extensions" && value.is_object())
                for (const auto& [name, extension] : value.items()) addUnique(names, name);
            collectExtensions(value, names);
        }
    } else if (v.is_array()) {
        for (const Json& e : v) collectExtensions(e, names);
    }
}

// ---------------------------------------------------------------------------------------------
// 3. Structure, on the schema-checked JSON: references, hierarchy, cameras, buffers.

const Json& member(const Json& object, const char* key) {
    static const Json kNull;
    const auto it = object.find(key);
    return it == object.end() ? kNull : *it;
}

struct Collection {
    const char* singular;
    const char* pluralForm;
    std::size_t size;
};

Collection collection(const Json& root, const char* key, const char* singular, const char* pluralForm) {
    return {singular, pluralForm, member(root, key).size()};
}

void checkIndexValue(const Json& value, const Collection& target, const std::string& where) {
    const std::uint64_t index = value.get<std::uint64_t>();
    if (index >= target.size)
        fail(where, ": ", target.singular, " ", index, " out of range, the file has ",
             plural(target.size, target.singular, target.pluralForm));
}

void checkIndex(const Json& object, const char* key, const Collection& target, const std::string& where) {
    if (const auto it = object.find(key); it != object.end()) checkIndexValue(*it, target, child(where, key));
}

void checkIndexArray(const Json& object, const char* key, const Collection& target, const std::string& where) {
    const Json& array = member(object, key);
    for (std::size_t i = 0; i < array.size(); ++i) checkIndexValue(array[i], target, element(child(where, key), i));
}

void checkIndexMapValues(const Json& map, const Collection& target, const std::string& where) {
    for (const auto& [key, value] : map.items()) checkIndexValue(value, target, child(where, key));
}

template <class Fn>
void forEach(const Json& object, const char* key, const std::string& where, Fn fn) {
    const Json& array = member(object, key);
    for (std::size_t i = 0; i < array.size(); ++i) fn(array[i], i, element(child(where, key), i));
}

struct Collections {
    Collection accessors, animations, buffers, bufferViews, cameras, images, materials, meshes, nodes, samplers, scenes,
        skins, textures;
    explicit Collections(const Json& root)
        : accessors(collection(root, "accessors", "accessor", "accessors")),
          animations(collection(root, "animations", "animation", "animations")),
          buffers(collection(root, "buffers", "buffer", "buffers")),
          bufferViews(collection(root, "bufferViews", "bufferView", "bufferViews")),
          cameras(collection(root, "cameras", "camera", "cameras")),
          images(collection(root, "images", "image", "images")),
          materials(collection(root, "materials", "material", "materials")),
          meshes(collection(root, "meshes", "mesh", "meshes")),
          nodes(collection(root, "nodes", "node", "nodes")),
          samplers(collection(root, "samplers", "sampler", "samplers")),
          scenes(collection(root, "scenes", "scene", "scenes")),
          skins(collection(root, "skins", "skin", "skins")),
          textures(collection(root, "textures", "texture", "textures")) {}
};

void checkAsset(const Json& asset) {
    const std::string& version = member(asset, "version").get_ref<const std::string&>();
    if (version.rfind("2.", 0) != 0) fail("asset.version: glTF ", oneLine(version, 20), " is not supported (2.x only)");
    if (asset.contains("minVersion")) {
        const std::string& minVersion = asset["minVersion"].get_ref<const std::string&>();
        if (minVersion != "2.0")
            fail("asset.minVersion: the file needs glTF ", oneLine(minVersion, 20), ", frugal reads 2.0");
    }
}

// KHR_draco_mesh_compression leaves the uncompressed accessors without a bufferView when the
// extension is required; frugal cannot decode Draco, so such a primitive has no data to draw.
void checkDraco(const Json& accessors, const Json& primitive, std::size_t mesh, std::size_t p) {
    if (!member(member(primitive, "extensions"), "KHR_draco_mesh_compression").is_object()) return;
    auto plain = [&](const Json& index) {
        const Json& accessor = accessors[index.get<std::size_t>()];
        return accessor.contains("bufferView") || accessor.contains("sparse");
    };
    bool ok = !primitive.contains("indices") || plain(primitive["indices"]);
    for (const auto& [name, index] : primitive["attributes"].items()) ok = ok && plain(index);
    if (!ok)
        fail("mesh ", mesh, " primitive ", p,
             ": compressed with KHR_draco_mesh_compression, which frugal cannot "
             "decode, and has no uncompressed fallback");
}

void checkMeshReferences(const Json& root, const Collections& n) {
    const Json& accessors = member(root, "accessors");
    forEach(root, "meshes", "", [&](const Json& mesh, std::size_t m, const std::string& meshWhere) {
        forEach(mesh, "primitives", meshWhere, [&](const Json& primitive, std::size_t p, const std::string& where) {
            checkIndexMapValues(primitive["attributes"], n.accessors, child(where, "attributes"));
            checkIndex(primitive, "indices", n.accessors, where);
            checkIndex(primitive, "material", n.materials, where);
            forEach(primitive, "targets", where, [&](const Json& target, std::size_t, const std::string& targetWhere) {
                checkIndexMapValues(target, n.accessors, targetWhere);
            });
            checkDraco(accessors, primitive, m, p);
            // tinygltf rejects index accessors without a bufferView (all-zero or sparse-only).
            if (primitive.contains("indices") &&
                !accessors[primitive["indices"].get<std::size_t>()].contains("bufferView"))
                fail(child(where, "indices"), ": accessor ", primitive["indices"].get<std::size_t>(),
                     " has no bufferView, which frugal does not support for indices");
        });
    });
    forEach(root, "accessors", "", [&](const Json& accessor, std::size_t, const std::string& where) {
        checkIndex(accessor, "bufferView", n.bufferViews, where);
        if (accessor.contains("sparse")) {
            const std::string sparse = child(where, "sparse");
            checkIndex(accessor["sparse"]["indices"], "bufferView", n.bufferViews, child(sparse, "indices"));
            checkIndex(accessor["sparse"]["values"], "bufferView", n.bufferViews, child(sparse, "values"));
        }
    });
    forEach(root, "bufferViews", "", [&](const Json& view, std::size_t, const std::string& where) {
        checkIndex(view, "buffer", n.buffers, where);
        if (view.contains("byteStride")) {
            const std::uint64_t stride = view["byteStride"].get<std::uint64_t>();
            if (stride < 4 || stride > 252 || stride % 4 != 0)
                fail(child(where, "byteStride"), ": ", stride, " is not a multiple of 4 between 4 and 252");
        }
    });
}

void checkMaterialReferences(const Json& root, const Collections& n) {
    forEach(root, "materials", "", [&](const Json& material, std::size_t, const std::string& where) {
        const Json& pbr = member(material, "pbrMetallicRoughness");
        const std::string pbrWhere = child(where, "pbrMetallicRoughness");
        for (const char* key : {"baseColorTexture", "metallicRoughnessTexture"})
            if (pbr.contains(key)) checkIndex(pbr[key], "index", n.textures, child(pbrWhere, key));
        for (const char* key : {"normalTexture", "occlusionTexture", "emissiveTexture"})
            if (material.contains(key)) checkIndex(material[key], "index", n.textures, child(where, key));
    });
    forEach(root, "textures", "", [&](const Json& texture, std::size_t, const std::string& where) {
        checkIndex(texture, "source", n.images, where);
        checkIndex(texture, "sampler", n.samplers, where);
    });
    forEach(root, "images", "", [&](const Json& image, std::size_t, const std::string& where) {
        const bool uri = image.contains("uri"), view = image.contains("bufferView");
        if (uri == view) fail(where, uri ? ": has both uri and bufferView" : ": has neither uri nor bufferView");
        checkIndex(image, "bufferView", n.bufferViews, where);
    });
}

void checkAnimationReferences(const Json& root, const Collections& n) {
    const Json& nodes = member(root, "nodes");
    forEach(root, "animations", "", [&](const Json& animation, std::size_t, const std::string& animationWhere) {
        const Collection samplers{"sampler", "samplers", member(animation, "samplers").size()};
        forEach(animation, "channels", animationWhere, [&](const Json& channel, std::size_t, const std::string& where) {
            checkIndex(channel, "sampler", samplers, where);
            const Json& target = channel["target"];
            checkIndex(target, "node", n.nodes, child(where, "target"));
            if (target.contains("node") && nodes[target["node"].get<std::size_t>()].contains("matrix") &&
                target["path"] != "weights")
                fail(child(child(where, "target"), "node"), ": node ", target["node"].get<std::size_t>(),
                     " has a matrix, but glTF animates only nodes with translation/rotation/scale");
        });
        forEach(animation, "samplers", animationWhere, [&](const Json& sampler, std::size_t, const std::string& where) {
            checkIndex(sampler, "input", n.accessors, where);
            checkIndex(sampler, "output", n.accessors, where);
        });
    });
    forEach(root, "skins", "", [&](const Json& skin, std::size_t, const std::string& where) {
        checkIndexArray(skin, "joints", n.nodes, where);
        checkIndex(skin, "skeleton", n.nodes, where);
        checkIndex(skin, "inverseBindMatrices", n.accessors, where);
    });
}

// glTF requires the nodes to form disjoint strict trees: no node with two parents, no cycle, and a
// scene lists only roots.
void checkNodeGraph(const Json& root, const Collections& n) {
    const Json& nodes = member(root, "nodes");
    std::vector<int> parent(nodes.size(), -1);
    for (std::size_t p = 0; p < nodes.size(); ++p) {
        const std::string where = cat("nodes[", p, "]");
        checkIndexArray(nodes[p], "children", n.nodes, where);
        checkIndex(nodes[p], "mesh", n.meshes, where);
        checkIndex(nodes[p], "camera", n.cameras, where);
        checkIndex(nodes[p], "skin", n.skins, where);
        const Json& children = member(nodes[p], "children");
        for (std::size_t k = 0; k < children.size(); ++k) {
            const int c = children[k].get<int>();
            if (std::size_t(c) == p) fail(where, ".children[", k, "]: node ", p, " is its own child");
            if (parent[c] == int(p)) fail(where, ".children: node ", c, " is listed twice");
            if (parent[c] >= 0) fail("node ", c, " has two parents: node ", parent[c], " and node ", p);
            parent[c] = int(p);
        }
    }
    // Walk up from every node; meeting a node already seen on the same walk closes a cycle.
    std::vector<int> walk(nodes.size(), -1);
    for (int start = 0; start < int(nodes.size()); ++start) {
        int x = start;
        while (x >= 0 && walk[x] < 0) {
            walk[x] = start;
            x = parent[x];
        }
        if (x < 0 || walk[x] != start) continue;
        std::vector<int> cycle{x};
        for (int y = parent[x]; y != x; y = parent[y]) cycle.push_back(y);
        cycle.push_back(x);
        std::reverse(cycle.begin(), cycle.end());  // parent → child order
        std::string text;
        for (int c : cycle) text += cat(text.empty() ? "" : " -> ", c);
        fail("nodes form a cycle: ", text);
    }
    std::vector<int> listedBy(nodes.size(), -1);  // last scene that listed the node as a root
    forEach(root, "scenes", "", [&](const Json& scene, std::size_t s, const std::string& where) {
        checkIndexArray(scene, "nodes", n.nodes, where);
        const Json& roots = member(scene, "nodes");
        for (std::size_t k = 0; k < roots.size(); ++k) {
            const int r = roots[k].get<int>();
            if (parent[r] >= 0)
                fail(where, ".nodes[", k, "]: node ", r, " is not a root, it is a child of node ", parent[r]);
            if (listedBy[r] == int(s)) fail(where, ".nodes: node ", r, " is listed twice");
            listedBy[r] = int(s);
        }
    });
    if (root.contains("scene")) checkIndexValue(root["scene"], n.scenes, "scene");
}

void checkCameras(const Json& root) {
    auto number = [](const Json& object, const char* key) { return object[key].get<double>(); };
    forEach(root, "cameras", "", [&](const Json& camera, std::size_t, const std::string& where) {
        const std::string& type = camera["type"].get_ref<const std::string&>();
        if (!camera.contains(type)) fail(where, ": type ", type, " but no '", type, "' object");
        const Json& p = camera[type];
        const std::string at = child(where, type);
        if (type == "perspective") {
            if (!(number(p, "yfov") > 0)) fail(child(at, "yfov"), ": must be > 0, got ", p["yfov"].dump());
            if (!(number(p, "znear") > 0)) fail(child(at, "znear"), ": must be > 0, got ", p["znear"].dump());
            if (p.contains("aspectRatio") && !(number(p, "aspectRatio") > 0))
                fail(child(at, "aspectRatio"), ": must be > 0, got ", p["aspectRatio"].dump());
            if (p.contains("zfar") && !(number(p, "zfar") > number(p, "znear")))
                fail(child(at, "zfar"), ": must be greater than znear ", p["znear"].dump(), ", got ", p["zfar"].dump());
        } else {
            if (number(p, "xmag") == 0) fail(child(at, "xmag"), ": must not be 0");
            if (number(p, "ymag") == 0) fail(child(at, "ymag"), ": must not be 0");
            if (!(number(p, "znear") >= 0)) fail(child(at, "znear"), ": must be >= 0, got ", p["znear"].dump());
            if (!(number(p, "zfar") > number(p, "znear")))
                fail(child(at, "zfar"), ": must be greater than znear ", p["znear"].dump(), ", got ", p["zfar"].dump());
        }
    });
}

void checkStructure(const Json& root) {
    const Collections n(root);
    checkAsset(root["asset"]);
    checkMeshReferences(root, n);
    checkMaterialReferences(root, n);
    checkAnimationReferences(root, n);
    checkNodeGraph(root, n);
    checkCameras(root);
}

std::string percentDecode(std::string_view uri) {
    auto hex = [](char c) -> int {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        if (c >= 'A' && c <= 'F') return c - 'A' + 10;
        return -1;
    };
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 && hex(uri[i + 2]) >= 0) {
            out += char(hex(uri[i + 1]) * 16 + hex(uri[i + 2]));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

// Checked before tinygltf runs, for messages that say which buffer and by how much; tinygltf then
// finds every buffer with exactly its byteLength.
void checkBuffers(const Json& root, const std::filesystem::path& dir, const GlbParts* glb) {
    forEach(root, "buffers", "", [&](const Json& buffer, std::size_t i, const std::string& where) {
        const std::uint64_t byteLength = buffer["byteLength"].get<std::uint64_t>();
        if (byteLength == 0) fail(child(where, "byteLength"), ": must be at least 1");
        if (!buffer.contains("uri")) {
            if (!glb || i != 0) fail(where, ": no uri (only buffer 0 of a .glb may use the BIN chunk)");
            if (!glb->hasBin) fail(where, ": no uri and the .glb has no BIN chunk");
            if (byteLength > glb->bin.size())
                fail(where, ": byteLength ", byteLength, " exceeds the GLB BIN chunk (", glb->bin.size(), " bytes)");
            return;
        }
        const std::string& uri = buffer["uri"].get_ref<const std::string&>();
        const std::string uriWhere = child(where, "uri");
        if (uri.rfind("data:", 0) == 0) {
            std::vector<unsigned char> data;
            std::string mime;
            if (!tinygltf::DecodeDataURI(&data, mime, uri, 0, false) || data.empty())
                fail(uriWhere,
                     ": cannot decode the data URI (frugal reads base64 application/octet-stream or "
                     "application/gltf-buffer)");
            if (data.size() != byteLength)
                fail(uriWhere, ": the data URI holds ", data.size(), " bytes, byteLength says ", byteLength);
            return;
        }
        const std::filesystem::path file = dir / percentDecode(uri);
        std::error_code ec;
        if (!std::filesystem::is_regular_file(file, ec)) fail(uriWhere, ": no such file '", oneLine(uri, 80), "'");
        const std::uintmax_t size = std::filesystem::file_size(file, ec);
        if (ec) fail(uriWhere, ": cannot read '", oneLine(uri, 80), "' (", ec.message(), ")");
        if (size != byteLength)
            fail(uriWhere, ": '", oneLine(uri, 80), "' has ", size, " bytes, byteLength says ", byteLength);
    });
}

// ---------------------------------------------------------------------------------------------
// tinygltf, with image decoding deferred: it would otherwise decode every image (normal maps we do
// not draw included) and, for images in a bufferView, hand the decoder an unchecked byte range.
// URI images keep their encoded bytes; bufferView images are read once their range is validated.

bool keepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
    if (image->bufferView < 0 && bytes != nullptr && size > 0) image->image.assign(bytes, bytes + size);
    return true;
}

tinygltf::Model runTinygltf(std::string_view data, bool binary, const std::string& baseDir) {
    if (data.size() > std::numeric_limits<unsigned int>::max()) fail("files of 4 GiB or more are not supported");
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(&keepEncodedImage, nullptr);
    tinygltf::Model model;
    std::string error, warning;
    const auto size = static_cast<unsigned int>(data.size());
    const bool ok =
        binary ? loader.LoadBinaryFromMemory(&model, &error, &warning,
                                             reinterpret_cast<const unsigned char*>(data.data()), size, baseDir)
               : loader.LoadASCIIFromString(&model, &error, &warning, data.data(), size, baseDir);
    // Its warnings are about images it could not load; the converter reports those that matter.
    if (!ok) fail("tinygltf: ", oneLine(error.empty() ? "unknown error" : error));
    return model;
}

// ---------------------------------------------------------------------------------------------
// 4. Data and conversion to the frugal Scene.

int componentSize(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return 4;
        default:
            return 0;  // excluded by the schema check
    }
}

const char* typeName(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return "SCALAR";
        case TINYGLTF_TYPE_VEC2:
            return "VEC2";
        case TINYGLTF_TYPE_VEC3:
            return "VEC3";
        case TINYGLTF_TYPE_VEC4:
            return "VEC4";
        case TINYGLTF_TYPE_MAT2:
            return "MAT2";
        case TINYGLTF_TYPE_MAT3:
            return "MAT3";
        case TINYGLTF_TYPE_MAT4:
            return "MAT4";
        default:
            return "?";
    }
}

const char* componentTypeName(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
            return "BYTE";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return "UNSIGNED_BYTE";
        case TINYGLTF_COMPONENT_TYPE_SHORT:
            return "SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return "UNSIGNED_SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            return "UNSIGNED_INT";
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return "FLOAT";
        default:
            return "?";
    }
}

const char* modeName(int mode) {
    switch (mode) {
        case TINYGLTF_MODE_POINTS:
            return "POINTS";
        case TINYGLTF_MODE_LINE:
            return "LINES";
        case TINYGLTF_MODE_LINE_LOOP:
            return "LINE_LOOP";
        case TINYGLTF_MODE_LINE_STRIP:
            return "LINE_STRIP";
        case TINYGLTF_MODE_TRIANGLES:
            return "TRIANGLES";
        case TINYGLTF_MODE_TRIANGLE_STRIP:
            return "TRIANGLE_STRIP";
        case TINYGLTF_MODE_TRIANGLE_FAN:
            return "TRIANGLE_FAN";
        default:
            return "?";
    }
}

// Component decoding; normalised integers follow the glTF 2.0 formulas (signed: max(c / MAX, -1)).
// memcpy because glTF only promises alignment to the component size within the buffer.
template <class T>
T load(const unsigned char* p) {
    T v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

float decodeFloat(const unsigned char* p, int componentType, bool normalized) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const float v = load<std::int8_t>(p);
            return normalized ? std::max(v / 127.0f, -1.0f) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            const float v = load<std::uint8_t>(p);
            return normalized ? v / 255.0f : v;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            const float v = load<std::int16_t>(p);
            return normalized ? std::max(v / 32767.0f, -1.0f) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            const float v = load<std::uint16_t>(p);
            return normalized ? v / 65535.0f : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            const auto v = static_cast<float>(load<std::uint32_t>(p));
            return normalized ? v / 4294967295.0f : v;
        }
        default:
            return load<float>(p);
    }
}

std::uint32_t decodeUint(const unsigned char* p, int componentType, bool) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return load<std::uint8_t>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return load<std::uint16_t>(p);
        default:
            return load<std::uint32_t>(p);
    }
}

bool addOverflows(std::size_t a, std::size_t b, std::size_t& out) { return __builtin_add_overflow(a, b, &out); }
bool mulOverflows(std::size_t a, std::size_t b, std::size_t& out) { return __builtin_mul_overflow(a, b, &out); }

// An accessor without a bufferView is all zeros (plus sparse values): its size is not bounded by the
// file, so bound it here.
constexpr std::size_t kMaxUnbackedComponents = std::size_t(1) << 26;

struct AccessorRequest {
    std::span<const int> types;           // allowed accessor types
    std::span<const int> componentTypes;  // allowed component types, empty = any
};

// What one file may make the loader build. A small file can make a large scene: many primitives
// can read one large accessor, many nodes can instance one large mesh.
constexpr std::size_t kMaxSceneElements = std::size_t(1) << 28;  // vertices + indices over all meshes
constexpr std::size_t kMaxInstances = std::size_t(1) << 24;

class Converter {
public:
    Converter(const tinygltf::Model& model, const std::string& path, const LoadOptions& options,
              std::vector<std::string> extensions)
        : model_(model), path_(path), options_(options), extensions_(std::move(extensions)) {}

    Scene run();

private:
    const tinygltf::Model& model_;
    const std::string& path_;
    const LoadOptions& options_;
    std::vector<std::string> extensions_;
    Scene scene_;
    std::vector<std::vector<int>> meshPrimitives_;  // glTF mesh → indices into scene_.meshes
    std::vector<bool> materialUsed_;
    std::map<int, int> textures_;         // glTF texture → index into scene_.textures, -1 = unusable
    std::vector<std::uint64_t> idCount_;  // per scene_ mesh: the triangle ids one instance of it takes
    std::size_t elements_ = 0;            // vertices + indices read so far
    std::size_t instances_ = 0;
    std::uint64_t ids_ = 0;
    std::vector<int> untextured_;  // scene_ meshes whose material's texture has no coordinates in them

    void report(const std::string& feature) {
        if (std::find(scene_.unsupported.begin(), scene_.unsupported.end(), feature) == scene_.unsupported.end())
            scene_.unsupported.push_back(feature);
    }
    void warn(const std::string& text) { scene_.warnings.push_back(cat(path_, ": ", text)); }
    void countElements(std::size_t count, const std::string& where) {
        elements_ += count;  // each count is bounded by the file size: no overflow
        if (elements_ > kMaxSceneElements)
            fail(where, ": the meshes need more than ", kMaxSceneElements, " vertices and indices, frugal's limit");
    }

    void checkBufferViews() const;
    std::vector<int> chooseRoots() const;
    Node convertNode(int index) const;
    void convertNodes();
    void convertMesh(int index);
    void convertPrimitive(int meshIndex, int primitiveIndex);
    void readAttributes(const tinygltf::Primitive& primitive, const std::string& where, Mesh& mesh);
    std::vector<std::uint32_t> readVertexList(const tinygltf::Primitive& primitive, const std::string& where,
                                              std::size_t vertexCount);
    void convertMaterials();
    void untextureMeshesWithoutUvs();
    int useTexture(int gltfTexture, int material);
    void convertAnimations();
    void addCamera(int node);

    template <class T, class Decode>
    std::vector<T> read(int accessor, const std::string& use, AccessorRequest request, Decode decode,
                        int* components = nullptr) const;
    std::vector<float> readFloats(int accessor, const std::string& use, std::span<const int> types,
                                  int* components = nullptr, std::span<const int> componentTypes = {}) const {
        return read<float>(accessor, use, {types, componentTypes}, decodeFloat, components);
    }
    std::vector<std::uint32_t> readIndices(int accessor, const std::string& use) const;
};

void Converter::checkBufferViews() const {
    for (std::size_t i = 0; i < model_.bufferViews.size(); ++i) {
        const tinygltf::BufferView& view = model_.bufferViews[i];
        const std::size_t bufferSize = model_.buffers[std::size_t(view.buffer)].data.size();
        std::size_t end = 0;
        if (view.byteLength == 0) fail("bufferViews[", i, "].byteLength: must be at least 1");
        if (addOverflows(view.byteOffset, view.byteLength, end) || end > bufferSize)
            fail("bufferViews[", i, "]: byteOffset ", view.byteOffset, " + byteLength ", view.byteLength,
                 " is beyond the end of buffer ", view.buffer, " (", bufferSize, " bytes)");
    }
}

template <class T, class Decode>
std::vector<T> Converter::read(int index, const std::string& use, AccessorRequest request, Decode decode,
                               int* componentsOut) const {
    const tinygltf::Accessor& a = model_.accessors[std::size_t(index)];
    const std::string label = cat("accessor ", index, " (", use, ")");
    if (std::find(request.types.begin(), request.types.end(), a.type) == request.types.end()) {
        std::string allowed;
        for (int t : request.types) allowed += cat(allowed.empty() ? "" : " or ", typeName(t));
        fail(label, ": type ", typeName(a.type), ", expected ", allowed);
    }
    if (!request.componentTypes.empty() && std::find(request.componentTypes.begin(), request.componentTypes.end(),
                                                     a.componentType) == request.componentTypes.end())
        fail(label, ": component type ", componentTypeName(a.componentType), " is not allowed here");
    if (a.count == 0) fail(label, ": count must be at least 1");
    const int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
    const std::size_t size = std::size_t(componentSize(a.componentType)) * std::size_t(components);
    if (componentsOut) *componentsOut = components;

    std::size_t total = 0;
    if (mulOverflows(a.count, std::size_t(components), total) || (a.bufferView < 0 && total > kMaxUnbackedComponents))
        fail(label, ": count ", a.count, " is too large");

    std::vector<T> values;
    if (a.bufferView < 0) {
        values.assign(total, T(0));
    } else {
        const tinygltf::BufferView& view = model_.bufferViews[std::size_t(a.bufferView)];
        const std::size_t stride = view.byteStride != 0 ? view.byteStride : size;
        if (stride < size)
            fail(label, ": bufferView ", a.bufferView, " byteStride ", stride, " is smaller than the ", size,
                 "-byte element");
        std::size_t span = 0, need = 0;
        if (mulOverflows(a.count - 1, stride, span) || addOverflows(span, size, need) ||
            addOverflows(need, a.byteOffset, need))
            fail(label, ": count ", a.count, " x stride ", stride, " overflows");
        if (need > view.byteLength)
            fail(label, ": ", a.count, " elements of ", size, " bytes (stride ", stride, ") from byteOffset ",
                 a.byteOffset, " need ", need, " bytes, bufferView ", a.bufferView, " has ", view.byteLength);
        const unsigned char* base =
            model_.buffers[std::size_t(view.buffer)].data.data() + view.byteOffset + a.byteOffset;
        const std::size_t componentBytes = std::size_t(componentSize(a.componentType));
        values.resize(total);
        for (std::size_t e = 0; e < a.count; ++e)
            for (int c = 0; c < components; ++c)
                values[e * std::size_t(components) + std::size_t(c)] =
                    decode(base + e * stride + std::size_t(c) * componentBytes, a.componentType, a.normalized);
    }

    if (!a.sparse.isSparse) return values;
    // Sparse: the listed elements replace those of the base (or of the zeros).
    const auto& sparse = a.sparse;
    const std::size_t count = std::size_t(sparse.count);
    if (count < 1 || count > a.count) fail(label, ": sparse count ", sparse.count, " outside [1, ", a.count, "]");
    auto sparseRange = [&](int viewIndex, int byteOffset, std::size_t elementSize, const char* what) {
        const tinygltf::BufferView& view = model_.bufferViews[std::size_t(viewIndex)];
        const std::size_t need = std::size_t(byteOffset) + count * elementSize;  // small: count ≤ a.count
        if (need > view.byteLength)
            fail(label, ": sparse ", what, " need ", need, " bytes, bufferView ", viewIndex, " has ", view.byteLength);
        return model_.buffers[std::size_t(view.buffer)].data.data() + view.byteOffset + std::size_t(byteOffset);
    };
    const int indexType = sparse.indices.componentType;
    const std::size_t indexSize = std::size_t(componentSize(indexType));
    const unsigned char* indices =
        sparseRange(sparse.indices.bufferView, sparse.indices.byteOffset, indexSize, "indices");
    const unsigned char* replacements = sparseRange(sparse.values.bufferView, sparse.values.byteOffset, size, "values");
    const std::size_t componentBytes = std::size_t(componentSize(a.componentType));
    std::int64_t previous = -1;
    for (std::size_t s = 0; s < count; ++s) {
        const std::uint32_t target = decodeUint(indices + s * indexSize, indexType, false);
        if (target >= a.count)
            fail(label, ": sparse index ", target, " out of range, the accessor has ", a.count, " elements");
        if (std::int64_t(target) <= previous)
            fail(label, ": sparse indices must increase, ", target, " follows ", previous);
        previous = target;
        for (int c = 0; c < components; ++c)
            values[target * std::size_t(components) + std::size_t(c)] =
                decode(replacements + s * size + std::size_t(c) * componentBytes, a.componentType, a.normalized);
    }
    return values;
}

std::vector<std::uint32_t> Converter::readIndices(int accessor, const std::string& use) const {
    static constexpr int kScalar[] = {TINYGLTF_TYPE_SCALAR};
    static constexpr int kIndexTypes[] = {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                          TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT};
    return read<std::uint32_t>(accessor, use, {kScalar, kIndexTypes}, decodeUint);
}

std::vector<int> Converter::chooseRoots() const {
    if (model_.defaultScene >= 0) return model_.scenes[std::size_t(model_.defaultScene)].nodes;
    if (!model_.scenes.empty()) return model_.scenes[0].nodes;
    std::vector<bool> isChild(model_.nodes.size(), false);
    for (const tinygltf::Node& node : model_.nodes)
        for (int c : node.children) isChild[std::size_t(c)] = true;
    std::vector<int> roots;
    for (int n = 0; n < int(model_.nodes.size()); ++n)
        if (!isChild[std::size_t(n)]) roots.push_back(n);
    return roots;
}

float toFloat(double value, const std::string& where) {
    const auto f = static_cast<float>(value);
    if (!std::isfinite(f)) fail(where, ": ", value, " does not fit a float");
    return f;
}

Node Converter::convertNode(int index) const {
    const tinygltf::Node& src = model_.nodes[std::size_t(index)];
    const std::string where = cat("nodes[", index, "]");
    Node node;
    node.name = src.name;
    node.children = src.children;
    if (!src.matrix.empty()) {
        node.hasMatrix = true;
        for (int k = 0; k < 16; ++k)
            glm::value_ptr(node.matrix)[k] = toFloat(src.matrix[std::size_t(k)], cat(where, ".matrix[", k, "]"));
    }
    if (!src.translation.empty())
        for (int k = 0; k < 3; ++k)
            node.translation[k] = toFloat(src.translation[std::size_t(k)], cat(where, ".translation[", k, "]"));
    if (!src.scale.empty())
        for (int k = 0; k < 3; ++k) node.scale[k] = toFloat(src.scale[std::size_t(k)], cat(where, ".scale[", k, "]"));
    if (!src.rotation.empty()) {
        glm::vec4 q;
        for (int k = 0; k < 4; ++k) q[k] = toFloat(src.rotation[std::size_t(k)], cat(where, ".rotation[", k, "]"));
        const float length = glm::length(q);
        if (!(length > 0.0f) || !std::isfinite(length))
            fail(where, ".rotation: not a unit quaternion (length ", length, ")");
        q /= length;  // exporters write slightly denormalised quaternions
        node.rotation = glm::quat(q.w, q.x, q.y, q.z);
    }
    return node;
}

void Converter::convertNodes() {
    scene_.nodes.resize(model_.nodes.size());
    for (int n = 0; n < int(model_.nodes.size()); ++n) scene_.nodes[std::size_t(n)] = convertNode(n);
    for (int n = 0; n < int(model_.nodes.size()); ++n)
        for (int c : scene_.nodes[std::size_t(n)].children) scene_.nodes[std::size_t(c)].parent = n;

    scene_.roots = chooseRoots();
    meshPrimitives_.assign(model_.meshes.size(), {});
    materialUsed_.assign(model_.materials.size(), false);
    // The nodes of the chosen scene: walk down from its roots (the hierarchy is a forest, checked).
    std::vector<bool> inScene(model_.nodes.size(), false);
    std::vector<bool> meshUsed(model_.meshes.size(), false);
    std::vector<int> stack = scene_.roots;
    while (!stack.empty()) {
        const tinygltf::Node& src = model_.nodes[std::size_t(stack.back())];
        inScene[std::size_t(stack.back())] = true;
        stack.pop_back();
        if (src.mesh >= 0) meshUsed[std::size_t(src.mesh)] = true;
        stack.insert(stack.end(), src.children.begin(), src.children.end());
    }
    // Meshes in file order, then what the nodes refer to in node order: stable whatever the hierarchy.
    for (int m = 0; m < int(model_.meshes.size()); ++m)
        if (meshUsed[std::size_t(m)]) convertMesh(m);
    for (int n = 0; n < int(model_.nodes.size()); ++n) {
        if (!inScene[std::size_t(n)]) continue;
        const tinygltf::Node& src = model_.nodes[std::size_t(n)];
        if (src.mesh >= 0) {
            const std::vector<int>& meshes = meshPrimitives_[std::size_t(src.mesh)];
            instances_ += meshes.size();
            for (int m : meshes) ids_ += idCount_[std::size_t(m)];
            if (instances_ > kMaxInstances)
                fail("the scene has more than ", kMaxInstances, " mesh instances, frugal's limit");
            // Global triangle ids are 32-bit and 0 is the background.
            if (ids_ > std::numeric_limits<std::uint32_t>::max() - 1u)
                fail("the scene instances more than ", std::numeric_limits<std::uint32_t>::max() - 1u,
                     " triangles, more than 32-bit triangle ids can number");
            scene_.nodes[std::size_t(n)].meshes = meshes;
        }
        if (src.camera >= 0) addCamera(n);
        if (src.skin >= 0) report("skins");
    }
}

void Converter::addCamera(int node) {
    const tinygltf::Camera& src = model_.cameras[std::size_t(model_.nodes[std::size_t(node)].camera)];
    const std::string where = cat("cameras[", model_.nodes[std::size_t(node)].camera, "]");
    Camera camera;
    camera.name = src.name;
    camera.node = node;
    if (src.type == "perspective") {
        camera.perspective = true;
        camera.yfov = toFloat(src.perspective.yfov, where + ".perspective.yfov");
        camera.aspect = toFloat(src.perspective.aspectRatio, where + ".perspective.aspectRatio");
        camera.znear = toFloat(src.perspective.znear, where + ".perspective.znear");
        camera.zfar = toFloat(src.perspective.zfar, where + ".perspective.zfar");
    } else {
        camera.perspective = false;
        camera.xmag = toFloat(src.orthographic.xmag, where + ".orthographic.xmag");
        camera.ymag = toFloat(src.orthographic.ymag, where + ".orthographic.ymag");
        camera.znear = toFloat(src.orthographic.znear, where + ".orthographic.znear");
        camera.zfar = toFloat(src.orthographic.zfar, where + ".orthographic.zfar");
    }
    scene_.nodes[std::size_t(node)].camera = int(scene_.cameras.size());
    scene_.cameras.push_back(camera);
}

void Converter::convertMesh(int index) {
    const tinygltf::Mesh& mesh = model_.meshes[std::size_t(index)];
    for (int p = 0; p < int(mesh.primitives.size()); ++p) convertPrimitive(index, p);
}

// The triangles of a primitive, as indices into its vertex list, with glTF's winding rules
// (spec, "Topology types"): strip triangle i = (v_i, v_{i+1+i%2}, v_{i+2-i%2}), fan triangle i = (v_{i+1},
// v_{i+2}, v_0). Triangle i of a strip or fan is emitted at position i, so triangleSource stays the
// identity that finalizeMesh fills in.
std::vector<std::uint32_t> triangulate(const std::vector<std::uint32_t>& v, int mode, const std::string& where) {
    std::vector<std::uint32_t> out;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (v.size() % 3 != 0) fail(where, ": TRIANGLES with ", v.size(), " vertices, which is not a multiple of 3");
        return v;
    }
    if (v.size() < 3) return out;
    const std::size_t n = v.size() - 2;
    out.reserve(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            const std::size_t odd = i % 2;
            out.insert(out.end(), {v[i], v[i + 1 + odd], v[i + 2 - odd]});
        } else {
            out.insert(out.end(), {v[i + 1], v[i + 2], v[0]});
        }
    }
    return out;
}

int attributeAccessor(const tinygltf::Primitive& primitive, const std::string& name) {
    const auto it = primitive.attributes.find(name);
    return it == primitive.attributes.end() ? -1 : it->second;
}

// glm vectors are tightly packed floats, so an accessor read as floats copies straight in.
template <class Vec>
std::vector<Vec> toVectors(const std::vector<float>& values) {
    std::vector<Vec> out(values.size() / Vec::length());
    std::memcpy(out.data(), values.data(), out.size() * sizeof(Vec));
    return out;
}

void Converter::readAttributes(const tinygltf::Primitive& primitive, const std::string& where, Mesh& mesh) {
    static constexpr int kVec2[] = {TINYGLTF_TYPE_VEC2};
    static constexpr int kVec3[] = {TINYGLTF_TYPE_VEC3};
    static constexpr int kVec34[] = {TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4};
    mesh.positions =
        toVectors<glm::vec3>(readFloats(attributeAccessor(primitive, "POSITION"), "POSITION of " + where, kVec3));
    const std::size_t vertexCount = mesh.positions.size();
    countElements(vertexCount, where);
    auto accessor = [&](const std::string& name) {
        const int index = attributeAccessor(primitive, name);
        if (index >= 0 && model_.accessors[std::size_t(index)].count != vertexCount)
            fail("accessor ", index, " (", name, " of ", where, "): ", model_.accessors[std::size_t(index)].count,
                 " elements, POSITION has ", vertexCount);
        return index;
    };

    if (const int normal = accessor("NORMAL"); normal >= 0)
        mesh.normals = toVectors<glm::vec3>(readFloats(normal, "NORMAL of " + where, kVec3));
    if (const int color = accessor("COLOR_0"); color >= 0) {
        int components = 0;
        const std::vector<float> colors = readFloats(color, "COLOR_0 of " + where, kVec34, &components);
        mesh.colors.assign(vertexCount, glm::vec4(1.0f));  // RGB colours get alpha 1
        for (std::size_t v = 0; v < vertexCount; ++v)
            for (int c = 0; c < components; ++c)
                mesh.colors[v][c] = colors[v * std::size_t(components) + std::size_t(c)];
    }
    // The one set of texture coordinates frugal keeps is the one the base colour texture samples.
    const tinygltf::TextureInfo* texture =
        primitive.material >= 0
            ? &model_.materials[std::size_t(primitive.material)].pbrMetallicRoughness.baseColorTexture
            : nullptr;
    const bool textured = texture && texture->index >= 0;
    const std::string uvName = cat("TEXCOORD_", textured ? texture->texCoord : 0);
    if (const int uv = accessor(uvName); uv >= 0) {
        mesh.uvs = toVectors<glm::vec2>(readFloats(uv, uvName + " of " + where, kVec2));
    } else if (textured) {
        warn(cat(where, ": material ", primitive.material, " samples its base colour texture with ", uvName,
                 ", which the primitive lacks: drawn untextured"));
        untextured_.push_back(int(scene_.meshes.size()));  // the index this mesh will get
    }
}

// The primitive's vertex list: its indices, checked against the vertex count, or 0..n-1.
std::vector<std::uint32_t> Converter::readVertexList(const tinygltf::Primitive& primitive, const std::string& where,
                                                     std::size_t vertexCount) {
    std::vector<std::uint32_t> vertices;
    if (primitive.indices < 0) {
        vertices.resize(vertexCount);
        for (std::size_t v = 0; v < vertexCount; ++v) vertices[v] = std::uint32_t(v);
        return vertices;
    }
    vertices = readIndices(primitive.indices, "indices of " + where);
    countElements(vertices.size(), where);
    for (std::uint32_t index : vertices)
        if (index >= vertexCount)
            fail("accessor ", primitive.indices, " (indices of ", where, "): index ", index, " out of range, mesh has ",
                 vertexCount, " vertices");
    return vertices;
}

void Converter::convertPrimitive(int meshIndex, int primitiveIndex) {
    const tinygltf::Mesh& gltfMesh = model_.meshes[std::size_t(meshIndex)];
    const tinygltf::Primitive& primitive = gltfMesh.primitives[std::size_t(primitiveIndex)];
    const std::string where = cat("mesh ", meshIndex, " primitive ", primitiveIndex);
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode < TINYGLTF_MODE_TRIANGLES) {
        report(cat("primitive mode ", modeName(mode)));
        return;
    }
    if (!primitive.targets.empty()) report("morph targets");
    if (attributeAccessor(primitive, "POSITION") < 0) {
        warn(cat(where, ": no POSITION attribute, not drawn"));
        return;
    }

    Mesh mesh;
    mesh.name = gltfMesh.name.empty() ? cat("mesh ", meshIndex) : gltfMesh.name;
    if (gltfMesh.primitives.size() > 1) mesh.name += cat(" #", primitiveIndex);
    mesh.material = primitive.material;
    if (primitive.material >= 0) materialUsed_[std::size_t(primitive.material)] = true;
    readAttributes(primitive, where, mesh);
    mesh.indices = triangulate(readVertexList(primitive, where, mesh.positions.size()), mode, where);

    const MeshBuildStats stats = finalizeMesh(mesh, options_.optimizeOrder);
    if (stats.droppedNonFinite > 0) {
        const std::string name =
            gltfMesh.name.empty() ? cat("mesh ", meshIndex) : cat("mesh '", oneLine(gltfMesh.name, 60), "'");
        warn(cat(name, " primitive ", primitiveIndex, ": dropped ", stats.droppedNonFinite,
                 " triangles with non-finite positions"));
    }
    const auto& source = mesh.triangleSource;
    idCount_.push_back(source.empty() ? 0 : std::uint64_t(*std::max_element(source.begin(), source.end())) + 1);
    meshPrimitives_[std::size_t(meshIndex)].push_back(int(scene_.meshes.size()));
    scene_.meshes.push_back(std::move(mesh));
}

// 16-bit channels are rounded to 8 bits; grey and grey+alpha are expanded to RGBA.
bool toRgba8(const tinygltf::Image& image, std::vector<std::uint8_t>& rgba) {
    const int channels = image.component;
    const int bytesPerChannel = image.bits == 16 ? 2 : 1;
    if (channels < 1 || channels > 4 || image.width < 1 || image.height < 1 || (image.bits != 8 && image.bits != 16))
        return false;
    const std::size_t pixels = std::size_t(image.width) * std::size_t(image.height);
    if (image.image.size() != pixels * std::size_t(channels * bytesPerChannel)) return false;
    rgba.resize(pixels * 4);
    auto channel = [&](std::size_t pixel, int c) -> std::uint8_t {
        const std::size_t at = (pixel * std::size_t(channels) + std::size_t(c)) * std::size_t(bytesPerChannel);
        if (bytesPerChannel == 1) return image.image[at];
        const unsigned v = load<std::uint16_t>(&image.image[at]);  // stb returns host-order shorts
        return std::uint8_t((v * 255u + 32767u) / 65535u);
    };
    for (std::size_t p = 0; p < pixels; ++p) {
        std::uint8_t* out = &rgba[p * 4];
        if (channels <= 2) {
            out[0] = out[1] = out[2] = channel(p, 0);
            out[3] = channels == 2 ? channel(p, 1) : 255;
        } else {
            for (int c = 0; c < 3; ++c) out[c] = channel(p, c);
            out[3] = channels == 4 ? channel(p, 3) : 255;
        }
    }
    return true;
}

Wrap toWrap(int wrap) {
    switch (wrap) {
        case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
            return Wrap::ClampToEdge;
        case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
            return Wrap::MirroredRepeat;
        default:
            return Wrap::Repeat;
    }
}

int Converter::useTexture(int gltfTexture, int material) {
    if (const auto it = textures_.find(gltfTexture); it != textures_.end()) return it->second;
    int& result = textures_[gltfTexture];
    result = -1;
    const tinygltf::Texture& texture = model_.textures[std::size_t(gltfTexture)];
    const std::string drawn = cat(": material ", material, " drawn without its base colour texture");
    if (texture.source < 0) {
        warn(cat("texture ", gltfTexture, " has no image frugal can read", drawn));
        return result;
    }
    const tinygltf::Image& image = model_.images[std::size_t(texture.source)];
    const std::string imageName = image.uri.empty() || image.uri.rfind("data:", 0) == 0
                                      ? cat("image ", texture.source)
                                      : cat("image ", texture.source, " ('", oneLine(image.uri, 80), "')");
    const unsigned char* bytes = image.image.data();
    std::size_t size = image.image.size();
    if (image.bufferView >= 0) {
        const tinygltf::BufferView& view = model_.bufferViews[std::size_t(image.bufferView)];
        bytes = model_.buffers[std::size_t(view.buffer)].data.data() + view.byteOffset;
        size = view.byteLength;
    }
    if (size == 0) {
        warn(cat(imageName, " could not be read", drawn));
        return result;
    }
    if (size > std::size_t(INT_MAX)) {
        warn(cat(imageName, " is larger than 2 GiB", drawn));
        return result;
    }
    tinygltf::Image decoded;
    std::string error, warning;
    if (!tinygltf::LoadImageData(&decoded, texture.source, &error, &warning, 0, 0, bytes, int(size), nullptr)) {
        warn(cat(imageName, " cannot be decoded (", oneLine(error, 120), ")", drawn));
        return result;
    }
    Texture out;
    out.name = !texture.name.empty()              ? texture.name
               : !image.name.empty()              ? image.name
               : image.uri.rfind("data:", 0) == 0 ? std::string()
                                                  : image.uri;
    out.width = decoded.width;
    out.height = decoded.height;
    if (!toRgba8(decoded, out.rgba)) {
        warn(cat(imageName, " decoded to an unexpected format (", decoded.component, " channels of ", decoded.bits,
                 " bits)", drawn));
        return result;
    }
    if (texture.sampler >= 0) {
        const tinygltf::Sampler& sampler = model_.samplers[std::size_t(texture.sampler)];
        out.wrapS = toWrap(sampler.wrapS);
        out.wrapT = toWrap(sampler.wrapT);
        // One filter for both directions: the magnification filter, else the base-level part of the
        // minification filter (NEAREST_MIPMAP_* samples the base level with NEAREST).
        const int filter = sampler.magFilter >= 0 ? sampler.magFilter : sampler.minFilter;
        out.filter =
            (filter == TINYGLTF_TEXTURE_FILTER_NEAREST || filter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST ||
             filter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR)
                ? Filter::Nearest
                : Filter::Linear;
        if (sampler.minFilter >= TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST)
            report("mipmaps (sampled base level only)");
    }
    result = int(scene_.textures.size());
    scene_.textures.push_back(std::move(out));
    return result;
}

void Converter::convertMaterials() {
    scene_.materials.resize(model_.materials.size());
    for (int m = 0; m < int(model_.materials.size()); ++m) {
        const tinygltf::Material& src = model_.materials[std::size_t(m)];
        const std::string where = cat("materials[", m, "]");
        Material& material = scene_.materials[std::size_t(m)];
        material.name = src.name;
        material.doubleSided = src.doubleSided;
        const std::vector<double>& factor = src.pbrMetallicRoughness.baseColorFactor;
        for (int k = 0; k < 4 && std::size_t(k) < factor.size(); ++k)
            material.baseColorFactor[k] =
                toFloat(factor[std::size_t(k)], cat(where, ".pbrMetallicRoughness.baseColorFactor[", k, "]"));
        // Features are reported, and textures decoded, only for materials the drawn meshes use.
        if (!materialUsed_[std::size_t(m)]) continue;
        if (src.alphaMode != "OPAQUE") report("alphaMode " + src.alphaMode);
        if (src.normalTexture.index >= 0) report("normalTexture");
        if (src.occlusionTexture.index >= 0) report("occlusionTexture");
        if (src.emissiveTexture.index >= 0) report("emissiveTexture");
        if (std::any_of(src.emissiveFactor.begin(), src.emissiveFactor.end(), [](double v) { return v != 0.0; }))
            report("emissiveFactor");
        if (src.pbrMetallicRoughness.baseColorTexture.index >= 0)
            material.baseColorTexture = useTexture(src.pbrMetallicRoughness.baseColorTexture.index, m);
    }
}

// A mesh without the texture coordinates its material's texture needs gets a copy of the material
// without the texture, so that a mesh with a textured material always has uvs.
void Converter::untextureMeshesWithoutUvs() {
    std::map<int, int> copies;  // material → its untextured copy
    for (int m : untextured_) {
        Mesh& mesh = scene_.meshes[std::size_t(m)];
        const auto [it, added] = copies.try_emplace(mesh.material, int(scene_.materials.size()));
        if (added) {
            Material copy = scene_.materials[std::size_t(mesh.material)];
            copy.name += " (untextured)";
            copy.baseColorTexture = -1;
            scene_.materials.push_back(copy);
        }
        mesh.material = it->second;
    }
}

void Converter::convertAnimations() {
    static constexpr int kScalar[] = {TINYGLTF_TYPE_SCALAR};
    static constexpr int kFloat[] = {TINYGLTF_COMPONENT_TYPE_FLOAT};
    static constexpr int kVec3[] = {TINYGLTF_TYPE_VEC3};
    static constexpr int kVec4[] = {TINYGLTF_TYPE_VEC4};
    for (int a = 0; a < int(model_.animations.size()); ++a) {
        const tinygltf::Animation& src = model_.animations[std::size_t(a)];
        Animation animation;
        animation.name = src.name;
        for (int c = 0; c < int(src.channels.size()); ++c) {
            const tinygltf::AnimationChannel& channel = src.channels[std::size_t(c)];
            if (channel.target_path == "weights") {
                report("morph target animation");
                continue;
            }
            if (channel.target_node < 0) continue;  // glTF: a channel without a node is ignored
            const int s = channel.sampler;
            const tinygltf::AnimationSampler& sampler = src.samplers[std::size_t(s)];
            const std::string where = cat("animation ", a, " sampler ", s);
            AnimChannel out;
            out.node = channel.target_node;
            out.path = channel.target_path == "translation" ? AnimPath::Translation
                       : channel.target_path == "rotation"  ? AnimPath::Rotation
                                                            : AnimPath::Scale;
            out.interpolation = sampler.interpolation == "STEP"          ? Interp::Step
                                : sampler.interpolation == "CUBICSPLINE" ? Interp::CubicSpline
                                                                         : Interp::Linear;
            out.times = readFloats(sampler.input, "input of " + where, kScalar, nullptr, kFloat);
            for (std::size_t k = 0; k < out.times.size(); ++k) {
                if (!std::isfinite(out.times[k])) fail(where, ": key time ", k, " is not finite");
                if (k > 0 && !(out.times[k] > out.times[k - 1]))
                    fail(where, ": key times must increase, time ", k, " (", out.times[k], ") follows ",
                         out.times[k - 1]);
            }
            const bool cubic = out.interpolation == Interp::CubicSpline;
            if (cubic && out.times.size() < 2)
                fail(where, ": CUBICSPLINE needs at least 2 keys, got ", out.times.size());
            const bool rotation = out.path == AnimPath::Rotation;
            int components = 0;
            const std::span<const int> outputTypes =
                rotation ? std::span<const int>(kVec4) : std::span<const int>(kVec3);
            const std::vector<float> values =
                readFloats(sampler.output, "output of " + where, outputTypes, &components);
            const std::size_t expected = out.times.size() * (cubic ? 3 : 1);
            const std::size_t count = values.size() / std::size_t(components);
            if (count != expected)
                fail(where, ": output has ", count, " elements, expected ", expected,
                     cubic ? " (3 per key, CUBICSPLINE)" : " (one per key)");
            out.values.resize(count, glm::vec4(0.0f));
            for (std::size_t k = 0; k < count; ++k)
                for (int i = 0; i < components; ++i) {
                    const float v = values[k * std::size_t(components) + std::size_t(i)];
                    if (!std::isfinite(v)) fail(where, ": output value ", k, " is not finite");
                    out.values[k][i] = v;
                }
            animation.channels.push_back(std::move(out));
        }
        scene_.animations.push_back(std::move(animation));
    }
}

Scene Converter::run() {
    scene_.source = path_;
    // KHR_mesh_quantization only widens the accessor types, which the readers above all accept.
    for (const std::string& name : extensions_)
        if (name != "KHR_mesh_quantization") report(oneLine(name, 80));
    checkBufferViews();
    convertNodes();
    convertMaterials();
    untextureMeshesWithoutUvs();
    convertAnimations();
    if (!model_.skins.empty()) report("skins");
    scene_.buildInstances();
    return std::move(scene_);
}

// A .glb, or any file that starts with the GLB magic, is read as binary glTF.
bool isBinary(const std::string& path, std::string_view bytes) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".glb" || (bytes.size() >= 4 && bytes.substr(0, 4) == "glTF");
}

Scene loadGltfOrThrow(const std::string& path, const LoadOptions& options) {
    const std::string file = readFile(path);
    if (file.empty()) fail("file is empty");
    const bool binary = isBinary(path, file);
    GlbParts glb;
    std::string_view jsonText = file;
    if (binary) {
        glb = splitGlb(file);
        jsonText = glb.json;
    }
    const Json root = parseJson(jsonText);
    checkObject(root, kRoot, "");
    checkStructure(root);
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    checkBuffers(root, dir, binary ? &glb : nullptr);

    std::vector<std::string> extensions;
    for (const char* key : {"extensionsUsed", "extensionsRequired"})
        for (const Json& name : member(root, key)) addUnique(extensions, name.get<std::string>());
    collectExtensions(root, extensions);

    const std::string repacked = binary && !glb.canonical ? canonicalGlb(glb) : std::string();
    const std::string_view forTinygltf = !binary         ? std::string_view(file)
                                         : glb.canonical ? std::string_view(file)
                                                         : std::string_view(repacked);
    const std::string baseDir = dir.empty() ? std::string(".") : dir.string();
    const tinygltf::Model model = runTinygltf(forTinygltf, binary, baseDir);
    return Converter(model, path, options, std::move(extensions)).run();
}

}  // namespace

Result<Scene> loadGltf(const std::string& path, const LoadOptions& options) {
    return load::guard(path, [&] { return loadGltfOrThrow(path, options); });
}

}  // namespace frugal
