#include "scene/GltfCompression.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <memory>

#include <draco/compression/decode.h>
#include <draco/mesh/mesh.h>
#include <meshoptimizer.h>

namespace frugal::gltf {

namespace {

const Json& extension(const Json& object, const char* name) { return member(member(object, "extensions"), name); }

bool isCount(const Json& v) { return v.is_number_unsigned() || (v.is_number_integer() && v.get<std::int64_t>() >= 0); }

// An integer member of an extension object, at least `least`; `fallback` when it may be left out
// (else required).
std::size_t integer(const Json& object, const char* key, const std::string& where, std::size_t least,
                    const std::size_t* fallback = nullptr) {
    const Json& v = member(object, key);
    if (v.is_null() && fallback) return *fallback;
    if (v.is_null()) fail(where, ": '", key, "' is required");
    if (!isCount(v) || v.get<std::uint64_t>() < least)
        fail(child(where, key), ": ", describe(v), " is not an integer of at least ", least);
    if (v.get<std::uint64_t>() > std::numeric_limits<std::uint32_t>::max())
        fail(child(where, key), ": ", v.get<std::uint64_t>(), " is too large");
    return std::size_t(v.get<std::uint64_t>());
}

std::string text(const Json& object, const char* key, const std::string& where, const char* fallback) {
    const Json& v = member(object, key);
    if (v.is_null() && fallback) return fallback;
    if (v.is_null()) fail(where, ": '", key, "' is required");
    if (!v.is_string()) fail(child(where, key), ": ", describe(v), " is not a string");
    return v.get<std::string>();
}

constexpr const char* kModeNames[] = {"ATTRIBUTES", "TRIANGLES", "INDICES"};
constexpr const char* kFilterNames[] = {"NONE", "OCTAHEDRAL", "QUATERNION", "EXPONENTIAL"};

template <class Enum, std::size_t N>
Enum named(const std::string& value, const char* const (&names)[N], const std::string& where) {
    for (std::size_t i = 0; i < N; ++i)
        if (value == names[i]) return Enum(i);
    std::string allowed;
    for (std::size_t i = 0; i < N; ++i) allowed += cat(i == 0 ? "" : i + 1 == N ? " or " : ", ", names[i]);
    fail(where, ": \"", oneLine(value, 40), "\" is not ", allowed);
}

// The EXT_meshopt_compression object of bufferViews[v], checked as the extension's specification
// requires (strides and counts each mode and filter can decode).
// A buffer without data: no uri, and not the BIN chunk of a .glb (buffer 0).
bool dataless(const Json& buffers, std::size_t b, bool glb) { return !buffers[b].contains("uri") && !(glb && b == 0); }

MeshoptView meshoptView(const Json& view, std::size_t v, const Json& buffers, bool glb) {
    const std::string where = cat("bufferViews[", v, "].extensions.EXT_meshopt_compression");
    const Json& ext = extension(view, "EXT_meshopt_compression");
    MeshoptView out;
    out.view = v;
    static constexpr std::size_t kZero = 0;
    out.buffer = integer(ext, "buffer", where, 0);
    if (out.buffer >= buffers.size())
        fail(child(where, "buffer"), ": buffer ", out.buffer, " out of range, the file has ",
             plural(buffers.size(), "buffer", "buffers"));
    if (dataless(buffers, out.buffer, glb))
        fail(child(where, "buffer"), ": buffer ", out.buffer, " has no data (no uri), so holds no compressed stream");
    out.byteOffset = integer(ext, "byteOffset", where, 0, &kZero);
    out.byteLength = integer(ext, "byteLength", where, 1);
    out.byteStride = integer(ext, "byteStride", where, 1);
    out.count = integer(ext, "count", where, 1);
    out.mode = named<MeshoptView::Mode>(text(ext, "mode", where, nullptr), kModeNames, child(where, "mode"));
    out.filter = named<MeshoptView::Filter>(text(ext, "filter", where, "NONE"), kFilterNames, child(where, "filter"));

    const std::size_t stride = out.byteStride;
    using Mode = MeshoptView::Mode;
    using Filter = MeshoptView::Filter;
    const char* mode = kModeNames[int(out.mode)];
    if (out.mode == Mode::Attributes && (stride % 4 != 0 || stride > 256))
        fail(child(where, "byteStride"), ": ", stride, " is not a multiple of 4 up to 256, as ATTRIBUTES needs");
    if (out.mode != Mode::Attributes && stride != 2 && stride != 4)
        fail(child(where, "byteStride"), ": ", stride, " is not 2 or 4, as ", mode, " needs");
    if (out.mode == Mode::Triangles && out.count % 3 != 0)
        fail(child(where, "count"), ": ", out.count, " is not a multiple of 3, as TRIANGLES needs");
    if (out.mode != Mode::Attributes && out.filter != Filter::None)
        fail(child(where, "filter"), ": ", kFilterNames[int(out.filter)], " applies to ATTRIBUTES only, the mode is ",
             mode);
    if ((out.filter == Filter::Octahedral && stride != 4 && stride != 8) ||
        (out.filter == Filter::Quaternion && stride != 8))
        fail(child(where, "byteStride"), ": ", stride, " is not one the ", kFilterNames[int(out.filter)],
             " filter decodes (", out.filter == Filter::Octahedral ? "4 or 8" : "8", ")");

    const std::size_t decoded = out.count * stride;  // both below 2^32: no overflow
    const std::size_t viewLength = view["byteLength"].get<std::size_t>();
    if (decoded != viewLength)
        fail(where, ": count ", out.count, " x byteStride ", stride, " = ", decoded,
             " bytes, the bufferView's byteLength is ", viewLength);
    if (view.contains("byteStride") && view["byteStride"].get<std::size_t>() != stride)
        fail(child(where, "byteStride"), ": ", stride, ", the bufferView's is ", view["byteStride"].get<std::size_t>());
    // meshoptimizer's codecs shrink data at most 64:1 (two header bits for 16 equal bytes): a count
    // far beyond what the stream can hold (256:1) is refused before its bytes are allocated.
    if (decoded > kMaxDecodedBytes || decoded / 256 > out.byteLength + 4096)
        fail(where, ": ", decoded, " bytes cannot come from a stream of ", out.byteLength, " bytes");
    const std::size_t bufferLength = buffers[out.buffer]["byteLength"].get<std::size_t>();
    if (out.byteOffset + out.byteLength > bufferLength)
        fail(where, ": byteOffset ", out.byteOffset, " + byteLength ", out.byteLength, " is beyond the end of buffer ",
             out.buffer, " (", bufferLength, " bytes)");
    return out;
}

DracoPrimitive dracoPrimitive(const Json& primitive, std::size_t m, std::size_t p, std::size_t bufferViews) {
    const std::string where = cat("meshes[", m, "].primitives[", p, "].extensions.KHR_draco_mesh_compression");
    const Json& ext = extension(primitive, "KHR_draco_mesh_compression");
    DracoPrimitive out;
    out.mesh = m;
    out.primitive = p;
    out.bufferView = integer(ext, "bufferView", where, 0);
    if (out.bufferView >= bufferViews)
        fail(child(where, "bufferView"), ": bufferView ", out.bufferView, " out of range, the file has ",
             plural(bufferViews, "bufferView", "bufferViews"));
    out.mode = member(primitive, "mode").is_null() ? 4 : primitive["mode"].get<int>();
    if (out.mode != 4 && out.mode != 5)
        fail(where, ": the primitive's mode is ", out.mode, ", Draco holds TRIANGLES (4) or TRIANGLE_STRIP (5)");
    out.indices = member(primitive, "indices").is_null() ? -1 : primitive["indices"].get<int>();
    const Json& attributes = member(ext, "attributes");
    if (!attributes.is_object()) fail(child(where, "attributes"), ": ", describe(attributes), " is not an object");
    for (const auto& [name, id] : attributes.items()) {
        const std::string at = child(child(where, "attributes"), name);
        if (!isCount(id) || id.get<std::uint64_t>() > std::numeric_limits<std::uint32_t>::max())
            fail(at, ": ", describe(id), " is not an attribute id");
        if (!primitive["attributes"].contains(name)) fail(at, ": the primitive has no attribute ", oneLine(name, 40));
        out.attributes.push_back({name, std::uint32_t(id.get<std::uint64_t>())});
    }
    if (std::none_of(out.attributes.begin(), out.attributes.end(),
                     [](const DracoPrimitive::Attribute& a) { return a.name == "POSITION"; }))
        fail(child(where, "attributes"), ": no POSITION, the one attribute every drawn primitive has");
    return out;
}

}  // namespace

Compression findCompression(const Json& root, bool glb) {
    Compression out;
    const Json& buffers = member(root, "buffers");
    const Json& views = member(root, "bufferViews");
    for (std::size_t v = 0; v < views.size(); ++v)
        if (extension(views[v], "EXT_meshopt_compression").is_object())
            out.meshopt.push_back(meshoptView(views[v], v, buffers, glb));
    const Json& meshes = member(root, "meshes");
    for (std::size_t m = 0; m < meshes.size(); ++m) {
        const Json& primitives = meshes[m]["primitives"];
        for (std::size_t p = 0; p < primitives.size(); ++p)
            if (extension(primitives[p], "KHR_draco_mesh_compression").is_object())
                out.draco.push_back(dracoPrimitive(primitives[p], m, p, views.size()));
    }
    // meshopt's placeholder buffers: without data, the parent of compressed bufferViews, which
    // decode into them; no other view may read them. (A dataless buffer no compressed view names
    // is left to checkBuffers, which says it has no uri.)
    std::vector<bool> compressed(views.size(), false), placeholder(buffers.size(), false);
    for (const MeshoptView& view : out.meshopt) {
        compressed[view.view] = true;
        const std::size_t parent = views[view.view]["buffer"].get<std::size_t>();
        placeholder[parent] = dataless(buffers, parent, glb);
    }
    for (std::size_t v = 0; v < views.size(); ++v) {
        const std::size_t b = views[v]["buffer"].get<std::size_t>();
        if (placeholder[b] && !compressed[v])
            fail(cat("bufferViews[", v, "]"), ": buffer ", b,
                 " has no data (no uri: an EXT_meshopt_compression fallback), and the view is not compressed");
    }
    for (std::size_t b = 0; b < buffers.size(); ++b)
        if (placeholder[b]) out.fallbackBuffers.push_back(b);
    return out;
}

Json forTinygltf(const Json& root, const Compression& compression) {
    Json out = root;
    for (const DracoPrimitive& d : compression.draco) out["meshes"][d.mesh]["primitives"][d.primitive].erase("indices");
    for (std::size_t b : compression.fallbackBuffers)
        out["buffers"][b] = Json{{"byteLength", 1}, {"uri", "data:application/octet-stream;base64,AA=="}};
    return out;
}

std::vector<unsigned char> decodeMeshopt(const MeshoptView& view, std::span<const unsigned char> stream,
                                         const std::string& where) {
    using Mode = MeshoptView::Mode;
    using Filter = MeshoptView::Filter;
    // Checked by findCompression; meshoptimizer asserts them.
    if (view.byteStride == 0 || view.count == 0 || view.count * view.byteStride > kMaxDecodedBytes)
        fail(where, ": EXT_meshopt_compression: ", view.count, " elements of ", view.byteStride, " bytes");
    std::vector<unsigned char> out(view.count * view.byteStride);
    int status = -1;
    switch (view.mode) {
        case Mode::Attributes:
            status = meshopt_decodeVertexBuffer(out.data(), view.count, view.byteStride, stream.data(), stream.size());
            break;
        case Mode::Triangles:
            status = meshopt_decodeIndexBuffer(out.data(), view.count, view.byteStride, stream.data(), stream.size());
            break;
        case Mode::Indices:
            status = meshopt_decodeIndexSequence(out.data(), view.count, view.byteStride, stream.data(), stream.size());
            break;
    }
    if (status != 0)
        fail(where, ": EXT_meshopt_compression: the ", kModeNames[int(view.mode)], " stream of ", stream.size(),
             " bytes does not decode to ", view.count, " elements of ", view.byteStride, " bytes (meshoptimizer ",
             status == -1 ? "does not know its header" : "finds it malformed or short", ")");
    switch (view.filter) {
        case Filter::None:
            break;
        case Filter::Octahedral:
            meshopt_decodeFilterOct(out.data(), view.count, view.byteStride);
            break;
        case Filter::Quaternion:
            meshopt_decodeFilterQuat(out.data(), view.count, view.byteStride);
            break;
        case Filter::Exponential:
            meshopt_decodeFilterExp(out.data(), view.count, view.byteStride);
            break;
    }
    return out;
}

namespace {

std::size_t componentBytes(int componentType) {
    switch (componentType) {
        case kByte:
        case kUnsignedByte:
            return 1;
        case kShort:
        case kUnsignedShort:
            return 2;
        default:
            return 4;
    }
}

template <class T>
bool convert(const draco::PointAttribute& attribute, draco::AttributeValueIndex value, int components,
             unsigned char* out) {
    T v[4] = {};
    if (!attribute.ConvertValue<T>(value, std::int8_t(components), v)) return false;
    std::memcpy(out, v, sizeof(T) * std::size_t(components));
    return true;
}

bool convertAs(int componentType, const draco::PointAttribute& attribute, draco::AttributeValueIndex value,
               int components, unsigned char* out) {
    switch (componentType) {
        case kByte:
            return convert<std::int8_t>(attribute, value, components, out);
        case kUnsignedByte:
            return convert<std::uint8_t>(attribute, value, components, out);
        case kShort:
            return convert<std::int16_t>(attribute, value, components, out);
        case kUnsignedShort:
            return convert<std::uint16_t>(attribute, value, components, out);
        case kUnsignedInt:
            return convert<std::uint32_t>(attribute, value, components, out);
        default:
            return convert<float>(attribute, value, components, out);
    }
}

}  // namespace

DracoDecoded decodeDraco(std::span<const unsigned char> stream, std::span<const DracoRequest> requests,
                         const std::string& where) {
    const std::string at = where + ": KHR_draco_mesh_compression";
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(stream.data()), stream.size());
    draco::Decoder decoder;
    auto decodedMesh = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decodedMesh.ok() || !decodedMesh.value())
        fail(at, ": the ", stream.size(), "-byte stream does not decode (Draco: ",
             oneLine(decodedMesh.ok() ? std::string("no mesh") : decodedMesh.status().error_msg_string(), 80), ")");
    const std::unique_ptr<draco::Mesh> mesh = std::move(decodedMesh).value();

    DracoDecoded out;
    out.points = mesh->num_points();
    if (mesh->num_faces() == 0 || out.points == 0)
        fail(at, ": the stream holds ", mesh->num_faces(), " faces and ", out.points, " points, nothing to draw");
    out.indices.reserve(std::size_t(mesh->num_faces()) * 3);
    for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
        for (const draco::PointIndex& point : mesh->face(f)) {
            if (point.value() >= out.points)
                fail(at, ": face ", f.value(), " names point ", point.value(), ", the stream holds ", out.points);
            out.indices.push_back(point.value());
        }

    for (const DracoRequest& request : requests) {
        const std::string name = cat(at, ".attributes.", oneLine(request.name, 40));
        const draco::PointAttribute* attribute = mesh->GetAttributeByUniqueId(request.uniqueId);
        if (!attribute) fail(name, ": the stream has no attribute ", request.uniqueId);
        if (attribute->num_components() != request.components)
            fail(name, ": the stream's attribute has ", int(attribute->num_components()), " components, the accessor ",
                 request.components);
        if (!attribute->is_mapping_identity() && attribute->indices_map_size() < out.points)
            fail(name, ": the stream maps ", attribute->indices_map_size(), " of its ", out.points, " points");
        const std::size_t element = componentBytes(request.componentType) * std::size_t(request.components);
        std::vector<unsigned char> data(out.points * element);
        for (std::size_t p = 0; p < out.points; ++p) {
            const draco::AttributeValueIndex value = attribute->mapped_index(draco::PointIndex(std::uint32_t(p)));
            if (value.value() >= attribute->size() ||
                !convertAs(request.componentType, *attribute, value, request.components, &data[p * element]))
                fail(name, ": point ", p, "'s value does not fit the accessor's component type");
        }
        out.data.push_back(std::move(data));
    }
    return out;
}

}  // namespace frugal::gltf
