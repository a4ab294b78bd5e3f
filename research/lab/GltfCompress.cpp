#include "lab/GltfCompress.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "lab/TradePage.h"  // base64

namespace frugal {

namespace {

using Json = nlohmann::json;
using Bytes = std::vector<unsigned char>;

Error bad(const std::string& path, const std::string& what) { return Error{path + ": " + what, ErrorKind::BadInput}; }

constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

std::optional<Bytes> unbase64(const std::string& text) {
    Bytes out;
    std::uint32_t group = 0;
    int bits = 0;
    for (const char c : text) {
        if (c == '=') break;
        const char* at = std::strchr(kDigits, c);
        if (!at || c == '\0') return std::nullopt;
        group = (group << 6) | std::uint32_t(at - kDigits);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out.push_back(static_cast<unsigned char>((group >> bits) & 0xFF));
        }
    }
    return out;
}

std::optional<Bytes> readFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

int componentBytes(int type) { return type == 5120 || type == 5121 ? 1 : type == 5122 || type == 5123 ? 2 : 4; }
int componentsOf(const std::string& type) {
    return type == "SCALAR" ? 1
           : type == "VEC2" ? 2
           : type == "VEC3" ? 3
           : type == "VEC4" ? 4
           : type == "MAT2" ? 4
           : type == "MAT3" ? 9
                            : 16;
}

// One file's JSON and buffers, read whole.
struct Gltf {
    Json json;
    std::vector<Bytes> buffers;

    // Accessor `a` as floats (normalised integers as glTF decodes them), packed.
    std::vector<float> floats(std::size_t a) const {
        const Json& accessor = json["accessors"][a];
        const int type = accessor["componentType"].get<int>();
        const int components = componentsOf(accessor["type"].get<std::string>());
        const std::size_t count = accessor["count"].get<std::size_t>();
        const bool normalized = accessor.value("normalized", false);
        std::vector<float> out(count * std::size_t(components), 0.0f);
        if (!accessor.contains("bufferView")) return out;
        const Json& view = json["bufferViews"][accessor["bufferView"].get<std::size_t>()];
        const std::size_t size = std::size_t(componentBytes(type));
        const std::size_t stride = view.value("byteStride", size * std::size_t(components));
        const unsigned char* base = buffers[view["buffer"].get<std::size_t>()].data() +
                                    view.value("byteOffset", std::size_t(0)) +
                                    accessor.value("byteOffset", std::size_t(0));
        for (std::size_t e = 0; e < count; ++e)
            for (int c = 0; c < components; ++c) {
                const unsigned char* p = base + e * stride + std::size_t(c) * size;
                float v = 0.0f;
                switch (type) {
                    case 5120:
                        v = normalized ? std::max(float(std::int8_t(*p)) / 127.0f, -1.0f) : float(std::int8_t(*p));
                        break;
                    case 5121:
                        v = normalized ? float(*p) / 255.0f : float(*p);
                        break;
                    case 5122: {
                        std::int16_t x;
                        std::memcpy(&x, p, 2);
                        v = normalized ? std::max(float(x) / 32767.0f, -1.0f) : float(x);
                        break;
                    }
                    case 5123: {
                        std::uint16_t x;
                        std::memcpy(&x, p, 2);
                        v = normalized ? float(x) / 65535.0f : float(x);
                        break;
                    }
                    case 5125: {
                        std::uint32_t x;
                        std::memcpy(&x, p, 4);
                        v = float(x);
                        break;
                    }
                    default:
                        std::memcpy(&v, p, 4);
                }
                out[e * std::size_t(components) + std::size_t(c)] = v;
            }
        return out;
    }
};

Result<Gltf> readGltf(const std::string& path) {
    const std::optional<Bytes> text = readFile(path);
    if (!text) return bad(path, "cannot read the file");
    Gltf gltf;
    gltf.json = Json::parse(text->begin(), text->end(), nullptr, false);
    if (!gltf.json.is_object()) return bad(path, "not a glTF JSON file (a .glb is not read here)");
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    for (const Json& buffer : gltf.json.value("buffers", Json::array())) {
        const std::string uri = buffer.value("uri", std::string());
        std::optional<Bytes> data;
        if (uri.rfind("data:", 0) == 0) {
            const std::size_t comma = uri.find(";base64,");
            if (comma != std::string::npos) data = unbase64(uri.substr(comma + 8));
        } else if (!uri.empty()) {
            data = readFile(dir / uri);
        }
        if (!data || data->size() < buffer["byteLength"].get<std::size_t>())
            return bad(path, "a buffer cannot be read whole ('" + uri.substr(0, 60) + "')");
        gltf.buffers.push_back(std::move(*data));
    }
    // Images beside the file go in too, so that the copy stands anywhere.
    if (gltf.json.contains("images"))
        for (Json& image : gltf.json["images"]) {
            const std::string uri = image.value("uri", std::string());
            if (uri.empty() || uri.rfind("data:", 0) == 0) continue;
            const std::optional<Bytes> data = readFile(dir / uri);
            if (!data) return bad(path, "cannot read image '" + uri.substr(0, 60) + "'");
            const bool png = data->size() > 4 && (*data)[0] == 0x89 && (*data)[1] == 'P';
            image["uri"] = std::string(png ? "data:image/png;base64," : "data:image/jpeg;base64,") + base64(*data);
        }
    return gltf;
}

void require(Json& json, const char* extension) {
    for (const char* key : {"extensionsUsed", "extensionsRequired"}) {
        Json& list = json[key];
        if (!list.is_array()) list = Json::array();
        if (std::find(list.begin(), list.end(), extension) == list.end()) list.push_back(extension);
    }
}

void align4(Bytes& bytes) { bytes.resize((bytes.size() + 3) / 4 * 4, 0); }

std::size_t append(Bytes& to, const unsigned char* data, std::size_t size) {
    align4(to);
    const std::size_t offset = to.size();
    to.insert(to.end(), data, data + size);
    return offset;
}

std::size_t addAccessor(Json& json, Json accessor) {
    json["accessors"].push_back(std::move(accessor));
    return json["accessors"].size() - 1;
}

// ---------------------------------------------------------------------------------------------
// KHR_draco_mesh_compression: each TRIANGLES primitive's attributes (as floats) and triangles in
// one Draco stream, appended to a new buffer; the primitive's accessors become new ones without a
// bufferView, of the decoded counts.

Result<std::string> compressDraco(Gltf gltf, const CompressOptions& options, const std::string& path) {
    Json& json = gltf.json;
    Bytes streams;
    bool any = false;
    for (Json& mesh : json["meshes"])
        for (Json& primitive : mesh["primitives"]) {
            if (primitive.value("mode", 4) != 4 || primitive.contains("targets") || primitive.contains("extensions"))
                continue;
            const std::size_t points =
                json["accessors"][primitive["attributes"]["POSITION"].get<std::size_t>()]["count"];
            draco::Mesh source;
            source.set_num_points(std::uint32_t(points));
            std::vector<std::pair<std::string, int>> ids;  // attribute name → Draco attribute
            for (const auto& [name, index] : primitive["attributes"].items()) {
                const std::vector<float> values = gltf.floats(index.get<std::size_t>());
                const int components = int(values.size() / points);
                using Type = draco::GeometryAttribute::Type;
                const Type type = name == "POSITION"                ? Type::POSITION
                                  : name == "NORMAL"                ? Type::NORMAL
                                  : name.rfind("TEXCOORD_", 0) == 0 ? Type::TEX_COORD
                                  : name.rfind("COLOR_", 0) == 0    ? Type::COLOR
                                                                    : Type::GENERIC;
                // Joint indices stay integers (glTF allows them unsigned byte or short only).
                const bool joints = name.rfind("JOINTS_", 0) == 0;
                draco::GeometryAttribute attribute;
                attribute.Init(type, nullptr, std::uint8_t(components), joints ? draco::DT_UINT16 : draco::DT_FLOAT32,
                               false, std::int64_t(joints ? sizeof(std::uint16_t) : sizeof(float)) * components, 0);
                const int id = source.AddAttribute(attribute, true, std::uint32_t(points));
                for (std::size_t p = 0; p < points; ++p) {
                    std::uint16_t integers[4] = {};
                    for (int c = 0; c < components && joints; ++c)
                        integers[c] = std::uint16_t(values[p * std::size_t(components) + std::size_t(c)]);
                    const void* value = joints ? static_cast<const void*>(integers)
                                               : static_cast<const void*>(&values[p * std::size_t(components)]);
                    source.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(std::uint32_t(p)), value);
                }
                ids.emplace_back(name, id);
            }
            std::vector<float> indices;
            if (primitive.contains("indices")) {
                indices = gltf.floats(primitive["indices"].get<std::size_t>());
            } else {
                for (std::size_t p = 0; p < points; ++p) indices.push_back(float(p));
            }
            for (std::size_t t = 0; t + 2 < indices.size(); t += 3)
                source.AddFace({draco::PointIndex(std::uint32_t(indices[t])),
                                draco::PointIndex(std::uint32_t(indices[t + 1])),
                                draco::PointIndex(std::uint32_t(indices[t + 2]))});

            draco::Encoder encoder;
            if (options.dracoBits > 0) {
                encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, options.dracoBits);
                encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, std::max(options.dracoBits, 10));
                encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, std::max(options.dracoBits, 10));
                encoder.SetAttributeQuantization(draco::GeometryAttribute::COLOR, std::max(options.dracoBits, 10));
                encoder.SetAttributeQuantization(draco::GeometryAttribute::GENERIC, std::max(options.dracoBits, 10));
            }
            if (options.dracoSequential) encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
            draco::EncoderBuffer encoded;
            if (const draco::Status status = encoder.EncodeMeshToBuffer(source, &encoded); !status.ok())
                return bad(path, "Draco cannot encode a primitive: " + status.error_msg_string());

            // Decoded again for the counts the accessors declare and the positions' bounds.
            draco::DecoderBuffer input;
            input.Init(encoded.data(), encoded.size());
            draco::Decoder decoder;
            auto decoded = decoder.DecodeMeshFromBuffer(&input);
            if (!decoded.ok()) return bad(path, "Draco cannot decode what it encoded");
            const std::unique_ptr<draco::Mesh> result = std::move(decoded).value();

            const std::size_t offset =
                append(streams, reinterpret_cast<const unsigned char*>(encoded.data()), encoded.size());
            json["bufferViews"].push_back(
                {{"buffer", gltf.buffers.size()}, {"byteOffset", offset}, {"byteLength", encoded.size()}});
            Json extension{{"bufferView", json["bufferViews"].size() - 1}, {"attributes", Json::object()}};
            for (const auto& [name, id] : ids) {
                const draco::PointAttribute& attribute = *result->GetAttributeByUniqueId(std::uint32_t(id));
                Json accessor{{"componentType", name.rfind("JOINTS_", 0) == 0 ? 5123 : 5126},
                              {"count", result->num_points()},
                              {"type", json["accessors"][primitive["attributes"][name].get<std::size_t>()]["type"]}};
                if (name == "POSITION") {
                    float low[3] = {1e30f, 1e30f, 1e30f}, high[3] = {-1e30f, -1e30f, -1e30f};
                    for (draco::PointIndex p(0); p < result->num_points(); ++p) {
                        float v[3];
                        attribute.ConvertValue<float>(attribute.mapped_index(p), 3, v);
                        for (int c = 0; c < 3; ++c) {
                            low[c] = std::min(low[c], v[c]);
                            high[c] = std::max(high[c], v[c]);
                        }
                    }
                    accessor["min"] = {low[0], low[1], low[2]};
                    accessor["max"] = {high[0], high[1], high[2]};
                }
                primitive["attributes"][name] = addAccessor(json, accessor);
                extension["attributes"][name] = attribute.unique_id();
            }
            primitive["indices"] =
                addAccessor(json, {{"componentType", 5125}, {"count", result->num_faces() * 3}, {"type", "SCALAR"}});
            primitive["extensions"]["KHR_draco_mesh_compression"] = extension;
            any = true;
        }
    if (!any) return bad(path, "no TRIANGLES primitive to compress");
    require(json, "KHR_draco_mesh_compression");
    json["buffers"].push_back({{"byteLength", streams.size()}});
    gltf.buffers.push_back(std::move(streams));
    for (std::size_t b = 0; b < gltf.buffers.size(); ++b) {
        json["buffers"][b]["byteLength"] = gltf.buffers[b].size();
        json["buffers"][b]["uri"] = "data:application/octet-stream;base64," + base64(gltf.buffers[b]);
    }
    return json.dump(1, '\t');
}

// ---------------------------------------------------------------------------------------------
// EXT_meshopt_compression: every bufferView the codecs take, decoded into a placeholder buffer;
// the others, and the streams, packed into one buffer.

struct ViewUse {
    bool index = false, vertex = false, other = false;
    std::set<std::size_t> elementSizes;
    std::vector<std::size_t> accessors;
};

Result<std::string> compressMeshopt(Gltf gltf, const CompressOptions& options, const std::string& path) {
    Json& json = gltf.json;
    Json& views = json["bufferViews"];
    std::vector<ViewUse> uses(views.size());
    std::vector<bool> triangleIndices(json["accessors"].size(), false), vertex(json["accessors"].size(), false);
    std::vector<std::string> attributeOf(json["accessors"].size());
    for (const Json& mesh : json.value("meshes", Json::array()))
        for (const Json& primitive : mesh["primitives"]) {
            if (primitive.contains("indices"))
                triangleIndices[primitive["indices"].get<std::size_t>()] = primitive.value("mode", 4) == 4;
            for (const auto& [name, index] : primitive["attributes"].items()) {
                vertex[index.get<std::size_t>()] = true;
                attributeOf[index.get<std::size_t>()] = name;
            }
        }
    std::set<std::size_t> indexAccessors;
    for (const Json& mesh : json.value("meshes", Json::array()))
        for (const Json& primitive : mesh["primitives"])
            if (primitive.contains("indices")) indexAccessors.insert(primitive["indices"].get<std::size_t>());
    for (std::size_t a = 0; a < json["accessors"].size(); ++a) {
        const Json& accessor = json["accessors"][a];
        if (!accessor.contains("bufferView") || accessor.contains("sparse")) continue;
        ViewUse& use = uses[accessor["bufferView"].get<std::size_t>()];
        const bool index = indexAccessors.count(a) > 0;
        (index ? use.index : use.vertex) = true;
        use.elementSizes.insert(std::size_t(componentBytes(accessor["componentType"].get<int>()) *
                                            componentsOf(accessor["type"].get<std::string>())));
        use.accessors.push_back(a);
    }
    for (const Json& image : json.value("images", Json::array()))
        if (image.contains("bufferView")) uses[image["bufferView"].get<std::size_t>()].other = true;

    std::vector<std::string> filters(views.size());  // per view, "" = none
    if (options.meshoptFilters) {
        // Normals: 16-bit octahedral, SHORT normalised (KHR_mesh_quantization), stride 8; positions:
        // float with a 15-bit mantissa. Each in a view of its own.
        for (std::size_t a = 0; a < json["accessors"].size(); ++a) {
            Json& accessor = json["accessors"][a];
            if (!vertex[a] || !accessor.contains("bufferView") || accessor["componentType"] != 5126 ||
                accessor["type"] != "VEC3" || (attributeOf[a] != "NORMAL" && attributeOf[a] != "POSITION"))
                continue;
            const std::vector<float> values = gltf.floats(a);
            const std::size_t count = values.size() / 3;
            Bytes encoded;
            if (attributeOf[a] == "NORMAL") {
                std::vector<float> four(count * 4, 0.0f);
                for (std::size_t v = 0; v < count; ++v) std::copy_n(&values[v * 3], 3, &four[v * 4]);
                encoded.resize(count * 8);
                meshopt_encodeFilterOct(encoded.data(), count, 8, 16, four.data());
                accessor["componentType"] = 5122;
                accessor["normalized"] = true;
                require(json, "KHR_mesh_quantization");
            } else {
                encoded.resize(count * 12);
                meshopt_encodeFilterExp(encoded.data(), count, 12, 15, values.data());
            }
            // The filtered data in a view of its own (in a new buffer), which the codec then takes.
            gltf.buffers.push_back(encoded);
            json["buffers"].push_back({{"byteLength", encoded.size()}});
            Json view{{"buffer", gltf.buffers.size() - 1}, {"byteLength", encoded.size()}};
            if (attributeOf[a] == "NORMAL") view["byteStride"] = 8;
            for (ViewUse& use : uses)
                use.accessors.erase(std::remove(use.accessors.begin(), use.accessors.end(), a), use.accessors.end());
            views.push_back(view);
            uses.push_back({false, true, false, {attributeOf[a] == "NORMAL" ? std::size_t(8) : std::size_t(12)}, {a}});
            filters.resize(views.size());
            filters.back() = attributeOf[a] == "NORMAL" ? "OCTAHEDRAL" : "EXPONENTIAL";
            accessor["bufferView"] = views.size() - 1;
            accessor.erase("byteOffset");
        }
    }

    Bytes data;                   // the uncompressed views and the streams
    std::size_t placeholder = 0;  // bytes of decoded data
    bool any = false;
    const std::size_t dataBuffer = 0, fallback = 1;
    for (std::size_t v = 0; v < views.size(); ++v) {
        Json& view = views[v];
        const ViewUse& use = uses[v];
        const Bytes& source = gltf.buffers[view["buffer"].get<std::size_t>()];
        const unsigned char* bytes = source.data() + view.value("byteOffset", std::size_t(0));
        const std::size_t length = view["byteLength"].get<std::size_t>();
        std::size_t stride = view.value("byteStride", std::size_t(0));
        if (stride == 0 && use.elementSizes.size() == 1) stride = *use.elementSizes.begin();
        const bool indices = use.index && !use.vertex && !use.other && (stride == 2 || stride == 4);
        bool triangles = indices && options.meshoptTriangles && (length / stride) % 3 == 0;
        for (std::size_t a : use.accessors) triangles = triangles && triangleIndices[a];
        const bool attributes =
            !use.index && !use.other && !use.accessors.empty() && stride % 4 == 0 && stride > 0 && stride <= 256;
        if ((!indices && !attributes) || length % stride != 0) {
            const std::size_t offset = append(data, bytes, length);
            view["buffer"] = dataBuffer;
            view["byteOffset"] = offset;
            continue;
        }
        const std::size_t count = length / stride;
        Bytes encoded;
        const char* mode = "ATTRIBUTES";
        if (attributes) {
            encoded.resize(meshopt_encodeVertexBufferBound(count, stride));
            encoded.resize(meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), bytes, count, stride));
        } else {
            std::vector<unsigned> list(count);
            std::uint32_t vertices = 0;
            for (std::size_t i = 0; i < count; ++i) {
                std::uint32_t x = 0;
                std::memcpy(&x, bytes + i * stride, stride);
                list[i] = x;
                vertices = std::max(vertices, x + 1);
            }
            mode = triangles ? "TRIANGLES" : "INDICES";
            encoded.resize(triangles ? meshopt_encodeIndexBufferBound(count, vertices)
                                     : meshopt_encodeIndexSequenceBound(count, vertices));
            encoded.resize(triangles ? meshopt_encodeIndexBuffer(encoded.data(), encoded.size(), list.data(), count)
                                     : meshopt_encodeIndexSequence(encoded.data(), encoded.size(), list.data(), count));
        }
        if (encoded.empty()) return bad(path, "meshoptimizer cannot encode bufferView " + std::to_string(v));
        const std::size_t offset = append(data, encoded.data(), encoded.size());
        Json extension{{"buffer", dataBuffer}, {"byteOffset", offset}, {"byteLength", encoded.size()},
                       {"byteStride", stride}, {"count", count},       {"mode", mode}};
        if (v < filters.size() && !filters[v].empty()) extension["filter"] = filters[v];
        placeholder = (placeholder + 3) / 4 * 4;
        view["buffer"] = fallback;
        view["byteOffset"] = placeholder;
        placeholder += length;
        view["extensions"]["EXT_meshopt_compression"] = extension;
        any = true;
    }
    if (!any) return bad(path, "no bufferView the meshopt codecs take");
    require(json, "EXT_meshopt_compression");
    json["buffers"] = Json::array();
    json["buffers"].push_back(
        {{"byteLength", data.size()}, {"uri", "data:application/octet-stream;base64," + base64(data)}});
    json["buffers"].push_back({{"byteLength", std::max<std::size_t>(placeholder, 1)},
                               {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
    return json.dump(1, '\t');
}

}  // namespace

Result<std::string> compressGltf(const std::string& path, const CompressOptions& options) {
    Result<Gltf> gltf = readGltf(path);
    if (!gltf) return gltf.error();
    if (options.method == CompressOptions::Method::Draco) return compressDraco(std::move(*gltf), options, path);
    return compressMeshopt(std::move(*gltf), options, path);
}

}  // namespace frugal
