// glTF 2.0 loader (.gltf and .glb) on top of tinygltf, the one file of the project that includes it.
//
// tinygltf (Debian 2.7) parses the JSON and loads buffers and images, but it accepts invalid files:
// it replaces wrong-typed fields by defaults, leaves most references unchecked, lets accessors run
// past their buffers, and its GLB reader trusts chunk lengths (it can read 8 bytes past the end).
// So loadGltf checks, in this order:
//   1. the container (GltfContainer.h): file readable, GLB header and chunks, JSON syntax and
//      nesting depth;
//   2. the raw JSON against the glTF 2.0 schema (GltfSchema.h);
//   3. the structure, still on the JSON (GltfStructure.h): indices, node forest, buffers, cameras,
//      and the compression extensions' objects (GltfCompression.h);
//   4. here, the data, while it is read from tinygltf's model: compressed geometry decoded first
//      (decompress: the model then reads as an uncompressed file), then bufferView and accessor
//      ranges, index values, animation key times and counts.
// A fatal problem becomes Error{"<path>: <what, where, with the numbers>"} on one line; no exception
// leaves loadGltf (GltfCheck.h says how). NaN/Inf positions are not fatal: finalizeMesh drops their
// triangles.
//
// Which scene is loaded: the file's default scene ("scene"), else scene 0, else (a file without
// scenes) every root node, so that a bare node list still renders. Nodes outside that scene are kept,
// so node indices match the file and animation targets stay valid, but they get no meshes and so
// no instances.
#include <algorithm>
#include <array>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "scene/GltfCheck.h"
#include "scene/GltfCompression.h"
#include "scene/GltfContainer.h"
#include "scene/GltfSchema.h"
#include "scene/GltfStructure.h"
#include "scene/ImageCheck.h"
#include "scene/LightCheck.h"
#include "scene/Load.h"
#include "scene/LoadSupport.h"
#include "scene/MeshBuild.h"

namespace frugal {

namespace gltf {
namespace {

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

// A texture reference's KHR_texture_transform: uv' = T · R · S · (u, v, 1) (the extension's
// matrices, computed in double and rounded to float), and the texture coordinate set it overrides
// texCoord with. Identity and the reference's own set without the extension.
struct TextureTransform {
    glm::mat3 matrix{1.0f};
    int texCoord = 0;
};

// A texture reference written inside an extension (tinygltf leaves those as JSON values).
struct ExtensionTexture {
    int index = -1, texCoord = 0;
    double scale = 1.0;  // a normal texture's
    tinygltf::ExtensionMap extensions;
};

// KHR_materials_pbrSpecularGlossiness as a material writes it (defaults where it does not).
struct SpecularGlossiness {
    bool present = false;
    glm::vec4 diffuse{1.0f};
    glm::vec3 specular{1.0f};
    float glossiness = 1.0f;
    ExtensionTexture diffuseTexture, specularGlossinessTexture;
};

// KHR_materials_clearcoat as a material writes it (defaults where it does not).
struct Clearcoat {
    float factor = 0.0f, roughness = 0.0f;
    ExtensionTexture texture, roughnessTexture, normalTexture;
};

// A material's textures as drawn: each map it has (base colour, metallic-roughness, occlusion,
// emissive, normal), sampled at one set of coordinates through one transform, the first map's. (frugal keeps
// one set of texture coordinates per mesh.) A map that asks for other coordinates is not drawn.
struct MaterialMaps {
    // Material's maps, in kMaterialMaps' order.
    enum Map {
        kBaseColor,
        kMetallicRoughness,
        kOcclusion,
        kEmissive,
        kNormal,
        kSpecularGlossiness,
        kClearcoat,
        kClearcoatRoughness,
        kClearcoatNormal,
        kMapCount
    };
    static constexpr const char* kNames[kMapCount] = {
        "base colour", "metallic-roughness",   "occlusion",        "emissive", "normal", "specular-glossiness",
        "clear-coat",  "clear-coat roughness", "clear-coat normal"};
    std::array<int, kMapCount> texture{-1, -1, -1, -1, -1, -1, -1, -1, -1};  // glTF texture, -1 = none or not drawn
    TextureTransform transform;  // the coordinates they share
    bool differing = false;      // a map was left out for its coordinates
    bool any() const { return std::any_of(texture.begin(), texture.end(), [](int t) { return t >= 0; }); }
};

class Converter {
public:
    Converter(const tinygltf::Model& model, const std::string& path, const LoadOptions& options,
              std::vector<std::string> extensions, std::vector<Decompression> decompressed)
        : model_(model), path_(path), options_(options), extensions_(std::move(extensions)) {
        scene_.decompressed = std::move(decompressed);
    }

    Scene run();

private:
    const tinygltf::Model& model_;
    const std::string& path_;
    const LoadOptions& options_;
    std::vector<std::string> extensions_;
    int lightNodes_ = 0;  // nodes of the scene that place a light
    Scene scene_;
    std::vector<std::vector<int>> meshPrimitives_;  // glTF mesh → indices into scene_.meshes
    std::vector<bool> materialUsed_;
    std::map<std::pair<int, bool>, int> textures_;  // (glTF texture, sRGB) → scene_.textures, -1 = unusable
    std::vector<std::uint64_t> idCount_;  // per scene_ mesh: the triangle ids one instance of it takes
    std::size_t elements_ = 0;            // vertices + indices read so far
    std::size_t instances_ = 0;
    std::uint64_t ids_ = 0;
    std::vector<int> untextured_;  // scene_ meshes whose material's textures have no coordinates in them

    void report(const std::string& feature) {
        if (std::find(scene_.unsupported.begin(), scene_.unsupported.end(), feature) == scene_.unsupported.end())
            scene_.unsupported.push_back(feature);
    }
    void warn(const std::string& text) { scene_.warnings.push_back(cat(load::shownPath(path_), ": ", text)); }
    void countElements(std::size_t count, const std::string& where) {
        elements_ += count;  // each count is bounded by the file size: no overflow
        if (elements_ > kMaxSceneElements)
            fail(where, ": the meshes need more than ", kMaxSceneElements, " vertices and indices, frugal's limit");
    }

    std::vector<int> chooseRoots() const;
    Node convertNode(int index) const;
    void convertNodes();
    void convertMesh(int index);
    void convertPrimitive(int meshIndex, int primitiveIndex);
    void readAttributes(const tinygltf::Primitive& primitive, const std::string& where, Mesh& mesh);
    void readTargets(const tinygltf::Primitive& primitive, const tinygltf::Mesh& gltfMesh, const std::string& where,
                     Mesh& mesh);
    std::vector<std::uint32_t> readVertexList(const tinygltf::Primitive& primitive, const std::string& where,
                                              std::size_t vertexCount);
    void convertMaterials();
    void untextureMeshesWithoutUvs();
    int useTexture(int gltfTexture, int material, bool srgb, const char* use);
    // The textures of material `material` that are drawn, and the coordinates they share.
    MaterialMaps mapsOf(int material) const;
    SpecularGlossiness specularGlossinessOf(int material) const;
    Clearcoat clearcoatOf(int material) const;
    ExtensionTexture extensionTexture(const tinygltf::Value& value, const std::string& where) const;
    void convertAnimations();
    void convertSkins();
    void addCamera(int node);
    void convertLights();

    template <class T, class Decode>
    std::vector<T> read(int accessor, const std::string& use, AccessorRequest request, Decode decode,
                        int* components = nullptr) const;
    std::vector<float> readFloats(int accessor, const std::string& use, std::span<const int> types,
                                  int* components = nullptr, std::span<const int> componentTypes = {}) const {
        return read<float>(accessor, use, {types, componentTypes}, decodeFloat, components);
    }
    std::vector<std::uint32_t> readIndices(int accessor, const std::string& use) const;
};

void checkBufferViews(const tinygltf::Model& model) {
    for (std::size_t i = 0; i < model.bufferViews.size(); ++i) {
        const tinygltf::BufferView& view = model.bufferViews[i];
        const std::size_t bufferSize = model.buffers[std::size_t(view.buffer)].data.size();
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

// A number member of an extension object, as a double that fits a float; `where` names it.
double extensionNumber(const tinygltf::Value& value, const std::string& where) {
    if (!value.IsNumber()) fail(where, ": not a number");
    const double d = value.GetNumberAsDouble();
    if (!std::isfinite(float(d))) fail(where, ": ", d, " does not fit a float");
    return d;
}

// A factor of a material extension: a number in [0, 1], as the extensions define them.
float extensionFactor(const tinygltf::Value& value, const std::string& where) {
    const double d = extensionNumber(value, where);
    if (!(d >= 0.0 && d <= 1.0)) fail(where, ": ", d, " is not in [0, 1]");
    return float(d);
}

TextureTransform textureTransformOf(int texCoord, const tinygltf::ExtensionMap& extensions, const std::string& where) {
    TextureTransform out;
    out.texCoord = texCoord;
    const auto it = extensions.find("KHR_texture_transform");
    if (it == extensions.end()) return out;
    const tinygltf::Value& ext = it->second;
    const std::string at = where + ".extensions.KHR_texture_transform";
    const auto number = [&](const tinygltf::Value& v, const std::string& name) {
        return extensionNumber(v, cat(at, ".", name));
    };
    const auto pair = [&](const char* name, double fallback) -> std::array<double, 2> {
        if (!ext.Has(name)) return {fallback, fallback};
        const tinygltf::Value& v = ext.Get(name);
        if (!v.IsArray() || v.ArrayLen() != 2) fail(at, ".", name, ": not an array of 2 numbers");
        return {number(v.Get(0), cat(name, "[0]")), number(v.Get(1), cat(name, "[1]"))};
    };
    const std::array<double, 2> offset = pair("offset", 0.0), scale = pair("scale", 1.0);
    const double rotation = ext.Has("rotation") ? number(ext.Get("rotation"), "rotation") : 0.0;
    if (ext.Has("texCoord")) {
        const double set = number(ext.Get("texCoord"), "texCoord");
        if (set < 0.0 || set > 255.0 || set != std::floor(set)) fail(at, ".texCoord: ", set, " is not a set index");
        out.texCoord = int(set);
    }
    // Column-major: T · R · S with R = [c s; −s c] as the extension writes it (rows).
    const double c = std::cos(rotation), s = std::sin(rotation);
    out.matrix[0] = glm::vec3(float(c * scale[0]), float(-s * scale[0]), 0.0f);
    out.matrix[1] = glm::vec3(float(s * scale[1]), float(c * scale[1]), 0.0f);
    out.matrix[2] = glm::vec3(float(offset[0]), float(offset[1]), 1.0f);
    return out;
}

ExtensionTexture Converter::extensionTexture(const tinygltf::Value& value, const std::string& where) const {
    if (!value.IsObject()) fail(where, ": not an object");
    const auto integer = [&](const char* name, double limit, const std::string& what) {
        const double d = extensionNumber(value.Get(name), cat(where, ".", name));
        if (d < 0.0 || d >= limit || d != std::floor(d)) fail(where, ".", name, ": ", d, what);
        return int(d);
    };
    if (!value.Has("index")) fail(where, ": no index");
    ExtensionTexture out;
    out.index = integer("index", double(model_.textures.size()),
                        cat(" is not a texture (the file has ", model_.textures.size(), ")"));
    if (value.Has("texCoord")) out.texCoord = integer("texCoord", 256.0, " is not a set index (0 to 255)");
    if (value.Has("scale")) out.scale = extensionNumber(value.Get("scale"), where + ".scale");
    if (value.Has("extensions")) {
        const tinygltf::Value& extensions = value.Get("extensions");
        if (!extensions.IsObject()) fail(where, ".extensions: not an object");
        for (const std::string& key : extensions.Keys()) out.extensions[key] = extensions.Get(key);
    }
    return out;
}

SpecularGlossiness Converter::specularGlossinessOf(int material) const {
    const tinygltf::Material& src = model_.materials[std::size_t(material)];
    SpecularGlossiness out;
    const auto it = src.extensions.find("KHR_materials_pbrSpecularGlossiness");
    if (it == src.extensions.end()) return out;
    out.present = true;
    const tinygltf::Value& ext = it->second;
    const std::string at = cat("materials[", material, "].extensions.KHR_materials_pbrSpecularGlossiness");
    if (!ext.IsObject()) fail(at, ": not an object");
    // Factors: numbers in [0, 1], as the extension defines them.
    const auto factors = [&](const char* name, float* values, int count) {
        if (!ext.Has(name)) return;
        const tinygltf::Value& v = ext.Get(name);
        if (!v.IsArray() || v.ArrayLen() != std::size_t(count))
            fail(at, ".", name, ": not an array of ", count, " numbers");
        for (int k = 0; k < count; ++k) values[k] = extensionFactor(v.Get(k), cat(at, ".", name, "[", k, "]"));
    };
    factors("diffuseFactor", &out.diffuse[0], 4);
    factors("specularFactor", &out.specular[0], 3);
    if (ext.Has("glossinessFactor"))
        out.glossiness = extensionFactor(ext.Get("glossinessFactor"), at + ".glossinessFactor");
    if (ext.Has("diffuseTexture"))
        out.diffuseTexture = extensionTexture(ext.Get("diffuseTexture"), at + ".diffuseTexture");
    if (ext.Has("specularGlossinessTexture"))
        out.specularGlossinessTexture =
            extensionTexture(ext.Get("specularGlossinessTexture"), at + ".specularGlossinessTexture");
    return out;
}

Clearcoat Converter::clearcoatOf(int material) const {
    const tinygltf::Material& src = model_.materials[std::size_t(material)];
    Clearcoat out;
    const auto it = src.extensions.find("KHR_materials_clearcoat");
    if (it == src.extensions.end()) return out;
    const tinygltf::Value& ext = it->second;
    const std::string at = cat("materials[", material, "].extensions.KHR_materials_clearcoat");
    if (!ext.IsObject()) fail(at, ": not an object");
    const auto factor = [&](const char* name) {
        return ext.Has(name) ? extensionFactor(ext.Get(name), cat(at, ".", name)) : 0.0f;
    };
    out.factor = factor("clearcoatFactor");
    out.roughness = factor("clearcoatRoughnessFactor");
    const auto texture = [&](const char* name, ExtensionTexture& into) {
        if (ext.Has(name)) into = extensionTexture(ext.Get(name), cat(at, ".", name));
    };
    texture("clearcoatTexture", out.texture);
    texture("clearcoatRoughnessTexture", out.roughnessTexture);
    texture("clearcoatNormalTexture", out.normalTexture);
    return out;
}

MaterialMaps Converter::mapsOf(int material) const {
    const tinygltf::Material& src = model_.materials[std::size_t(material)];
    const std::string where = cat("materials[", material, "]");
    struct Reference {
        int index, texCoord;
        const tinygltf::ExtensionMap& extensions;
        const char* member;
    };
    const tinygltf::TextureInfo& base = src.pbrMetallicRoughness.baseColorTexture;
    const tinygltf::TextureInfo& mr = src.pbrMetallicRoughness.metallicRoughnessTexture;
    // With KHR_materials_pbrSpecularGlossiness the diffuse texture is the base colour's, and the
    // specular-glossiness map replaces the metallic-roughness one.
    const SpecularGlossiness sg = specularGlossinessOf(material);
    const ExtensionTexture& diffuse = sg.diffuseTexture;
    const ExtensionTexture& specular = sg.specularGlossinessTexture;
    // A clear coat's maps are drawn only where there is a coat (factor above 0).
    const Clearcoat coat = clearcoatOf(material);
    const bool coated = coat.factor > 0.0f;
    const auto coatReference = [coated](const ExtensionTexture& t, const char* member) {
        return Reference{coated ? t.index : -1, t.texCoord, t.extensions, member};
    };
    const Reference references[MaterialMaps::kMapCount] = {
        sg.present ? Reference{diffuse.index, diffuse.texCoord, diffuse.extensions,
                               ".extensions.KHR_materials_pbrSpecularGlossiness.diffuseTexture"}
                   : Reference{base.index, base.texCoord, base.extensions, ".pbrMetallicRoughness.baseColorTexture"},
        {sg.present ? -1 : mr.index, mr.texCoord, mr.extensions, ".pbrMetallicRoughness.metallicRoughnessTexture"},
        {src.occlusionTexture.index, src.occlusionTexture.texCoord, src.occlusionTexture.extensions,
         ".occlusionTexture"},
        {src.emissiveTexture.index, src.emissiveTexture.texCoord, src.emissiveTexture.extensions, ".emissiveTexture"},
        {src.normalTexture.index, src.normalTexture.texCoord, src.normalTexture.extensions, ".normalTexture"},
        {specular.index, specular.texCoord, specular.extensions,
         ".extensions.KHR_materials_pbrSpecularGlossiness.specularGlossinessTexture"},
        coatReference(coat.texture, ".extensions.KHR_materials_clearcoat.clearcoatTexture"),
        coatReference(coat.roughnessTexture, ".extensions.KHR_materials_clearcoat.clearcoatRoughnessTexture"),
        coatReference(coat.normalTexture, ".extensions.KHR_materials_clearcoat.clearcoatNormalTexture"),
    };
    MaterialMaps maps;
    bool first = true;
    for (int k = 0; k < MaterialMaps::kMapCount; ++k) {
        const Reference& r = references[k];
        if (r.index < 0) continue;
        const TextureTransform t = textureTransformOf(r.texCoord, r.extensions, where + r.member);
        if (first) {
            maps.transform = t;
            first = false;
        } else if (t.texCoord != maps.transform.texCoord || t.matrix != maps.transform.matrix) {
            maps.differing = true;
            continue;
        }
        maps.texture[std::size_t(k)] = r.index;
    }
    return maps;
}

Node Converter::convertNode(int index) const {
    const tinygltf::Node& src = model_.nodes[std::size_t(index)];
    const std::string where = cat("nodes[", index, "]");
    Node node;
    node.name = src.name;
    node.children = src.children;
    for (std::size_t k = 0; k < src.weights.size(); ++k)
        node.weights.push_back(toFloat(src.weights[k], cat(where, ".weights[", k, "]")));
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
        scene_.nodes[std::size_t(n)].skin = src.skin;
        if (const auto it = src.extensions.find("KHR_lights_punctual"); it != src.extensions.end()) {
            const std::string where = cat("nodes[", n, "].extensions.KHR_lights_punctual");
            if (!it->second.IsObject() || !it->second.Has("light")) fail(where, ": no light");
            const double light = extensionNumber(it->second.Get("light"), where + ".light");
            if (!(light >= 0.0 && light < double(model_.lights.size()) && light == std::floor(light)))
                fail(where, ".light: ", light, " is not a light index (the file has ", model_.lights.size(), ")");
            scene_.nodes[std::size_t(n)].light = int(light);
            if (++lightNodes_ == kMaxLights + 1)
                report(cat("more than ", kMaxLights, " punctual lights (the first ", kMaxLights, " are drawn)"));
        }
    }
    convertLights();
}

// KHR_lights_punctual's lights, all of them in file order (nodes refer to them by index).
void Converter::convertLights() {
    for (int l = 0; l < int(model_.lights.size()); ++l) {
        const tinygltf::Light& src = model_.lights[std::size_t(l)];
        const std::string where = cat("extensions.KHR_lights_punctual.lights[", l, "]");
        PunctualLight light;
        light.name = src.name;
        if (!lightTypeNamed(src.type, light.type))
            fail(where, ".type: '", oneLine(src.type, 40), "' is not a light type (directional, point, spot)");
        // The file's numbers as floats (beyond a float's range: infinite, and refused), checked by
        // the one rule (LightCheck.h) and named with the file's own values.
        const auto asFloat = [](double v) {
            if (std::isnan(v) || std::fabs(v) <= 3.4e38) return float(v);
            return v > 0.0 ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity();
        };
        if (!src.color.empty()) {
            if (src.color.size() != 3) fail(where, ".color: ", src.color.size(), " numbers, not 3");
            for (int c = 0; c < 3; ++c) light.color[c] = asFloat(src.color[std::size_t(c)]);
        }
        light.intensity = asFloat(src.intensity);
        light.range = asFloat(src.range);  // read for point and spot lights only (frameLights)
        if (light.type == LightType::Spot) {
            light.innerConeAngle = asFloat(src.spot.innerConeAngle);
            light.outerConeAngle = asFloat(src.spot.outerConeAngle);
        }
        if (const std::optional<LightProblem> problem = lightProblem(light)) {
            const double outer = src.spot.outerConeAngle;
            switch (problem->value) {
                case LightValue::Color:
                    fail(where, ".color[", problem->channel, "]: ", src.color[std::size_t(problem->channel)],
                         " is not a colour value (0 or more)");
                case LightValue::Intensity:
                    fail(where, ".intensity: ", src.intensity, " is not an intensity (0 or more)");
                case LightValue::Range:
                    fail(where, ".range: ", src.range, " is not a range (above 0)");
                case LightValue::OuterCone:
                    fail(where, ".spot.outerConeAngle: ", outer, " is not in (0, pi/2]");
                case LightValue::InnerCone:
                    fail(where, ".spot.innerConeAngle: ", src.spot.innerConeAngle, " is not in [0, outerConeAngle ",
                         outer, ")");
            }
        }
        scene_.lights.push_back(std::move(light));
    }
}

void Converter::addCamera(int node) {
    const tinygltf::Camera& src = model_.cameras[std::size_t(model_.nodes[std::size_t(node)].camera)];
    const std::string where = cat("cameras[", model_.nodes[std::size_t(node)].camera, "]");
    SceneCamera camera;
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

Topology topologyOf(int mode) {
    switch (mode) {
        case TINYGLTF_MODE_POINTS:
            return Topology::Points;
        case TINYGLTF_MODE_LINE:
        case TINYGLTF_MODE_LINE_LOOP:
        case TINYGLTF_MODE_LINE_STRIP:
            return Topology::Lines;
        default:
            return Topology::Triangles;
    }
}

// The points or line segments of a primitive, as indices into its vertex list: POINTS as they are,
// LINES in pairs, LINE_STRIP segment i = (v_i, v_{i+1}), LINE_LOOP the same and a last one (v_{n-1},
// v_0) (spec, "Topology types"); segment i at position i, so triangleSource stays the identity. A
// strip or loop of fewer than 2 vertices has no segment, as GL draws it.
std::vector<std::uint32_t> segments(const std::vector<std::uint32_t>& v, int mode, const std::string& where) {
    if (mode == TINYGLTF_MODE_POINTS) return v;
    if (mode == TINYGLTF_MODE_LINE) {
        if (v.size() % 2 != 0) fail(where, ": LINES with ", v.size(), " vertices, which is not a multiple of 2");
        return v;
    }
    std::vector<std::uint32_t> out;
    if (v.size() < 2) return out;
    out.reserve(2 * v.size());
    for (std::size_t i = 0; i + 1 < v.size(); ++i) out.insert(out.end(), {v[i], v[i + 1]});
    if (mode == TINYGLTF_MODE_LINE_LOOP) out.insert(out.end(), {v.back(), v.front()});
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
    // The one set of texture coordinates frugal keeps is the one the material's textures sample.
    const MaterialMaps maps = primitive.material >= 0 ? mapsOf(primitive.material) : MaterialMaps{};
    const bool textured = maps.any();
    const int texCoord = textured ? maps.transform.texCoord : 0;
    const std::string uvName = cat("TEXCOORD_", texCoord);
    // Tangents are kept for a normal map only, the surface's or its coat's (and only with the
    // normals they belong to).
    static constexpr int kVec4[] = {TINYGLTF_TYPE_VEC4};
    static constexpr int kFloat[] = {TINYGLTF_COMPONENT_TYPE_FLOAT};
    const bool normalMapped =
        maps.texture[MaterialMaps::kNormal] >= 0 || maps.texture[MaterialMaps::kClearcoatNormal] >= 0;
    if (const int tangent = accessor("TANGENT"); tangent >= 0 && normalMapped && !mesh.normals.empty())
        mesh.tangents = toVectors<glm::vec4>(readFloats(tangent, "TANGENT of " + where, kVec4, nullptr, kFloat));
    // Skinning: JOINTS_n (unsigned byte or short) and WEIGHTS_n (float or normalised), sets 0 and 1.
    static constexpr int kJointTypes[] = {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                          TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
    for (int set = 0; set < 2; ++set) {
        const int joints = accessor(cat("JOINTS_", set)), weights = accessor(cat("WEIGHTS_", set));
        if (joints < 0 || weights < 0) break;
        Mesh::Influences influences;
        const std::vector<std::uint32_t> indices =
            read<std::uint32_t>(joints, cat("JOINTS_", set, " of ", where), {kVec4, kJointTypes}, decodeUint);
        const std::vector<float> values = readFloats(weights, cat("WEIGHTS_", set, " of ", where), kVec4);
        influences.joints.resize(vertexCount);
        influences.weights.resize(vertexCount);
        for (std::size_t v = 0; v < vertexCount; ++v)
            for (int k = 0; k < 4; ++k) {
                influences.joints[v][k] = indices[4 * v + std::size_t(k)];
                const float w = values[4 * v + std::size_t(k)];
                if (!std::isfinite(w))
                    fail("accessor ", weights, " (WEIGHTS_", set, " of ", where, "): weight ", 4 * v + std::size_t(k),
                         " is not finite");
                influences.weights[v][k] = w;
            }
        mesh.influences.push_back(std::move(influences));
    }
    if (const int uv = accessor(uvName); uv >= 0) {
        mesh.uvs = toVectors<glm::vec2>(readFloats(uv, uvName + " of " + where, kVec2));
    } else if (textured) {
        warn(cat(where, ": material ", primitive.material, " samples its textures with ", uvName,
                 ", which the primitive lacks: drawn untextured"));
        untextured_.push_back(int(scene_.meshes.size()));  // the index this mesh will get
    }
}

// The primitive's morph targets (POSITION, NORMAL and TANGENT displacements, one a vertex; normals
// and tangents kept where the mesh keeps its own) and the mesh's default weights. A displacement
// that is not finite counts 0 (warned once).
void Converter::readTargets(const tinygltf::Primitive& primitive, const tinygltf::Mesh& gltfMesh,
                            const std::string& where, Mesh& mesh) {
    static constexpr int kVec3[] = {TINYGLTF_TYPE_VEC3};
    const std::size_t vertices = mesh.positions.size();
    bool repaired = false;
    for (std::size_t t = 0; t < primitive.targets.size(); ++t) {
        MorphTarget target;
        for (const auto& [name, index] : primitive.targets[t]) {
            std::vector<glm::vec3>* into = name == "POSITION"                            ? &target.positions
                                           : name == "NORMAL" && !mesh.normals.empty()   ? &target.normals
                                           : name == "TANGENT" && !mesh.tangents.empty() ? &target.tangents
                                                                                         : nullptr;
            if (!into) continue;
            const std::string use = cat(name, " of ", where, " target ", t);
            if (model_.accessors[std::size_t(index)].count != vertices)
                fail("accessor ", index, " (", use, "): ", model_.accessors[std::size_t(index)].count,
                     " elements, POSITION has ", vertices);
            *into = toVectors<glm::vec3>(readFloats(index, use, kVec3));
            for (glm::vec3& d : *into)
                if (!(std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z))) {
                    d = glm::vec3(0.0f);
                    repaired = true;
                }
        }
        mesh.targets.push_back(std::move(target));
    }
    if (repaired) warn(cat(where, ": morph target displacements that are not finite count 0"));
    if (mesh.targets.empty()) return;
    if (!gltfMesh.weights.empty() && gltfMesh.weights.size() != mesh.targets.size())
        fail(where, ": the mesh has ", gltfMesh.weights.size(), " weights for ", mesh.targets.size(), " morph targets");
    mesh.weights.assign(mesh.targets.size(), 0.0f);
    for (std::size_t t = 0; t < gltfMesh.weights.size(); ++t)
        mesh.weights[t] = toFloat(gltfMesh.weights[t], cat(where, ": weight ", t));
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
    readTargets(primitive, gltfMesh, where, mesh);
    mesh.topology = topologyOf(mode);
    mesh.indices = mesh.triangles() ? triangulate(readVertexList(primitive, where, mesh.positions.size()), mode, where)
                                    : segments(readVertexList(primitive, where, mesh.positions.size()), mode, where);

    const MeshBuildStats stats = finalizeMesh(mesh, options_.optimizeOrder);
    if (stats.droppedNonFinite > 0) {
        const std::string name =
            gltfMesh.name.empty() ? cat("mesh ", meshIndex) : cat("mesh '", oneLine(gltfMesh.name, 60), "'");
        warn(cat(name, " primitive ", primitiveIndex, ": dropped ", stats.droppedNonFinite, " ",
                 mesh.triangles()                   ? "triangles"
                 : mesh.topology == Topology::Lines ? "line segments"
                                                    : "points",
                 " with non-finite positions"));
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

// glTF texture `gltfTexture` as a scene texture whose colour channels are sRGB or linear (an image
// used both ways becomes two textures).
int Converter::useTexture(int gltfTexture, int material, bool srgb, const char* use) {
    if (const auto it = textures_.find({gltfTexture, srgb}); it != textures_.end()) return it->second;
    int& result = textures_[{gltfTexture, srgb}];
    result = -1;
    const tinygltf::Texture& texture = model_.textures[std::size_t(gltfTexture)];
    const std::string drawn = cat(": material ", material, " drawn without its ", use, " texture");
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
    if (const Result<ImageSize> checked = checkTextureImage({bytes, size}); !checked) {
        warn(cat(imageName, " cannot be decoded (", checked.error().message, ")", drawn));
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
    out.srgb = srgb;
    if (!toRgba8(decoded, out.rgba)) {
        warn(cat(imageName, " decoded to an unexpected format (", decoded.component, " channels of ", decoded.bits,
                 " bits)", drawn));
        return result;
    }
    // The sampler's filters; where the file leaves them undefined (no sampler, or no filter in it),
    // LINEAR and LINEAR_MIPMAP_LINEAR, the Khronos glTF Sample Renderer's defaults.
    int magFilter = -1, minFilter = -1;
    if (texture.sampler >= 0) {
        const tinygltf::Sampler& sampler = model_.samplers[std::size_t(texture.sampler)];
        out.wrapS = toWrap(sampler.wrapS);
        out.wrapT = toWrap(sampler.wrapT);
        magFilter = sampler.magFilter;
        minFilter = sampler.minFilter;
    }
    out.filter = magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ? Filter::Nearest : Filter::Linear;
    switch (minFilter) {
        case TINYGLTF_TEXTURE_FILTER_NEAREST:
            out.minFilter = Filter::Nearest;
            break;
        case TINYGLTF_TEXTURE_FILTER_LINEAR:
            out.minFilter = Filter::Linear;
            break;
        case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST:
            out.minFilter = Filter::Nearest;
            out.mipmaps = MipFilter::Nearest;
            break;
        case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST:
            out.minFilter = Filter::Linear;
            out.mipmaps = MipFilter::Nearest;
            break;
        case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR:
            out.minFilter = Filter::Nearest;
            out.mipmaps = MipFilter::Linear;
            break;
        default:  // LINEAR_MIPMAP_LINEAR, or undefined
            out.minFilter = Filter::Linear;
            out.mipmaps = MipFilter::Linear;
            break;
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
        material.metallicFactor = std::clamp(
            toFloat(src.pbrMetallicRoughness.metallicFactor, cat(where, ".pbrMetallicRoughness.metallicFactor")), 0.0f,
            1.0f);
        material.roughnessFactor = std::clamp(
            toFloat(src.pbrMetallicRoughness.roughnessFactor, cat(where, ".pbrMetallicRoughness.roughnessFactor")),
            0.0f, 1.0f);
        material.unlit = src.extensions.count("KHR_materials_unlit") > 0;
        // The emissive factor, times KHR_materials_emissive_strength (and the emissive texture).
        double strength = 1.0;
        if (const auto it = src.extensions.find("KHR_materials_emissive_strength");
            it != src.extensions.end() && it->second.Has("emissiveStrength")) {
            const std::string at = where + ".extensions.KHR_materials_emissive_strength.emissiveStrength";
            strength = extensionNumber(it->second.Get("emissiveStrength"), at);
            if (strength < 0.0) fail(at, ": ", strength, " is negative");
        }
        for (int k = 0; k < 3 && std::size_t(k) < src.emissiveFactor.size(); ++k)
            material.emissiveFactor[k] =
                toFloat(src.emissiveFactor[std::size_t(k)] * strength, cat(where, ".emissiveFactor[", k, "]"));
        const double occlusion = src.occlusionTexture.strength;
        if (!(occlusion >= 0.0 && occlusion <= 1.0))
            fail(where, ".occlusionTexture.strength: ", occlusion, " is not in [0, 1]");
        material.occlusionStrength = float(occlusion);
        material.normalScale = toFloat(src.normalTexture.scale, where + ".normalTexture.scale");
        material.alphaMode = src.alphaMode == "MASK"    ? AlphaMode::Mask
                             : src.alphaMode == "BLEND" ? AlphaMode::Blend
                                                        : AlphaMode::Opaque;  // the schema allows no other
        const double cutoff = src.alphaCutoff;
        if (!(cutoff >= 0.0)) fail(where, ".alphaCutoff: ", cutoff, " is negative");
        material.alphaCutoff = toFloat(cutoff, where + ".alphaCutoff");
        if (const SpecularGlossiness sg = specularGlossinessOf(m); sg.present) {
            material.specularGlossiness = true;
            material.baseColorFactor = sg.diffuse;  // the diffuse colour is the base colour
            material.specularFactor = sg.specular;
            material.glossinessFactor = sg.glossiness;
        }
        if (const Clearcoat coat = clearcoatOf(m); coat.factor > 0.0f) {
            material.clearcoatFactor = coat.factor;
            material.clearcoatRoughnessFactor = coat.roughness;
            material.clearcoatNormalScale = toFloat(
                coat.normalTexture.scale, where + ".extensions.KHR_materials_clearcoat.clearcoatNormalTexture.scale");
        }
        // Features are reported, and textures decoded, only for materials the drawn meshes use.
        if (!materialUsed_[std::size_t(m)]) continue;
        const MaterialMaps maps = mapsOf(m);  // (KHR_texture_transform: one transform for them all)
        if (maps.differing) report("textures of one material on different coordinates (the first one's are used)");
        material.baseColorTransform = maps.transform.matrix;
        static_assert(std::size(kMaterialMaps) == MaterialMaps::kMapCount);
        for (int k = 0; k < MaterialMaps::kMapCount; ++k) {
            if (maps.texture[std::size_t(k)] < 0) continue;
            // Colour is sRGB-encoded (base colour, emission); data is linear. The Khronos renderer
            // reads both textures of KHR_materials_pbrSpecularGlossiness as linear (the extension
            // says their rgb is sRGB), and so does frugal: its images are measured against that
            // renderer's (docs/fidelity.md).
            const bool srgb =
                (k == MaterialMaps::kBaseColor && !material.specularGlossiness) || k == MaterialMaps::kEmissive;
            material.*kMaterialMaps[k].texture =
                useTexture(maps.texture[std::size_t(k)], m, srgb, MaterialMaps::kNames[k]);
        }
        // Emission from a texture that is not drawn: none (rather than the factor's full brightness
        // everywhere).
        if (src.emissiveTexture.index >= 0 && material.emissiveTexture < 0)
            material.emissiveFactor = glm::vec3(0.0f);
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
            if (copy.emissiveTexture >= 0) copy.emissiveFactor = glm::vec3(0.0f);  // its emission needs it
            for (const MaterialMap& map : kMaterialMaps) copy.*map.texture = -1;
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
            if (channel.target_node < 0) continue;  // glTF: a channel without a node is ignored
            const bool weights = channel.target_path == "weights";
            const int s = channel.sampler;
            const tinygltf::AnimationSampler& sampler = src.samplers[std::size_t(s)];
            const std::string where = cat("animation ", a, " sampler ", s);
            AnimChannel out;
            out.node = channel.target_node;
            out.path = channel.target_path == "translation" ? AnimPath::Translation
                       : channel.target_path == "rotation"  ? AnimPath::Rotation
                       : weights                            ? AnimPath::Weights
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
            if (weights) {
                // As many weights a key as the node's mesh has targets.
                const int meshIndex = model_.nodes[std::size_t(out.node)].mesh;
                const std::size_t targets = meshIndex < 0 || model_.meshes[std::size_t(meshIndex)].primitives.empty()
                                                ? 0
                                                : model_.meshes[std::size_t(meshIndex)].primitives[0].targets.size();
                if (targets == 0) {
                    warn(cat(where, ": animates the morph weights of node ", out.node,
                             ", whose mesh has no morph targets: ignored"));
                    continue;
                }
                static constexpr int kScalar1[] = {TINYGLTF_TYPE_SCALAR};
                out.weights = readFloats(sampler.output, "output of " + where, kScalar1);
                out.weightCount = int(targets);
                const std::size_t expected = out.times.size() * (cubic ? 3 : 1) * targets;
                if (out.weights.size() != expected)
                    fail(where, ": output has ", out.weights.size(), " weights, expected ", expected, " (", targets,
                         " targets x ", out.times.size(), " keys", cubic ? " x 3, CUBICSPLINE)" : ")");
                for (std::size_t k = 0; k < out.weights.size(); ++k)
                    if (!std::isfinite(out.weights[k])) fail(where, ": output value ", k, " is not finite");
                animation.channels.push_back(std::move(out));
                continue;
            }
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

// Skins: joints and inverse bind matrices (MAT4 floats, one a joint at least; identity without an
// accessor). A node with a skin that draws a skinned mesh must have every joint its vertices name.
void Converter::convertSkins() {
    static constexpr int kMat4[] = {TINYGLTF_TYPE_MAT4};
    static constexpr int kFloat[] = {TINYGLTF_COMPONENT_TYPE_FLOAT};
    for (std::size_t k = 0; k < model_.skins.size(); ++k) {
        const tinygltf::Skin& src = model_.skins[k];
        const std::string where = cat("skins[", k, "]");
        Skin skin;
        skin.name = src.name;
        skin.joints = src.joints;
        if (skin.joints.empty()) fail(where, ": no joints");
        skin.inverseBindMatrices.assign(skin.joints.size(), glm::mat4(1.0f));
        if (src.inverseBindMatrices >= 0) {
            const std::vector<float> values =
                readFloats(src.inverseBindMatrices, "inverseBindMatrices of " + where, kMat4, nullptr, kFloat);
            if (values.size() < 16 * skin.joints.size())
                fail(where, ": ", values.size() / 16, " inverse bind matrices for ", skin.joints.size(), " joints");
            for (std::size_t j = 0; j < skin.joints.size(); ++j)
                for (int e = 0; e < 16; ++e) {
                    const float v = values[16 * j + std::size_t(e)];
                    if (!std::isfinite(v)) fail(where, ": inverse bind matrix ", j, " is not finite");
                    glm::value_ptr(skin.inverseBindMatrices[j])[e] = v;
                }
        }
        scene_.skins.push_back(std::move(skin));
    }
    for (std::size_t n = 0; n < scene_.nodes.size(); ++n) {
        const Node& node = scene_.nodes[n];
        if (node.skin < 0) continue;
        const std::size_t joints = scene_.skins[std::size_t(node.skin)].joints.size();
        for (int m : node.meshes) {
            const Mesh& mesh = scene_.meshes[std::size_t(m)];
            for (std::size_t set = 0; set < mesh.influences.size(); ++set)
                for (std::size_t v = 0; v < mesh.influences[set].joints.size(); ++v)
                    for (int c = 0; c < 4; ++c) {
                        const std::uint32_t j = mesh.influences[set].joints[v][c];
                        if (j >= joints && mesh.influences[set].weights[v][c] != 0.0f)
                            fail("mesh '", oneLine(mesh.name, 60), "': JOINTS_", set, " of vertex ", v, " names joint ",
                                 j, ", the skin of node ", n, " has ", joints);
                    }
        }
    }
}

Scene Converter::run() {
    scene_.source = path_;
    // KHR_mesh_quantization only widens the accessor types, which the readers above all accept;
    // KHR_materials_unlit is Material::unlit; KHR_texture_transform, Material::baseColorTransform (one
    // per material: mapsOf); KHR_materials_emissive_strength scales Material::emissiveFactor;
    // KHR_materials_pbrSpecularGlossiness is Material::specularGlossiness (specularGlossinessOf);
    // KHR_materials_clearcoat, Material::clearcoatFactor and the rest (clearcoatOf); KHR_lights_punctual,
    // Scene::lights and Node::light (convertLights); KHR_draco_mesh_compression and
    // EXT_meshopt_compression are decoded before the conversion (decompress).
    for (const std::string& name : extensions_)
        if (name != "KHR_mesh_quantization" && name != "KHR_materials_unlit" && name != "KHR_texture_transform" &&
            name != "KHR_materials_emissive_strength" && name != "KHR_materials_pbrSpecularGlossiness" &&
            name != "KHR_materials_clearcoat" && name != "KHR_lights_punctual" &&
            name != "KHR_draco_mesh_compression" && name != "EXT_meshopt_compression")
            report(oneLine(name, 80));
    convertNodes();
    convertMaterials();
    untextureMeshesWithoutUvs();
    convertAnimations();
    convertSkins();
    scene_.buildInstances();
    return std::move(scene_);
}

// ---------------------------------------------------------------------------------------------
// Compressed geometry (GltfCompression.h), decoded into tinygltf's model before anything reads it.

template <class T>
std::size_t append(std::vector<T>& list, T item) {
    list.push_back(std::move(item));
    return list.size() - 1;
}

// A new buffer holding `bytes`, and a bufferView of all of it; returns the view.
int addView(tinygltf::Model& model, std::vector<unsigned char> bytes) {
    tinygltf::BufferView view;
    view.byteLength = bytes.size();
    tinygltf::Buffer buffer;
    buffer.data = std::move(bytes);
    view.buffer = int(append(model.buffers, std::move(buffer)));
    return int(append(model.bufferViews, std::move(view)));
}

// Every meshopt bufferView reads its decoded bytes (its own new buffer: the fallback buffer it
// names has no data); every Draco primitive reads new accessors of its decoded attributes and
// indices, as TRIANGLES (a Draco mesh decodes to triangles, strip or not). bufferViews are checked
// between the two, so that a Draco stream is read only from a range that exists.
std::vector<Decompression> decompress(tinygltf::Model& model, const Compression& compression) {
    using Clock = std::chrono::steady_clock;
    std::vector<Decompression> out;
    if (!compression.meshopt.empty()) {
        Decompression entry{"EXT_meshopt_compression", compression.meshopt.size(), 0, 0, 0.0};
        const Clock::time_point start = Clock::now();
        for (const MeshoptView& compressed : compression.meshopt) {
            const std::string where = cat("bufferViews[", compressed.view, "]");
            const std::vector<unsigned char>& source = model.buffers[compressed.buffer].data;
            if (compressed.byteOffset + compressed.byteLength > source.size())
                fail(where, ".extensions.EXT_meshopt_compression: byteOffset ", compressed.byteOffset, " + byteLength ",
                     compressed.byteLength, " is beyond the end of buffer ", compressed.buffer, " (", source.size(),
                     " bytes)");
            std::vector<unsigned char> decoded = decodeMeshopt(
                compressed, std::span(source).subspan(compressed.byteOffset, compressed.byteLength), where);
            entry.compressedBytes += compressed.byteLength;
            entry.decodedBytes += decoded.size();
            tinygltf::Buffer buffer;
            buffer.data = std::move(decoded);
            tinygltf::BufferView& view = model.bufferViews[compressed.view];
            view.buffer = int(append(model.buffers, std::move(buffer)));
            view.byteOffset = 0;
        }
        entry.seconds = std::chrono::duration<double>(Clock::now() - start).count();
        out.push_back(entry);
    }
    checkBufferViews(model);
    if (compression.draco.empty()) return out;

    Decompression entry{"KHR_draco_mesh_compression", compression.draco.size(), 0, 0, 0.0};
    const Clock::time_point start = Clock::now();
    for (const DracoPrimitive& draco : compression.draco) {
        tinygltf::Primitive& primitive = model.meshes[draco.mesh].primitives[draco.primitive];
        const std::string where = cat("mesh ", draco.mesh, " primitive ", draco.primitive);
        std::vector<DracoRequest> requests;
        for (const DracoPrimitive::Attribute& attribute : draco.attributes) {
            const tinygltf::Accessor& accessor = model.accessors[std::size_t(primitive.attributes.at(attribute.name))];
            const int components = tinygltf::GetNumComponentsInType(std::uint32_t(accessor.type));
            if (components < 1 || components > 4)
                fail("accessor ", primitive.attributes.at(attribute.name), " (", attribute.name, " of ", where,
                     "): type ", typeName(accessor.type), ", a Draco attribute is a scalar or a vector");
            requests.push_back({attribute.uniqueId, accessor.componentType, components, attribute.name});
        }
        const tinygltf::BufferView& view = model.bufferViews[draco.bufferView];
        const std::span<const unsigned char> stream(
            model.buffers[std::size_t(view.buffer)].data.data() + view.byteOffset, view.byteLength);
        entry.compressedBytes += stream.size();
        DracoDecoded decoded = decodeDraco(stream, requests, where);
        for (std::size_t a = 0; a < requests.size(); ++a) {
            tinygltf::Accessor accessor = model.accessors[std::size_t(primitive.attributes.at(requests[a].name))];
            accessor.count = decoded.points;
            accessor.byteOffset = 0;
            accessor.sparse = {};
            entry.decodedBytes += decoded.data[a].size();
            accessor.bufferView = addView(model, std::move(decoded.data[a]));
            primitive.attributes[requests[a].name] = int(append(model.accessors, std::move(accessor)));
        }
        tinygltf::Accessor indices;
        indices.type = TINYGLTF_TYPE_SCALAR;
        indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
        indices.count = decoded.indices.size();
        std::vector<unsigned char> bytes(decoded.indices.size() * sizeof(std::uint32_t));
        std::memcpy(bytes.data(), decoded.indices.data(), bytes.size());
        entry.decodedBytes += bytes.size();
        indices.bufferView = addView(model, std::move(bytes));
        primitive.indices = int(append(model.accessors, std::move(indices)));
        primitive.mode = TINYGLTF_MODE_TRIANGLES;
    }
    entry.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    out.push_back(entry);
    return out;
}

bool decodeDataUri(const std::string& uri, std::vector<unsigned char>& bytes) {
    std::string mime;
    return tinygltf::DecodeDataURI(&bytes, mime, uri, 0, false);
}

Scene loadGltfOrThrow(std::string_view file, const std::string& path, const LoadOptions& options) {
    if (file.empty()) fail("file is empty");
    const bool binary = isBinary(path, file);
    GlbParts glb;
    std::string_view jsonText = file;
    if (binary) {
        glb = splitGlb(file);
        jsonText = glb.json;
    }
    const Json root = parseJson(jsonText);
    checkSchema(root);
    checkStructure(root);
    const Compression compression = findCompression(root, binary);
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    checkBuffers(root, dir, binary ? &glb : nullptr, &decodeDataUri, compression.fallbackBuffers);
    std::vector<std::string> extensions = usedExtensions(root);

    // tinygltf reads the file as it is, unless it is compressed (it could not: forTinygltf) or a
    // .glb tinygltf cannot take as it is (canonicalGlb).
    std::string rewritten;
    if (compression.any()) {
        rewritten = forTinygltf(root, compression).dump(-1, ' ', false, Json::error_handler_t::replace);
        if (binary) {
            GlbParts parts = glb;
            parts.json = rewritten;
            rewritten = canonicalGlb(parts);
        }
    } else if (binary && !glb.canonical) {
        rewritten = canonicalGlb(glb);
    }
    const std::string_view input = rewritten.empty() ? file : std::string_view(rewritten);
    const std::string baseDir = dir.empty() ? std::string(".") : dir.string();
    tinygltf::Model model = runTinygltf(input, binary, baseDir);
    std::vector<Decompression> decompressed = decompress(model, compression);
    return Converter(model, path, options, std::move(extensions), std::move(decompressed)).run();
}

}  // namespace
}  // namespace gltf

Result<Scene> loadGltf(const std::string& path, const LoadOptions& options) {
    return load::guard(path, [&] { return gltf::loadGltfOrThrow(load::readFile(path), path, options); });
}

Result<Scene> loadGltfFromMemory(std::string_view bytes, const std::string& name, const LoadOptions& options) {
    return load::guard(name, [&] { return gltf::loadGltfOrThrow(bytes, name, options); });
}

}  // namespace frugal
