#include "scene/GltfStructure.h"

#include <algorithm>
#include <cstdint>
#include <string_view>
#include <system_error>

namespace frugal::gltf {

namespace {

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

void checkMeshReferences(const Json& root, const Collections& n) {
    const Json& accessors = member(root, "accessors");
    forEach(root, "meshes", "", [&](const Json& mesh, std::size_t, const std::string& meshWhere) {
        forEach(mesh, "primitives", meshWhere, [&](const Json& primitive, std::size_t, const std::string& where) {
            checkIndexMapValues(primitive["attributes"], n.accessors, child(where, "attributes"));
            checkIndex(primitive, "indices", n.accessors, where);
            checkIndex(primitive, "material", n.materials, where);
            forEach(primitive, "targets", where, [&](const Json& target, std::size_t, const std::string& targetWhere) {
                checkIndexMapValues(target, n.accessors, targetWhere);
            });
            // tinygltf rejects index accessors without a bufferView (all-zero or sparse-only); a
            // Draco primitive's indices are decoded from its stream (GltfCompression.h).
            const bool draco = member(member(primitive, "extensions"), "KHR_draco_mesh_compression").is_object();
            if (primitive.contains("indices") && !draco &&
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

}  // namespace

void checkStructure(const Json& root) {
    const Collections n(root);
    checkAsset(root["asset"]);
    checkMeshReferences(root, n);
    checkMaterialReferences(root, n);
    checkAnimationReferences(root, n);
    checkNodeGraph(root, n);
    checkCameras(root);
}

void checkBuffers(const Json& root, const std::filesystem::path& dir, const GlbParts* glb, DataUriDecoder decodeDataUri,
                  const std::vector<std::size_t>& placeholders) {
    forEach(root, "buffers", "", [&](const Json& buffer, std::size_t i, const std::string& where) {
        if (std::find(placeholders.begin(), placeholders.end(), i) != placeholders.end()) return;
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
            if (!decodeDataUri(uri, data) || data.empty())
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

std::vector<std::string> usedExtensions(const Json& root) {
    std::vector<std::string> extensions;
    for (const char* key : {"extensionsUsed", "extensionsRequired"})
        for (const Json& name : member(root, key)) addUnique(extensions, name.get<std::string>());
    collectExtensions(root, extensions);
    return extensions;
}

}  // namespace frugal::gltf
