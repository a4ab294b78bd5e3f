// Wavefront OBJ loader on top of tinyobjloader (Debian 2.0.0rc10, float build).
//
// tinyobjloader is asked not to triangulate: its triangulation reads positions through face indices
// it has not checked (a wrong index in the file is an out-of-bounds read), and it silently skips some
// bad faces. So faces come back as polygons, every index is validated here, and polygons are split:
// quads along their shorter diagonal (as tinyobjloader does), larger polygons as fans, which assumes
// they are convex and planar, as OBJ exporters write them.
//
// Conventions: texture v is flipped (v' = 1 − v) so that uv (0,0) is the first row of the image, as in
// glTF (Scene.h). Materials become dielectrics (metallic 0): Kd the base colour, the Phong exponent Ns
// a roughness (objRoughness); a face without a material gets Ns 0, the roughest. One Mesh per
// (shape, material), one root node per shape. OBJ has no culling flag: LoadOptions::objDoubleSided decides.
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "scene/Load.h"
#include "scene/LoadSupport.h"
#include "scene/MeshBuild.h"

namespace frugal {

namespace {

using namespace load;

// tinyobjloader's number parser overflows an int (undefined behaviour) on an exponent of 10 digits
// or more, such as 1e2147483648, so text with one is refused before it is parsed; a float ends at
// 1e38, so no number anyone writes has one. Returns "" or the problem, with its line.
std::string exponentProblem(std::string_view text) {
    for (std::size_t i = 1; i < text.size(); ++i) {
        const bool afterMantissa = std::isdigit(static_cast<unsigned char>(text[i - 1])) || text[i - 1] == '.';
        if ((text[i] != 'e' && text[i] != 'E') || !afterMantissa) continue;
        std::size_t k = i + 1;
        if (k < text.size() && (text[k] == '+' || text[k] == '-')) ++k;
        while (k < text.size() && text[k] == '0') ++k;
        std::size_t digits = 0;
        while (k + digits < text.size() && std::isdigit(static_cast<unsigned char>(text[k + digits]))) ++digits;
        if (digits >= 10)
            return cat("line ", std::count(text.begin(), text.begin() + std::ptrdiff_t(i), '\n') + 1,
                       ": a number with an exponent of ", digits, " digits (floats end at 1e38)");
    }
    return {};
}

// Whether a number that std::from_chars found out of a double's range is too large (else it is too
// small and reads as 0): the decimal order of its first significant digit, plus its exponent.
bool overflows(std::string_view word) {
    std::size_t i = (word[0] == '-') ? 1 : 0;
    long order = 0;
    bool significant = false;
    for (; i < word.size() && word[i] != 'e' && word[i] != 'E'; ++i) {
        if (word[i] == '.') {
            if (significant) break;
            for (++i; i < word.size() && word[i] == '0'; ++i) --order;
            break;
        }
        if (word[i] != '0' || significant) {
            significant = true;
            ++order;
        }
    }
    const std::size_t e = word.find_first_of("eE");
    if (e != std::string_view::npos) {
        long exponent = 0;  // at most 9 digits: exponentProblem has run
        std::from_chars(word.data() + e + 1 + (word[e + 1] == '+' ? 1 : 0), word.data() + word.size(), exponent);
        order += exponent;
    }
    return order > 0;
}

// tinyobjloader reads a word it cannot parse as a number as 0, without a word: `v nan 0 0`,
// `v 1 x 0` and `v 0 0` all put a vertex where the file does not. So v, vn and vt lines are read here
// first: v and vn need three numbers, vt one, and every word on them (up to a '#') must be a finite
// float. Returns "" or the problem, with its line.
std::string vertexLineProblem(std::string_view text) {
    // The least double that rounds to infinity as a float: past the largest float by half its step
    // (2^104; a tie rounds to even, infinity). 3.4028235e38, the largest float printed with 8 digits,
    // lies above the largest float and is still one.
    const double kFloatOverflow = double(std::numeric_limits<float>::max()) + std::ldexp(1.0, 103);
    std::size_t line = 0;
    std::vector<std::string_view> words;
    for (std::size_t begin = 0; begin < text.size();) {
        // Lines end at "\n", "\r\n" or "\r", as tinyobjloader reads them.
        std::size_t end = text.find_first_of("\r\n", begin);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view rest = text.substr(begin, end - begin);
        begin = end + ((end + 1 < text.size() && text[end] == '\r' && text[end + 1] == '\n') ? 2 : 1);
        ++line;

        words.clear();
        for (std::size_t i = 0; i < rest.size();) {
            i = rest.find_first_not_of(" \t", i);
            if (i == std::string_view::npos || rest[i] == '#') break;
            const std::size_t j = std::min(rest.find_first_of(" \t", i), rest.size());
            words.push_back(rest.substr(i, j - i));
            i = j;
        }
        if (words.empty() || (words[0] != "v" && words[0] != "vn" && words[0] != "vt")) continue;
        const std::size_t needed = words[0] == "vt" ? 1 : 3;
        if (words.size() - 1 < needed)
            return cat("line ", line, ": a ", words[0], " line needs ", needed, needed == 1 ? " number" : " numbers",
                       ", it has ", words.size() - 1);
        for (std::size_t k = 1; k < words.size(); ++k) {
            const std::string_view word = words[k];
            const std::string_view digits =
                (word.size() > 1 && word[0] == '+' && word[1] != '-') ? word.substr(1) : word;
            double value = 0.0;
            const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
            const std::string shown = "'" + oneLine(word, 40) + "'";
            if (ptr != digits.data() + digits.size() || (ec != std::errc() && ec != std::errc::result_out_of_range))
                return cat("line ", line, ": ", shown, " in a ", words[0], " line is not a number");
            if (ec == std::errc() && !std::isfinite(value))
                return cat("line ", line, ": ", shown, " in a ", words[0], " line is not finite");
            if ((ec == std::errc::result_out_of_range && overflows(digits)) || std::abs(value) >= kFloatOverflow)
                return cat("line ", line, ": ", shown, " in a ", words[0],
                           " line does not fit a float (floats end at 3.4e38)");
        }
    }
    return {};
}

// Reads "mtllib" files relative to the OBJ's folder. tinyobjloader's own reader splits its base
// directory at ':' (a search path), which breaks folders whose name contains one.
class MtlReader : public tinyobj::MaterialReader {
public:
    explicit MtlReader(std::filesystem::path dir) : dir_(std::move(dir)) {}
    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* names, std::string* warn, std::string* err) override {
        // Regular files only: a device such as /dev/zero never ends.
        const std::filesystem::path file = dir_ / name;
        std::error_code ec;
        std::ifstream in;
        if (std::filesystem::is_regular_file(file, ec)) in.open(file);
        if (!in.is_open()) {
            const bool exists = std::filesystem::exists(file, ec);
            if (warn) *warn += "material library '" + name + (exists ? "' is not a readable file\n" : "' not found\n");
            return false;
        }
        const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
        if (const std::string problem = exponentProblem(text); !problem.empty()) {
            if (warn) *warn += "material library '" + name + "' not read: " + problem + "\n";
            return false;
        }
        std::istringstream stream(text);
        tinyobj::LoadMtl(names, materials, &stream, warn, err);
        return true;
    }

private:
    std::filesystem::path dir_;
};

struct ObjData {
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::vector<std::string> warnings;
};

ObjData parseObj(std::string_view bytes, const std::string& path) {
    if (bytes.empty()) fail("file is empty");
    if (const std::string problem = exponentProblem(bytes); !problem.empty()) fail(problem);
    if (const std::string problem = vertexLineProblem(bytes); !problem.empty()) fail(problem);
    std::istringstream in{std::string(bytes)};
    MtlReader mtl(std::filesystem::path(path).parent_path());
    ObjData obj;
    std::string warnings, errors;
    const bool ok = tinyobj::LoadObj(&obj.attrib, &obj.shapes, &obj.materials, &warnings, &errors, &in, &mtl,
                                     /*triangulate=*/false, /*default_vcols_fallback=*/false);
    if (!ok) fail(oneLine(errors.empty() ? "tinyobjloader failed" : errors));
    // Non-fatal errors (a broken .mtl) are kept as warnings, one per line. tinyobjloader follows a
    // library it could not read with a line of its own, which says less than MtlReader's.
    std::istringstream lines(warnings + errors);
    for (std::string line; std::getline(lines, line);)
        if (!oneLine(line).empty() && line != "Failed to load material file(s). Use default material.")
            obj.warnings.push_back(oneLine(line));
    return obj;
}

// The number of faces tinyobjloader records per polygon is an unsigned char: a polygon of more than
// 255 vertices leaves the face list out of step with the index list.
void checkFaces(const tinyobj::shape_t& shape, const std::string& where) {
    std::size_t total = 0;
    for (unsigned char n : shape.mesh.num_face_vertices) total += n;
    if (total != shape.mesh.indices.size())
        fail(where, ": a face has more than 255 vertices, which tinyobjloader cannot represent");
}

// tinyobjloader has already resolved relative (negative) indices against the counts read so far and
// made them 0-based; -1 marks an absent texcoord or normal.
void checkIndex(int index, std::size_t count, bool optional, const char* what, const std::string& where) {
    if (optional && index == -1) return;
    if (index < 0) fail(where, ": a relative ", what, " index points before the first ", what);
    if (std::size_t(index) >= count)
        fail(where, ": ", what, " index ", index + 1, " out of range, the file has ", count, " ", what, "s");
}

struct VertexKey {
    int v, vt, vn;
    bool operator==(const VertexKey&) const = default;
};

struct VertexKeyHash {
    std::size_t operator()(const VertexKey& k) const {
        return std::size_t(std::uint32_t(k.v)) * 0x9E3779B97F4A7C15ull ^
               std::size_t(std::uint32_t(k.vt)) * 0xC2B2AE3Dull ^ std::size_t(std::uint32_t(k.vn)) * 0x165667B1ull;
    }
};

// Builds one mesh from the faces of `shape` that use `material`, re-indexing the (v, vt, vn) triples
// the faces use into one vertex list.
class MeshBuilder {
public:
    MeshBuilder(const tinyobj::attrib_t& attrib, Mesh& mesh) : attrib_(attrib), mesh_(mesh) {}

    void addFace(const tinyobj::index_t* corners, std::size_t n) {
        std::uint32_t v[256];
        for (std::size_t k = 0; k < n; ++k) v[k] = vertex(corners[k]);
        if (n == 4) {
            const glm::vec3 &p0 = mesh_.positions[v[0]], &p1 = mesh_.positions[v[1]], &p2 = mesh_.positions[v[2]],
                            &p3 = mesh_.positions[v[3]];
            const glm::vec3 d02 = p2 - p0, d13 = p3 - p1;
            if (glm::dot(d02, d02) < glm::dot(d13, d13)) {
                triangle(v[0], v[1], v[2]);
                triangle(v[0], v[2], v[3]);
            } else {
                triangle(v[0], v[1], v[3]);
                triangle(v[1], v[2], v[3]);
            }
            return;
        }
        for (std::size_t k = 1; k + 1 < n; ++k) triangle(v[0], v[k], v[k + 1]);
    }

    // Normals are kept only if every vertex has one (finalizeMesh computes them otherwise); texture
    // coordinates if any vertex has one (the others get (0, 0)).
    void finish() {
        if (!allNormals_) mesh_.normals.clear();
        if (!anyUv_) mesh_.uvs.clear();
    }

private:
    const tinyobj::attrib_t& attrib_;
    Mesh& mesh_;
    std::unordered_map<VertexKey, std::uint32_t, VertexKeyHash> index_;
    bool allNormals_ = true;
    bool anyUv_ = false;

    std::uint32_t vertex(const tinyobj::index_t& corner) {
        const VertexKey key{corner.vertex_index, corner.texcoord_index, corner.normal_index};
        const auto [it, inserted] = index_.try_emplace(key, std::uint32_t(mesh_.positions.size()));
        if (!inserted) return it->second;
        const std::size_t v = std::size_t(key.v);
        mesh_.positions.emplace_back(attrib_.vertices[3 * v], attrib_.vertices[3 * v + 1], attrib_.vertices[3 * v + 2]);
        if (!attrib_.colors.empty())
            mesh_.colors.emplace_back(attrib_.colors[3 * v], attrib_.colors[3 * v + 1], attrib_.colors[3 * v + 2],
                                      1.0f);
        if (key.vn >= 0) {
            const std::size_t n = std::size_t(key.vn);
            mesh_.normals.emplace_back(attrib_.normals[3 * n], attrib_.normals[3 * n + 1], attrib_.normals[3 * n + 2]);
        } else {
            allNormals_ = false;
            mesh_.normals.emplace_back(0.0f);
        }
        if (key.vt >= 0) {
            const std::size_t t = std::size_t(key.vt);
            mesh_.uvs.emplace_back(attrib_.texcoords[2 * t], 1.0f - attrib_.texcoords[2 * t + 1]);
            anyUv_ = true;
        } else {
            mesh_.uvs.emplace_back(0.0f);
        }
        return it->second;
    }

    void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        mesh_.indices.insert(mesh_.indices.end(), {a, b, c});
    }
};

// GGX roughness of a Blinn-Phong exponent: the lobes match when alpha² = 2 / (Ns + 2) (Walter et
// al. 2007), and perceptual roughness is √alpha. Ns 0 gives 1; Ns 1000, 0.21.
float objRoughness(float ns) {
    const float exponent = std::isfinite(ns) ? std::max(ns, 0.0f) : 0.0f;
    return std::sqrt(std::sqrt(2.0f / (exponent + 2.0f)));
}

class ObjConverter {
public:
    ObjConverter(const ObjData& obj, const std::string& path, const LoadOptions& options)
        : obj_(obj), path_(path), options_(options), materialUsed_(obj.materials.size(), false) {}

    Scene run() {
        scene_.source = path_;
        for (const std::string& warning : obj_.warnings)
            scene_.warnings.push_back(cat(shownPath(path_), ": ", warning));
        for (const tinyobj::material_t& src : obj_.materials) {
            Material material;
            material.name = src.name;
            material.baseColorFactor = glm::vec4(src.diffuse[0], src.diffuse[1], src.diffuse[2], 1.0f);
            material.doubleSided = options_.objDoubleSided;
            material.metallicFactor = 0.0f;
            material.roughnessFactor = objRoughness(src.shininess);
            scene_.materials.push_back(material);
        }
        for (std::size_t s = 0; s < obj_.shapes.size(); ++s) convertShape(s);
        for (std::size_t m = 0; m < obj_.materials.size(); ++m)
            if (materialUsed_[m] && !obj_.materials[m].diffuse_texname.empty()) report("map_Kd textures");
        if (scene_.meshes.empty()) scene_.warnings.push_back(shownPath(path_) + ": no faces to draw");
        scene_.buildInstances();
        return std::move(scene_);
    }

private:
    const ObjData& obj_;
    const std::string& path_;
    const LoadOptions& options_;
    Scene scene_;
    int defaultMaterial_ = -1;  // created when a face has no (known) material
    std::vector<bool> materialUsed_;

    void report(const std::string& feature) {
        if (std::find(scene_.unsupported.begin(), scene_.unsupported.end(), feature) == scene_.unsupported.end())
            scene_.unsupported.push_back(feature);
    }

    int materialFor(int id) {
        if (id >= 0 && std::size_t(id) < obj_.materials.size()) {
            materialUsed_[std::size_t(id)] = true;
            return id;
        }
        if (defaultMaterial_ < 0) {
            defaultMaterial_ = int(scene_.materials.size());
            Material fallback;
            fallback.name = "default";
            fallback.doubleSided = options_.objDoubleSided;
            fallback.metallicFactor = 0.0f;
            fallback.roughnessFactor = objRoughness(0.0f);
            scene_.materials.push_back(fallback);
        }
        return defaultMaterial_;
    }

    // Validates every index of the shape and groups its faces by material, in order of first use.
    struct FaceGroups {
        std::vector<std::size_t> start;  // per face: its first entry in shape.mesh.indices
        std::vector<int> materials;
        std::vector<std::vector<std::size_t>> faces;
    };
    FaceGroups groupFaces(const tinyobj::shape_t& shape, const std::string& where) {
        const tinyobj::attrib_t& attrib = obj_.attrib;
        const std::size_t positions = attrib.vertices.size() / 3, texcoords = attrib.texcoords.size() / 2,
                          normals = attrib.normals.size() / 3;
        FaceGroups groups;
        std::size_t offset = 0;
        for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
            groups.start.push_back(offset);
            const std::string face = cat(where, " face ", f + 1);
            for (std::size_t k = 0; k < shape.mesh.num_face_vertices[f]; ++k, ++offset) {
                const tinyobj::index_t& corner = shape.mesh.indices[offset];
                checkIndex(corner.vertex_index, positions, false, "position", face);
                checkIndex(corner.texcoord_index, texcoords, true, "texcoord", face);
                checkIndex(corner.normal_index, normals, true, "normal", face);
            }
            const int material = materialFor(f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1);
            const auto it = std::find(groups.materials.begin(), groups.materials.end(), material);
            const std::size_t g = std::size_t(it - groups.materials.begin());
            if (it == groups.materials.end()) {
                groups.materials.push_back(material);
                groups.faces.emplace_back();
            }
            groups.faces[g].push_back(f);
        }
        return groups;
    }

    void convertShape(std::size_t s) {
        const tinyobj::shape_t& shape = obj_.shapes[s];
        const std::string name = shape.name.empty() ? cat("shape ", s) : shape.name;
        const std::string where = shape.name.empty() ? name : cat("shape '", oneLine(name, 60), "'");
        checkFaces(shape, where);
        if (!shape.lines.indices.empty()) report("OBJ lines (l)");
        if (!shape.points.indices.empty()) report("OBJ points (p)");
        const FaceGroups groups = groupFaces(shape, where);

        Node node;
        node.name = name;
        for (std::size_t g = 0; g < groups.materials.size(); ++g) {
            Mesh mesh;
            mesh.name = name;
            if (groups.materials.size() > 1)
                mesh.name += " (" + scene_.materials[std::size_t(groups.materials[g])].name + ")";
            mesh.material = groups.materials[g];
            MeshBuilder builder(obj_.attrib, mesh);
            for (std::size_t f : groups.faces[g])
                builder.addFace(&shape.mesh.indices[groups.start[f]], shape.mesh.num_face_vertices[f]);
            builder.finish();
            const MeshBuildStats stats = finalizeMesh(mesh, options_.optimizeOrder);
            if (stats.droppedNonFinite > 0)
                scene_.warnings.push_back(cat(shownPath(path_), ": mesh '", oneLine(mesh.name, 60), "': dropped ",
                                              stats.droppedNonFinite, " triangles with non-finite positions"));
            node.meshes.push_back(int(scene_.meshes.size()));
            scene_.meshes.push_back(std::move(mesh));
        }
        scene_.roots.push_back(int(scene_.nodes.size()));
        scene_.nodes.push_back(std::move(node));
    }
};

Scene loadObjOrThrow(std::string_view bytes, const std::string& path, const LoadOptions& options) {
    const ObjData obj = parseObj(bytes, path);
    return ObjConverter(obj, path, options).run();
}

}  // namespace

Result<Scene> loadObj(const std::string& path, const LoadOptions& options) {
    return load::guard(path, [&] { return loadObjOrThrow(load::readFile(path), path, options); });
}

Result<Scene> loadObjFromMemory(std::string_view bytes, const std::string& name, const LoadOptions& options) {
    return load::guard(name, [&] { return loadObjOrThrow(bytes, name, options); });
}

}  // namespace frugal
