// frugal._frugal: the library's entry point (frugal/Renderer.h) for Python. Scenes (loaded or built
// from numpy arrays), cameras, a renderer whose keyword arguments are the command line's options,
// and frames whose images are numpy arrays. The GIL is released while anything renders, loads or
// writes; errors are exceptions under frugal.Error, one class per frugal::ErrorKind.
#include <chrono>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <frugal/Files.h>
#include <frugal/Renderer.h>
#include <frugal/Scene.h>
#include <frugal/Stats.h>
#include <frugal/Version.h>

#include "Arrays.h"
#include "Settings.h"

namespace frugal::python {

namespace {

// A frugal::Error on its way to Python (the translator below picks the class by its kind).
struct Failure {
    Error error;
};

template <class T>
T take(Result<T>&& result) {
    if (!result) throw Failure{result.failure()};
    return std::move(*result);
}

// The exception classes, made once at import (frugal.Error and one subclass a kind).
struct ErrorClasses {
    py::object base, input, backend, memory, interrupted, io;
};
ErrorClasses& errorClasses() {
    static ErrorClasses* classes = new ErrorClasses();  // never destroyed: lives as long as the interpreter
    return *classes;
}

py::object makeError(py::module_& m, const char* name, py::object bases, const char* doc) {
    const std::string qualified = std::string("frugal.") + name;
    PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
    if (type == nullptr) throw py::error_already_set();
    py::object object = py::reinterpret_steal<py::object>(type);
    m.attr(name) = object;
    return object;
}

void defineErrors(py::module_& m) {
    ErrorClasses& c = errorClasses();
    const py::module_ builtins = py::module_::import("builtins");
    c.base = makeError(m, "Error", builtins.attr("Exception"), "Any error frugal reports: one line, '<what>: <why>'.");
    const auto with = [&](const char* builtin) { return py::make_tuple(c.base, builtins.attr(builtin)); };
    c.input = makeError(m, "InputError", with("ValueError"),
                        "A scene, an array, a setting or a value that cannot be used as given.");
    c.backend = makeError(m, "BackendUnavailable", with("RuntimeError"),
                          "No backend of the kind asked for runs here (no GL context, no glClipControl, ...).");
    c.memory = makeError(m, "OutOfMemory", with("MemoryError"),
                         "More memory than the process may still take (checked before a target is made).");
    c.interrupted = makeError(m, "Interrupted", py::make_tuple(c.base), "A signal stopped the work between frames.");
    c.io = makeError(m, "IoError", with("OSError"), "A file that cannot be read or written.");

    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const InputError& e) {
            PyErr_SetString(errorClasses().input.ptr(), e.message.c_str());
        } catch (const Failure& f) {
            const ErrorClasses& classes = errorClasses();
            const py::object* type = &classes.base;
            switch (f.error.kind) {
                case ErrorKind::BadInput: type = &classes.input; break;
                case ErrorKind::BackendUnavailable: type = &classes.backend; break;
                case ErrorKind::OutOfMemory: type = &classes.memory; break;
                case ErrorKind::Interrupted: type = &classes.interrupted; break;
                case ErrorKind::Io: type = &classes.io; break;
            }
            PyErr_SetString(type->ptr(), f.error.message.c_str());
        }
    });
}

// --- scenes ------------------------------------------------------------------------------------

// A scene being built or loaded. Instances and ids are numbered when it is first used after a
// change (Scene::buildInstances).
struct PyScene {
    Scene scene;
    bool dirty = false;

    Scene& built() {
        if (dirty) scene.buildInstances();
        dirty = false;
        return scene;
    }
};

Wrap wrapFrom(const std::string& name) {
    if (name == "repeat") return Wrap::Repeat;
    if (name == "clamp") return Wrap::ClampToEdge;
    if (name == "mirror") return Wrap::MirroredRepeat;
    throw InputError{"wrap: '" + name + "' is not a mode (repeat, clamp, mirror)"};
}

int addTexture(PyScene& s, const py::handle& pixels, const std::string& wrap, const std::string& filter,
               const std::string& name) {
    Pixels p = pixelsFrom(pixels);
    Texture texture;
    texture.name = name;
    texture.width = p.width;
    texture.height = p.height;
    texture.rgba = std::move(p.rgba);
    texture.wrapS = texture.wrapT = wrapFrom(wrap);
    if (filter != "linear" && filter != "nearest")
        throw InputError{"filter: '" + filter + "' is not a filter (linear, nearest)"};
    texture.filter = filter == "nearest" ? Filter::Nearest : Filter::Linear;
    return take(s.scene.addTexture(std::move(texture)));
}

int addMaterial(PyScene& s, const py::handle& color, std::optional<int> texture, bool doubleSided,
                const std::string& name) {
    Material material;
    material.name = name;
    const bool rgb = py::isinstance<py::sequence>(color) && py::len(color) == 3;
    material.baseColorFactor = rgb ? glm::vec4(vectorFrom<3>(color, "color"), 1.0f) : vectorFrom<4>(color, "color");
    material.baseColorTexture = texture.value_or(-1);
    material.doubleSided = doubleSided;
    return take(s.scene.addMaterial(std::move(material)));
}

int addMesh(PyScene& s, const py::handle& positions, const py::handle& indices, const py::handle& normals,
            const py::handle& colors, const py::handle& uvs, std::optional<int> material, const std::string& name,
            bool fileOrder) {
    Mesh mesh;
    mesh.name = name;
    mesh.positions = vectorsFrom<3>(positions, "positions");
    mesh.indices = indicesFrom(indices);
    if (!normals.is_none()) mesh.normals = vectorsFrom<3>(normals, "normals");
    if (!colors.is_none()) mesh.colors = colorsFrom(colors);
    if (!uvs.is_none()) mesh.uvs = vectorsFrom<2>(uvs, "uvs");
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
    py::array_t<std::uint32_t> indices({py::ssize_t(mesh.triangleCount()), py::ssize_t(3)});
    if (!mesh.indices.empty()) std::memcpy(indices.mutable_data(), mesh.indices.data(), mesh.indices.size() * 4);
    d["indices"] = indices;
    py::array_t<std::uint32_t> source(py::ssize_t(mesh.triangleSource.size()));
    if (!mesh.triangleSource.empty())
        std::memcpy(source.mutable_data(), mesh.triangleSource.data(), mesh.triangleSource.size() * 4);
    d["triangle_source"] = source;
    d["colors"] = mesh.colors.empty() ? py::object(py::none()) : py::object(rows(mesh.colors, 4, 0.0f));
    d["uvs"] = mesh.uvs.empty() ? py::object(py::none()) : py::object(rows(mesh.uvs, 2, 0.0f));
    d["material"] = mesh.material;
    return d;
}

void bindScene(py::module_& m) {
    py::class_<PyScene>(m, "Scene", "A scene: loaded with frugal.load, or built here from numpy arrays.")
        .def(py::init<>())
        .def("add_texture", &addTexture, py::arg("pixels"), py::kw_only(), py::arg("wrap") = "repeat",
             py::arg("filter") = "linear", py::arg("name") = "",
             "An (H, W, 4) or (H, W, 3) uint8 image, first row first (texture coordinate v = 0, as glTF).\n"
             "wrap: repeat, clamp or mirror; filter: linear or nearest. Returns its index.")
        .def("add_material", &addMaterial, py::arg("color") = py::make_tuple(1.0, 1.0, 1.0, 1.0), py::kw_only(),
             py::arg("texture") = py::none(), py::arg("double_sided") = false, py::arg("name") = "",
             "A material: base colour (RGB or RGBA, linear factors), a texture index, and whether back faces\n"
             "are drawn (single-sided by default, as glTF). Returns its index.")
        .def("add_mesh", &addMesh, py::arg("positions"), py::arg("indices"), py::kw_only(),
             py::arg("normals") = py::none(), py::arg("colors") = py::none(), py::arg("uvs") = py::none(),
             py::arg("material") = py::none(), py::arg("name") = "", py::arg("file_order") = false,
             "A triangle mesh: positions (N, 3), indices (T, 3) or (3T,) of an integer dtype, counter-clockwise\n"
             "= front; normals (N, 3) (computed when None), colors (N, 3|4), uvs (N, 2). Checked (dtype, shape,\n"
             "finite values, indices below N) and finished as a loaded mesh is: its triangles are reordered for\n"
             "the vertex cache unless file_order, and triangle ids stay those of `indices`. Returns its index.")
        .def("add_instance", &addInstance, py::arg("mesh"), py::arg("transform") = py::none(), py::kw_only(),
             py::arg("name") = "",
             "Places mesh `mesh` with a 4x4 model matrix (row-major, translation in the last column).\n"
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
        .def_property_readonly("warnings", [](PyScene& s) { return s.scene.warnings; })
        .def_property_readonly("unsupported", [](PyScene& s) { return s.scene.unsupported; })
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

// --- frames ------------------------------------------------------------------------------------

// Frames whose Python objects are gone, kept for the next render() to fill (Renderer::render into a
// Frame: no allocation, no page faults a frame). A frame goes back only when nothing views it: its
// arrays keep the Python frame, and so the memory they show, alive.
struct FramePool {
    static constexpr std::size_t kKept = 2;
    std::mutex lock;
    std::vector<Frame> frames;

    Frame take() {
        std::lock_guard<std::mutex> held(lock);
        if (frames.empty()) return {};
        Frame frame = std::move(frames.back());
        frames.pop_back();
        return frame;
    }
    void give(Frame&& frame) {
        std::lock_guard<std::mutex> held(lock);
        if (frames.size() < kKept) frames.push_back(std::move(frame));
    }
};

struct PyFrame {
    Frame frame;
    Settings settings;
    py::object depth, stats;           // made on first use
    std::shared_ptr<FramePool> pool;  // where the frame's memory goes when this object does

    PyFrame() = default;
    PyFrame(PyFrame&&) noexcept = default;
    PyFrame& operator=(PyFrame&&) noexcept = default;
    ~PyFrame() {
        if (pool) pool->give(std::move(frame));
    }
};

py::array depthArray(py::object self) {
    PyFrame& f = self.cast<PyFrame&>();
    const DepthImage& d = f.frame.depth;
    if (d.format == DepthFormat::D32F)  // the values are the floats' bits: a view
        return topFirstView(reinterpret_cast<const float*>(d.values.data()), d.width, d.height, 1, self);
    // D24: window z = value / (2^24 - 1), converted once (a copy, top row first).
    py::array_t<float> out({py::ssize_t(d.height), py::ssize_t(d.width)});
    float* data = out.mutable_data();
    {
        py::gil_scoped_release unlocked;
        for (int y = 0; y < d.height; ++y) {
            const std::uint32_t* row = d.values.data() + std::size_t(d.height - 1 - y) * std::size_t(d.width);
            float* to = data + std::size_t(y) * std::size_t(d.width);
            // windowDepth(D24, v), with v (below 2^24) converted as a signed integer: it vectorises.
            for (int x = 0; x < d.width; ++x) to[x] = float(std::int32_t(row[x])) / float(kDepthMax);
        }
    }
    return out;
}

py::object jsonLoads(const std::string& text) { return py::module_::import("json").attr("loads")(text); }

py::array matrixArray(const glm::mat4& m) {
    py::array_t<float> out({4, 4});
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) out.mutable_at(r, c) = m[c][r];
    return out;
}

void writeFiles(PyFrame& f, const std::optional<std::filesystem::path>& colorPath,
                const std::optional<std::filesystem::path>& depthPath, const std::optional<std::filesystem::path>& idsPath) {
    const auto text = [](const std::optional<std::filesystem::path>& p) {
        return p ? std::optional<std::string>(p->string()) : std::nullopt;
    };
    const std::optional<std::string> color = text(colorPath), depth = text(depthPath), ids = text(idsPath);
    if (ids && f.frame.ids.ids.empty())
        throw InputError{"ids: the frame has no ids (make the renderer with ids=True)"};
    py::gil_scoped_release unlocked;
    if (color) take(writePng(*color, f.frame.color));
    if (depth) {
        const bool pfm = depth->size() >= 4 && depth->compare(depth->size() - 4, 4, ".pfm") == 0;
        take(pfm ? writePfm(*depth, f.frame.depth) : writePng(*depth, f.frame.depth));
    }
    if (ids) take(writePng(*ids, f.frame.ids));
}

void bindFrame(py::module_& m) {
    py::class_<PyFrame>(m, "Frame", "One rendered frame: images as numpy arrays (top row first) and its stats.")
        .def_property_readonly(
            "color",
            [](py::object self) {
                const ColorImage& c = self.cast<PyFrame&>().frame.color;
                return topFirstView(c.rgba.data(), c.width, c.height, 4, self);
            },
            "(H, W, 4) uint8 RGBA, top row first: a view of the frame's memory (no copy).")
        .def_property_readonly(
            "depth",
            [](py::object self) {
                PyFrame& f = self.cast<PyFrame&>();
                if (!f.depth) f.depth = depthArray(self);
                return f.depth;
            },
            "(H, W) float32 window z, top row first. d24: value / (2^24 - 1), 0 near, 1 far (converted on\n"
            "first use: a copy); d32f: the stored floats, reversed (1 near, 0 far), a view.")
        .def_property_readonly(
            "depth_values",
            [](py::object self) {
                const DepthImage& d = self.cast<PyFrame&>().frame.depth;
                return topFirstView(d.values.data(), d.width, d.height, 1, self);
            },
            "(H, W) uint32 as stored: d24 the 24-bit values, d32f the floats' bits (a view).")
        .def_property_readonly(
            "ids",
            [](py::object self) -> py::object {
                const IdImage& ids = self.cast<PyFrame&>().frame.ids;
                if (ids.ids.empty()) return py::none();
                return topFirstView(ids.ids.data(), ids.width, ids.height, 1, self);
            },
            "(H, W) uint32 triangle ids, 0 = background (a view); None unless the renderer has ids=True.")
        .def_property_readonly(
            "stats",
            [](PyFrame& f) {
                if (!f.stats) f.stats = jsonLoads(frameStatsJsonText(f.frame.stats, f.settings));
                return f.stats;
            },
            "The render JSON's record of this frame: time, render_ms, readback_ms, culling, reuse, ...")
        .def_property_readonly(
            "camera",
            [](PyFrame& f) {
                py::dict d = jsonLoads(viewJsonText(f.frame.view, f.settings));
                d["view_matrix"] = matrixArray(f.frame.view.view);
                d["projection_matrix"] = matrixArray(f.frame.view.projection);
                return d;
            },
            "The camera as resolved for this frame (the render JSON's 'camera') and its 4x4 matrices.")
        .def("write", &writeFiles, py::kw_only(), py::arg("color") = py::none(), py::arg("depth") = py::none(),
             py::arg("ids") = py::none(),
             "Writes the images as frugal render does (each file whole or not at all): colour PNG, depth\n"
             "(.png 16-bit or .pfm float32), ids PNG.");
}

// --- the renderer ------------------------------------------------------------------------------

// One frugal::Renderer, used by one thread at a time (the lock), with its context released after
// every call so that the next may come from another thread. close() frees it before the garbage
// collector would.
struct PyRenderer {
    std::optional<Renderer> renderer;
    std::mutex lock;
    std::shared_ptr<FramePool> pool = std::make_shared<FramePool>();

    PyRenderer(PyScene& scene, const py::kwargs& kwargs) {
        const Settings settings = settingsFrom(kwargs);
        Scene copy = scene.built();
        py::gil_scoped_release unlocked;
        Result<Renderer> made = Renderer::create(std::move(copy), settings);
        if (made) made->releaseThread();
        renderer.emplace(take(std::move(made)));
    }
    ~PyRenderer() { close(); }

    void close() {
        py::gil_scoped_release unlocked;  // a GL context's teardown may wait for its threads
        std::lock_guard<std::mutex> held(lock);
        renderer.reset();
    }

    // The renderer, or InputError once closed. Callers hold the lock where it renders.
    Renderer& live() {
        if (!renderer) throw InputError{"the renderer is closed"};
        return *renderer;
    }

    PyFrame render(const std::optional<Camera>& camera, double time) {
        if (!std::isfinite(time)) throw InputError{"time: " + std::to_string(time) + " is not finite"};
        PyFrame out;
        {
            py::gil_scoped_release unlocked;
            std::lock_guard<std::mutex> held(lock);
            Renderer& r = live();
            out.frame = pool->take();
            Result<bool> rendered = r.render(camera.value_or(Camera{}), time, out.frame);
            r.releaseThread();
            take(std::move(rendered));
            out.settings = r.settings();
        }
        out.pool = pool;
        return out;
    }

    void setTransform(int node, const py::handle& transform) {
        const glm::mat4 m = matrixFrom(transform, "transform");
        std::lock_guard<std::mutex> held(lock);
        take(live().setTransform(node, m));
    }
};

// The C++ loop a benchmark compares Python's with: `frames` renders through the same renderer into
// one Frame (as a C++ program does best), without Python between them; the wall time of each, in
// milliseconds, with the context released after each as render() does.
std::vector<double> cppLoop(PyRenderer& r, const std::optional<Camera>& camera, double time, int frames) {
    std::vector<double> ms;
    py::gil_scoped_release unlocked;
    std::lock_guard<std::mutex> held(r.lock);
    Renderer& renderer = r.live();
    std::optional<Error> failed;
    Frame frame;
    for (int i = 0; i < frames && !failed; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        Result<bool> rendered = renderer.render(camera.value_or(Camera{}), time, frame);
        renderer.releaseThread();
        if (!rendered) failed = rendered.failure();
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    if (failed) throw Failure{*failed};
    return ms;
}

py::object cullPreparationDict(const Renderer& r) {
    const std::optional<Renderer::CullPreparation> p = r.cullPreparation();
    if (!p) return py::none();
    py::dict d;
    d["sphere_ms"] = p->sphereMs;
    d["map_ms"] = p->mapMs;
    d["cluster_ms"] = p->clusterMs;
    d["hull_ms"] = p->hullMs;
    d["total_ms"] = p->totalMs;
    d["hull"] = p->hull;
    return d;
}

py::object stateCostsDict(const Renderer& r) {
    const std::optional<StateCosts> costs = r.stateCosts();
    if (!costs) return py::none();
    py::dict d;
    d["kinds"] = costs->kinds;
    d["start_us"] = costs->startUs;
    d["us"] = costs->us;
    d["rounds"] = costs->rounds;
    d["refine_every"] = costs->refineEvery;
    return d;
}

void bindRenderer(py::module_& m) {
    py::class_<PyRenderer>(m, "Renderer",
                           "Renderer(scene, **settings): frugal's renderer on a copy of `scene`. The settings are the\n"
                           "command line's options (size=(800, 600), backend='auto', cull='conservative', reuse=True,\n"
                           "order='key', hsr=..., depth_format='d32f', ids=True, ...; frugal.default_settings()).\n"
                           "Usable as a context manager: leaving the block closes it.")
        .def(py::init<PyScene&, const py::kwargs&>(), py::arg("scene"))
        .def("render", &PyRenderer::render, py::arg("camera") = py::none(), py::arg("time") = 0.0,
             "The frame at scene time `time` (seconds) through `camera` (default: the scene's first camera,\n"
             "else a view that fits the scene). The GIL is released while it renders.")
        .def("set_transform", &PyRenderer::setTransform, py::arg("node"), py::arg("transform"),
             "Moves node `node` (an add_instance result) for the frames that follow; reuse redraws only it.")
        .def("close", &PyRenderer::close, "Frees the backend, its context and uploads now; later calls raise InputError.")
        .def("__enter__", [](py::object self) { return self; })
        .def("__exit__", [](PyRenderer& r, const py::args&) { r.close(); })
        .def_property_readonly("backend", [](PyRenderer& r) { return r.live().backendName(); },
                               "The backend chosen: egl-surfaceless, egl-device, osmesa or software.")
        .def_property_readonly("backend_renderer", [](PyRenderer& r) { return r.live().backendRenderer(); },
                               "GL_RENDERER and GL_VERSION, or the software backend's description.")
        .def_property_readonly("backend_log", [](PyRenderer& r) { return r.live().backendLog(); },
                               "One line per GL context tried.")
        .def_property_readonly("settings", [](PyRenderer& r) { return settingsDict(r.live().settings()); })
        .def_property_readonly("triangle_count", [](PyRenderer& r) { return r.live().scene().triangleCount(); })
        .def_property_readonly("cull_preparation", [](PyRenderer& r) { return cullPreparationDict(r.live()); },
                               "With culling: what preparing it took (ms: sphere, map, cluster, hull, total); else None.")
        .def_property_readonly("state_costs", [](PyRenderer& r) { return stateCostsDict(r.live()); },
                               "With order paper, greedy or best: the state costs measured (us a change, by kind).")
        .def_property_readonly("static_pair_bytes", [](PyRenderer& r) { return r.live().staticPairBytes(); },
                               "With reuse: the bytes of the static pair (one more target); else 0.")
        .def("__repr__", [](PyRenderer& r) {
            if (!r.renderer) return std::string("<frugal.Renderer (closed)>");
            const Settings& s = r.renderer->settings();
            return "<frugal.Renderer " + std::to_string(s.width) + "x" + std::to_string(s.height) + " on " +
                   r.renderer->backendName() + ">";
        });
    m.def("_cpp_loop", &cppLoop, py::arg("renderer"), py::arg("camera"), py::arg("time"), py::arg("frames"));
}

}  // namespace

}  // namespace frugal::python

PYBIND11_MODULE(_frugal, m) {
    using namespace frugal;
    using namespace frugal::python;
    m.doc() = "frugal: an offscreen OpenGL renderer that does only the work a scene requires.";
    m.attr("__version__") = version();
    defineErrors(m);
    bindScene(m);
    bindCamera(m);
    bindFrame(m);
    bindRenderer(m);
    m.def("settings_names", [] { return py::list(settingsDict(Settings{}).attr("keys")()); },
          "The keyword arguments frugal.Renderer takes.");
    m.def("default_settings", [] { return settingsDict(Settings{}); }, "Every setting with its default.");
}
