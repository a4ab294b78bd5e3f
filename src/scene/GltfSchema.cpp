// The glTF 2.0 JSON schema, as far as the loader or tinygltf reads it. Properties not listed are
// allowed and ignored, as the spec allows. Every object may also carry "name" (string),
// "extensions" (an object of objects) and "extras" (anything).
#include "scene/GltfSchema.h"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace frugal::gltf {

namespace {

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

}  // namespace

void checkSchema(const Json& root) { checkObject(root, kRoot, ""); }

}  // namespace frugal::gltf
