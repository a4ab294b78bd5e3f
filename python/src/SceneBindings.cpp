// The scene half of the module: frugal.Scene (built from numpy arrays or loaded), frugal.load and
// frugal.Camera.
#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <frugal/Camera.h>
#include <frugal/Scene.h>

#include "Arrays.h"
#include "Bindings.h"

namespace frugal::python {

namespace {

// --- scenes ------------------------------------------------------------------------------------

Wrap wrapFrom(const std::string& name) {
    if (name == "repeat") return Wrap::Repeat;
    if (name == "clamp") return Wrap::ClampToEdge;
    if (name == "mirror") return Wrap::MirroredRepeat;
    throw InputError{"wrap: '" + name + "' is not a mode (repeat, clamp, mirror)"};
}

Filter filterFrom(const char* what, const std::string& name) {
    if (name != "linear" && name != "nearest")
        throw InputError{std::string(what) + ": '" + name + "' is not a filter (linear, nearest)"};
    return name == "nearest" ? Filter::Nearest : Filter::Linear;
}

int addTexture(PyScene& s, const py::handle& pixels, const std::string& wrap, const std::string& filter,
               const std::optional<std::string>& minFilter, const std::string& mipmaps, bool srgb,
               const std::string& name) {
    Pixels p = pixelsFrom(pixels);
    Texture texture;
    texture.name = name;
    texture.width = p.width;
    texture.height = p.height;
    texture.rgba = std::move(p.rgba);
    texture.wrapS = texture.wrapT = wrapFrom(wrap);
    texture.filter = filterFrom("filter", filter);
    texture.minFilter = minFilter ? filterFrom("min_filter", *minFilter) : texture.filter;
    if (mipmaps != "none" && mipmaps != "nearest" && mipmaps != "linear")
        throw InputError{"mipmaps: '" + mipmaps + "' is not a mipmap filter (none, nearest, linear)"};
    texture.mipmaps = mipmaps == "none"      ? MipFilter::None
                      : mipmaps == "nearest" ? MipFilter::Nearest
                                             : MipFilter::Linear;
    texture.srgb = srgb;
    return take(s.scene.addTexture(std::move(texture)));
}

int addMaterial(PyScene& s, const py::handle& color, std::optional<int> texture, bool doubleSided, double metallic,
                double roughness, bool unlit, const py::handle& emissive, std::optional<int> metallicRoughnessTexture,
                std::optional<int> occlusionTexture, double occlusionStrength, std::optional<int> emissiveTexture,
                std::optional<int> normalTexture, double normalScale, const std::string& alpha, double alphaCutoff,
                const py::handle& specular, double glossiness, std::optional<int> specularGlossinessTexture,
                double clearcoat, double clearcoatRoughness, std::optional<int> clearcoatTexture,
                std::optional<int> clearcoatRoughnessTexture, std::optional<int> clearcoatNormalTexture,
                double clearcoatNormalScale, const std::string& name) {
    if (alpha != "opaque" && alpha != "mask" && alpha != "blend")
        throw InputError{"alpha: '" + alpha + "' is not an alpha mode (opaque, mask, blend)"};
    Material material;
    material.name = name;
    material.baseColorFactor = colorFrom(color, "color");
    material.baseColorTexture = texture.value_or(-1);
    material.doubleSided = doubleSided;
    material.metallicFactor = float(metallic);
    material.roughnessFactor = float(roughness);
    material.unlit = unlit;
    material.emissiveFactor = vectorFrom<3>(emissive, "emissive");
    material.metallicRoughnessTexture = metallicRoughnessTexture.value_or(-1);
    material.occlusionTexture = occlusionTexture.value_or(-1);
    material.occlusionStrength = float(occlusionStrength);
    material.emissiveTexture = emissiveTexture.value_or(-1);
    material.normalTexture = normalTexture.value_or(-1);
    material.normalScale = float(normalScale);
    material.alphaMode = alpha == "mask" ? AlphaMode::Mask : alpha == "blend" ? AlphaMode::Blend : AlphaMode::Opaque;
    material.alphaCutoff = float(alphaCutoff);
    material.specularGlossiness = !specular.is_none();
    if (material.specularGlossiness) material.specularFactor = vectorFrom<3>(specular, "specular");
    material.glossinessFactor = float(glossiness);
    material.specularGlossinessTexture = specularGlossinessTexture.value_or(-1);
    material.clearcoatFactor = float(clearcoat);
    material.clearcoatRoughnessFactor = float(clearcoatRoughness);
    material.clearcoatTexture = clearcoatTexture.value_or(-1);
    material.clearcoatRoughnessTexture = clearcoatRoughnessTexture.value_or(-1);
    material.clearcoatNormalTexture = clearcoatNormalTexture.value_or(-1);
    material.clearcoatNormalScale = float(clearcoatNormalScale);
    return take(s.scene.addMaterial(std::move(material)));
}

int addMesh(PyScene& s, const py::handle& positions, const py::handle& indices, const py::handle& normals,
            const py::handle& colors, const py::handle& uvs, const py::handle& tangents, std::optional<int> material,
            const std::string& name, bool fileOrder, const std::string& topology) {
    Mesh mesh;
    mesh.name = name;
    if (!topologyNamed(topology, mesh.topology))
        throw InputError{"topology: '" + topology + "' is not a topology (triangles, lines, points)"};
    mesh.positions = vectorsFrom<3>(positions, "positions");
    mesh.indices = indicesFrom(indices, py::ssize_t(verticesPerPrimitive(mesh.topology)));
    if (!normals.is_none()) mesh.normals = vectorsFrom<3>(normals, "normals");
    if (!colors.is_none()) mesh.colors = colorsFrom(colors);
    if (!uvs.is_none()) mesh.uvs = vectorsFrom<2>(uvs, "uvs");
    if (!tangents.is_none()) mesh.tangents = vectorsFrom<4>(tangents, "tangents");
    mesh.material = material.value_or(-1);
    py::gil_scoped_release unlocked;  // normals and the vertex-cache order
    return take(s.scene.addMesh(std::move(mesh), !fileOrder));
}

int addInstance(PyScene& s, int mesh, const py::handle& transform, const std::string& name) {
    const glm::mat4 m = transform.is_none() ? glm::mat4(1.0f) : matrixFrom(transform, "transform");
    const int node = take(s.scene.addInstance(mesh, m, name));
    s.dirty = true;
    return node;
}

int addLight(PyScene& s, const std::string& kind, const py::handle& color, double intensity, double range,
             double innerCone, double outerCone, const py::handle& transform, const std::string& name) {
    PunctualLight light;
    light.name = name;
    if (!lightTypeNamed(kind, light.type))
        throw InputError{"kind: '" + kind + "' is not a kind of light (directional, point, spot)"};
    light.color = vectorFrom<3>(color, "color");
    light.intensity = float(intensity);
    light.range = float(range);
    light.innerConeAngle = float(innerCone);
    light.outerConeAngle = float(outerCone);
    const glm::mat4 m = transform.is_none() ? glm::mat4(1.0f) : matrixFrom(transform, "transform");
    const int node = take(s.scene.addLight(std::move(light), m, name));
    s.dirty = true;
    return node;
}

// The drawn instances in draw order: node, mesh, first id (a triangle's id is first_id plus its
// index in the mesh's source, 0 = background) and triangle count.
py::list instanceList(Scene& scene) {
    py::list out;
    for (const Instance& instance : scene.instances) {
        py::dict d;
        d["node"] = instance.node;
        d["mesh"] = instance.mesh;
        d["first_id"] = instance.firstId;
        d["triangles"] = scene.meshes[std::size_t(instance.mesh)].triangleCount();
        d["primitives"] = scene.meshes[std::size_t(instance.mesh)].primitiveCount();
        out.append(d);
    }
    return out;
}

py::list materialList(const Scene& scene) {
    py::list out;
    for (const Material& m : scene.materials) {
        py::dict d;
        d["name"] = m.name;
        d["color"] = py::make_tuple(m.baseColorFactor.r, m.baseColorFactor.g, m.baseColorFactor.b, m.baseColorFactor.a);
        d["texture"] = m.baseColorTexture < 0 ? py::object(py::none()) : py::object(py::int_(m.baseColorTexture));
        d["double_sided"] = m.doubleSided;
        d["metallic"] = m.metallicFactor;
        d["roughness"] = m.roughnessFactor;
        d["unlit"] = m.unlit;
        d["emissive"] = py::make_tuple(m.emissiveFactor.r, m.emissiveFactor.g, m.emissiveFactor.b);
        const auto index = [](int t) { return t < 0 ? py::object(py::none()) : py::object(py::int_(t)); };
        d["metallic_roughness_texture"] = index(m.metallicRoughnessTexture);
        d["occlusion_texture"] = index(m.occlusionTexture);
        d["occlusion_strength"] = m.occlusionStrength;
        d["emissive_texture"] = index(m.emissiveTexture);
        d["normal_texture"] = index(m.normalTexture);
        d["normal_scale"] = m.normalScale;
        d["alpha"] = m.alphaMode == AlphaMode::Mask ? "mask" : m.alphaMode == AlphaMode::Blend ? "blend" : "opaque";
        d["alpha_cutoff"] = m.alphaCutoff;
        d["specular"] = m.specularGlossiness ? py::object(py::make_tuple(m.specularFactor.r, m.specularFactor.g,
                                                                          m.specularFactor.b))
                                             : py::object(py::none());
        d["glossiness"] = m.glossinessFactor;
        d["specular_glossiness_texture"] = index(m.specularGlossinessTexture);
        d["clearcoat"] = m.clearcoatFactor;
        d["clearcoat_roughness"] = m.clearcoatRoughnessFactor;
        d["clearcoat_texture"] = index(m.clearcoatTexture);
        d["clearcoat_roughness_texture"] = index(m.clearcoatRoughnessTexture);
        d["clearcoat_normal_texture"] = index(m.clearcoatNormalTexture);
        d["clearcoat_normal_scale"] = m.clearcoatNormalScale;
        out.append(d);
    }
    return out;
}

py::array worldMatrix(PyScene& s, int node, double time) {
    if (node < 0 || node >= int(s.scene.nodes.size()))
        throw InputError{"node " + std::to_string(node) + " does not exist (the scene has " +
                         std::to_string(s.scene.nodes.size()) + ")"};
    if (!std::isfinite(time)) throw InputError{"time: " + std::to_string(time) + " is not finite"};
    return matrixArray(s.scene.worldTransforms(time)[std::size_t(node)]);
}

py::dict cameraDict(const SceneCamera& c) {
    py::dict d;
    d["name"] = c.name;
    d["node"] = c.node;
    d["perspective"] = c.perspective;
    d["yfov_degrees"] = glm::degrees(c.yfov);
    d["aspect_ratio"] = c.fileAspect();
    d["znear"] = c.znear;
    d["zfar"] = c.zfar;
    return d;
}

// One mesh's arrays (copies), as add_mesh takes them: (N, 3) float32 positions and normals,
// (T, 3) uint32 indices in the drawing order, triangle_source (T,) uint32, colours and uvs when
// the mesh has them, and its material.
template <class T, class V>
py::array_t<T> rowsOf(const std::vector<V>& values, py::ssize_t columns) {
    py::array_t<T> array({py::ssize_t(values.size()), columns});
    if (!values.empty()) std::memcpy(array.mutable_data(), values.data(), values.size() * sizeof(V));
    return array;
}

py::dict meshDict(const Mesh& mesh) {
    const auto rows = [](const auto& values, py::ssize_t columns, auto zero) {
        return rowsOf<decltype(zero)>(values, columns);
    };
    py::dict d;
    d["name"] = mesh.name;
    d["positions"] = rows(mesh.positions, 3, 0.0f);
    d["normals"] = rows(mesh.normals, 3, 0.0f);
    d["topology"] = topologyName(mesh.topology);
    py::array_t<std::uint32_t> indices(
        {py::ssize_t(mesh.primitiveCount()), py::ssize_t(verticesPerPrimitive(mesh.topology))});
    if (!mesh.indices.empty()) std::memcpy(indices.mutable_data(), mesh.indices.data(), mesh.indices.size() * 4);
    d["indices"] = indices;
    py::array_t<std::uint32_t> source(py::ssize_t(mesh.triangleSource.size()));
    if (!mesh.triangleSource.empty())
        std::memcpy(source.mutable_data(), mesh.triangleSource.data(), mesh.triangleSource.size() * 4);
    d["triangle_source"] = source;
    d["colors"] = mesh.colors.empty() ? py::object(py::none()) : py::object(rows(mesh.colors, 4, 0.0f));
    d["uvs"] = mesh.uvs.empty() ? py::object(py::none()) : py::object(rows(mesh.uvs, 2, 0.0f));
    d["tangents"] = mesh.tangents.empty() ? py::object(py::none()) : py::object(rows(mesh.tangents, 4, 0.0f));
    d["material"] = mesh.material;
    return d;
}


// --- cameras -----------------------------------------------------------------------------------

Camera withPlanes(Camera c, std::optional<float> znear, std::optional<float> zfar, const std::string& depthRange) {
    if (znear && !(std::isfinite(*znear) && *znear > 0.0f))
        throw InputError{"near: " + std::to_string(*znear) + " must be a finite number above 0"};
    if (zfar && !(std::isfinite(*zfar) && *zfar >= 0.0f))
        throw InputError{"far: " + std::to_string(*zfar) + " must be a finite number, 0 (infinite) or above"};
    c.znear = znear;
    c.zfar = zfar;
    if (depthRange != "fit" && depthRange != "file")
        throw InputError{"depth_range: '" + depthRange + "' is not a mode (fit, file)"};
    c.depthRange = depthRange == "file" ? DepthRange::File : DepthRange::Fit;
    return c;
}

float fovFrom(float degrees) {
    if (!(std::isfinite(degrees) && degrees > 0.0f && degrees < 180.0f))
        throw InputError{"fov: " + std::to_string(degrees) + " degrees: must be above 0 and below 180"};
    return degrees;
}

}  // namespace

void bindScene(py::module_& m) {
    py::class_<PyScene>(m, "Scene", "A scene: loaded with frugal.load, or built here from numpy arrays.")
        .def(py::init<>())
        .def("add_texture", &addTexture, py::arg("pixels"), py::kw_only(), py::arg("wrap") = "repeat",
             py::arg("filter") = "linear", py::arg("min_filter") = py::none(), py::arg("mipmaps") = "none",
             py::arg("srgb") = true, py::arg("name") = "",
             "An (H, W, 4) or (H, W, 3) uint8 image, first row first (texture coordinate v = 0, as glTF).\n"
             "srgb: its colours are sRGB-encoded, as a glTF base colour or emissive texture's (alpha is\n"
             "linear); False for data (a metallic-roughness or occlusion map).\n"
             "wrap: repeat, clamp or mirror; filter: linear or nearest where the texture is magnified,\n"
             "min_filter where it is minified (default: filter); mipmaps: none, nearest or linear (made\n"
             "when the texture is uploaded; 'linear' blends the two nearest levels). Returns its index.")
        .def("add_material", &addMaterial, py::arg("color") = py::make_tuple(1.0, 1.0, 1.0, 1.0), py::kw_only(),
             py::arg("texture") = py::none(), py::arg("double_sided") = false, py::arg("metallic") = 1.0,
             py::arg("roughness") = 1.0, py::arg("unlit") = false,
             py::arg("emissive") = py::make_tuple(0.0, 0.0, 0.0), py::arg("metallic_roughness_texture") = py::none(),
             py::arg("occlusion_texture") = py::none(), py::arg("occlusion_strength") = 1.0,
             py::arg("emissive_texture") = py::none(), py::arg("normal_texture") = py::none(),
             py::arg("normal_scale") = 1.0, py::arg("alpha") = "opaque", py::arg("alpha_cutoff") = 0.5,
             py::arg("specular") = py::none(), py::arg("glossiness") = 1.0,
             py::arg("specular_glossiness_texture") = py::none(), py::arg("clearcoat") = 0.0,
             py::arg("clearcoat_roughness") = 0.0, py::arg("clearcoat_texture") = py::none(),
             py::arg("clearcoat_roughness_texture") = py::none(), py::arg("clearcoat_normal_texture") = py::none(),
             py::arg("clearcoat_normal_scale") = 1.0, py::arg("name") = "",
             "A glTF metallic-roughness material: base colour (RGB or RGBA, linear factors), a texture index,\n"
             "whether back faces are drawn (single-sided by default, as glTF), metallic and roughness in [0, 1]\n"
             "(glTF's defaults: 1 and 1; 0 and about 0.5 is a plastic), and unlit (KHR_materials_unlit: the\n"
             "base colour as it is, no light), emissive: linear RGB added to the lit colour.\n"
             "The maps, as glTF reads them (texture indices, sampled at the mesh's uvs): metallic_roughness_texture\n"
             "(blue x metallic, green x roughness), occlusion_texture (red darkens the environment's light, by\n"
             "occlusion_strength in [0, 1]), emissive_texture (rgb x emissive), normal_texture (tangent-space\n"
             "normals, x and y x normal_scale; a mesh's tangents are generated when it is drawn).\n"
             "alpha (the base colour's, texture and vertex colours included): 'opaque' (ignored), 'mask' (fragments\n"
             "below alpha_cutoff are discarded) or 'blend' (drawn after the rest, far to near, over what is\n"
             "behind; depth and ids are written as for the others).\n"
             "specular (RGB in [0, 1]) makes it a KHR_materials_pbrSpecularGlossiness material: color is the\n"
             "diffuse colour, metallic and roughness are not read, the reflectance at normal incidence is specular\n"
             "(x the rgb of specular_glossiness_texture) and roughness 1 - glossiness (x its alpha).\n"
             "clearcoat in [0, 1] (0: none) coats it as KHR_materials_clearcoat does: a clear dielectric layer\n"
             "(x the red of clearcoat_texture) of clearcoat_roughness (x the green of\n"
             "clearcoat_roughness_texture), with its own normal map, clearcoat_normal_texture, at\n"
             "clearcoat_normal_scale.\n"
             "Returns its index.")
        .def("add_mesh", &addMesh, py::arg("positions"), py::arg("indices"), py::kw_only(),
             py::arg("normals") = py::none(), py::arg("colors") = py::none(), py::arg("uvs") = py::none(),
             py::arg("tangents") = py::none(),
             py::arg("material") = py::none(), py::arg("name") = "", py::arg("file_order") = false,
             py::arg("topology") = "triangles",
             "A mesh: positions (N, 3), indices (T, 3) or (3T,) of an integer dtype, counter-clockwise\n"
             "= front; normals (N, 3) (computed when None), colors (N, 3|4), uvs (N, 2), tangents (N, 4) as glTF's\n"
             "TANGENT (xyz toward increasing u, w = +1 or -1 the handedness; generated for a normal map when None).\n"
             "topology 'lines' or 'points': indices (T, 2) or (T,) name line segments or points, 1 pixel wide,\n"
             "lit where normals are given, else drawn in the base colour plus the emission.\n"
             "Checked (dtype, shape, finite values, indices below N) and finished as a loaded mesh is: its\n"
             "triangles are reordered for\n"
             "the vertex cache unless file_order, and triangle ids stay those of `indices`. Returns its index.")
        .def("add_instance", &addInstance, py::arg("mesh"), py::arg("transform") = py::none(), py::kw_only(),
             py::arg("name") = "",
             "Places mesh `mesh` with a 4x4 model matrix (row-major, translation in the last column).\n"
             "Returns the node, which set_transform and Renderer.set_transform take.")
        .def("add_light", &addLight, py::arg("kind") = "point", py::kw_only(),
             py::arg("color") = py::make_tuple(1.0, 1.0, 1.0), py::arg("intensity") = 1.0, py::arg("range") = 0.0,
             py::arg("inner_cone") = 0.0, py::arg("outer_cone") = 0.7853981633974483,
             py::arg("transform") = py::none(), py::arg("name") = "",
             "A punctual light as glTF's KHR_lights_punctual holds one: kind directional, point or spot;\n"
             "color linear RGB; intensity in lux (directional) or candela (point, spot); range where a point\n"
             "or spot light ends (0 = unbounded); a spot's inner and outer cone angles in radians. Placed by\n"
             "a new node with `transform` (4x4, row-major): at its origin, shining down its -Z. A scene with\n"
             "lights is lit by them (the first 8) and the environment instead of the default light.\n"
             "Returns the node, which set_transform and Renderer.set_transform take.")
        .def(
            "set_transform",
            [](PyScene& s, int node, const py::handle& transform) {
                take(s.scene.setTransform(node, matrixFrom(transform, "transform")));
                s.dirty = true;
            },
            py::arg("node"), py::arg("transform"), "Node `node`'s local transform becomes `transform` (4x4).")
        .def(
            "mesh", [](PyScene& s, int i) {
                if (i < 0 || i >= int(s.scene.meshes.size()))
                    throw InputError{"mesh " + std::to_string(i) + " does not exist (the scene has " +
                                     std::to_string(s.scene.meshes.size()) + ")"};
                return meshDict(s.scene.meshes[std::size_t(i)]);
            },
            py::arg("index"), "Mesh `index`'s arrays (copies) and material, as add_mesh takes them.")
        .def_property_readonly("source", [](PyScene& s) { return s.scene.source; })
        .def_property_readonly("mesh_count", [](PyScene& s) { return s.scene.meshes.size(); })
        .def_property_readonly("instance_count", [](PyScene& s) { return s.built().instances.size(); })
        .def_property_readonly("triangle_count", [](PyScene& s) { return s.built().triangleCount(); })
        .def_property_readonly("duration", [](PyScene& s) { return s.scene.duration(); })
        .def_property_readonly("fps", [](PyScene& s) { return s.scene.fps; })
        .def_property_readonly("node_names",
                               [](PyScene& s) {
                                   std::vector<std::string> names;
                                   for (const Node& n : s.scene.nodes) names.push_back(n.name);
                                   return names;
                               })
        .def_property_readonly("cameras",
                               [](PyScene& s) {
                                   py::list cameras;
                                   for (const SceneCamera& c : s.scene.cameras) cameras.append(cameraDict(c));
                                   return cameras;
                               })
        .def_property_readonly("instances", [](PyScene& s) { return instanceList(s.built()); },
                               "The drawn instances in draw order: node, mesh, first_id, triangles (ids: first_id +\n"
                               "the triangle's index in its mesh's source; 0 = background).")
        .def_property_readonly("materials", [](PyScene& s) { return materialList(s.scene); },
                               "Each material: name, color (RGBA factors), texture (index or None), double_sided.")
        .def("world_transform", &worldMatrix, py::arg("node"), py::arg("time") = 0.0,
             "Node `node`'s 4x4 world matrix at `time` (animations sampled, parents applied).")
        .def_property_readonly("warnings", [](PyScene& s) { return s.scene.warnings; })
        .def_property_readonly("unsupported", [](PyScene& s) { return s.scene.unsupported; })
        .def_property_readonly(
            "decompressed",
            [](PyScene& s) {
                py::list out;
                for (const Decompression& d : s.scene.decompressed)
                    out.append(py::dict(py::arg("method") = d.method, py::arg("items") = d.items,
                                        py::arg("compressed_bytes") = d.compressedBytes,
                                        py::arg("decoded_bytes") = d.decodedBytes, py::arg("seconds") = d.seconds));
                return out;
            },
            "What the loader decoded (KHR_draco_mesh_compression: primitives; EXT_meshopt_compression:\n"
            "bufferViews), one dict a method: method, items, compressed_bytes, decoded_bytes, seconds.")
        .def(
            "bounds",
            [](PyScene& s, double time) {
                const Bounds b = s.built().bounds(time);
                return py::make_tuple(py::make_tuple(b.min.x, b.min.y, b.min.z), py::make_tuple(b.max.x, b.max.y, b.max.z));
            },
            py::arg("time") = 0.0, "((xmin, ymin, zmin), (xmax, ymax, zmax)) of every instance at `time`.")
        .def("__repr__", [](PyScene& s) {
            return "<frugal.Scene '" + s.scene.source + "': " + std::to_string(s.scene.meshes.size()) + " meshes, " +
                   std::to_string(s.built().instances.size()) + " instances, " +
                   std::to_string(s.built().triangleCount()) + " triangles>";
        });

}

void bindLoad(py::module_& m) {
    m.def(
        "load",
        [](const std::filesystem::path& spec, bool cullBackfaces, bool fileOrder) {
            LoadOptions options;
            options.optimizeOrder = !fileOrder;
            options.objDoubleSided = !cullBackfaces;
            std::optional<Result<Scene>> loaded;
            {
                py::gil_scoped_release unlocked;
                loaded.emplace(loadScene(spec.string(), options));
            }
            return PyScene{take(std::move(*loaded)), false};
        },
        py::arg("spec"), py::kw_only(), py::arg("cull_backfaces") = false, py::arg("file_order") = false,
        "A scene from a .gltf/.glb or .obj file, or a built-in ('builtin:dominoes?polygons=1404').\n"
        "cull_backfaces: draw OBJ single-sided; file_order: keep the file's triangle order.");
}

void bindCamera(py::module_& m) {
    py::class_<Camera>(m, "Camera", "What a frame is seen through (frugal.Camera.look_at, from_pose, from_scene, automatic).")
        .def_static(
            "look_at",
            [](const py::handle& eye, const py::handle& target, float fov, const py::handle& up,
               std::optional<float> znear, std::optional<float> zfar, const std::string& depthRange) {
                const glm::vec3 e = vectorFrom<3>(eye, "eye"), t = vectorFrom<3>(target, "target");
                if (e == t) throw InputError{"eye and target coincide: the camera has no direction"};
                return withPlanes(Camera::lookAt(e, t, fovFrom(fov), vectorFrom<3>(up, "up")), znear, zfar, depthRange);
            },
            py::arg("eye"), py::arg("target"), py::arg("fov") = 40.0f, py::kw_only(),
            py::arg("up") = py::make_tuple(0.0, 1.0, 0.0), py::arg("near") = py::none(), py::arg("far") = py::none(),
            py::arg("depth_range") = "fit",
            "From `eye` towards `target`, a vertical field of view in degrees, `up` the image's up.\n"
            "near/far: the clip planes (default: around the scene; far 0 = infinite); depth_range: fit (the\n"
            "planes moved in to where the scene is) or file (as given).")
        .def_static(
            "from_pose",
            [](const py::handle& pose, float fov, std::optional<float> znear, std::optional<float> zfar,
               const std::string& depthRange) {
                return withPlanes(Camera::fromPose(matrixFrom(pose, "pose"), fovFrom(fov)), znear, zfar, depthRange);
            },
            py::arg("pose"), py::arg("fov") = 40.0f, py::kw_only(), py::arg("near") = py::none(),
            py::arg("far") = py::none(), py::arg("depth_range") = "fit",
            "A 4x4 camera-to-world matrix in OpenGL's convention (looks down its -z, +y up; pyrender's):\n"
            "the eye is pose[:3, 3].")
        .def_static("from_scene", &Camera::fromScene, py::arg("index") = 0,
                    "The scene's camera `index` (its node's transform at the frame's time).")
        .def_static("automatic", &Camera::automatic,
                    "A view that fits the scene's bounds at the frame's time, from the front and a little above.")
        .def("__repr__", [](const Camera& c) {
            if (c.sceneCamera) return "<frugal.Camera scene camera " + std::to_string(*c.sceneCamera) + ">";
            if (c.eye) return std::string("<frugal.Camera look-at>");
            return std::string("<frugal.Camera automatic>");
        });
}

}  // namespace frugal::python
