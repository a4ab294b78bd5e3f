// The rendering half of the module: frugal.Renderer (a frugal::Renderer with its keyword arguments,
// a lock and a pool of frames to fill again) and frugal.Frame (the images as numpy arrays).
#include <cmath>
#include <filesystem>
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

#include "Arrays.h"
#include "Bindings.h"
#include "RenderBindings.h"
#include "Settings.h"

namespace frugal::python {

namespace {

// --- frames ------------------------------------------------------------------------------------

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

// png_level="auto" or 0..12 (frugal/Files.h).
int pngLevelFrom(const py::object& level) {
    if (py::isinstance<py::str>(level) && level.cast<std::string>() == "auto") return kAutoPngLevel;
    if (py::isinstance<py::int_>(level) && !py::isinstance<py::bool_>(level)) {
        const long long value = level.cast<long long>();
        if (value >= 0 && value <= kMaxPngLevel) return int(value);
    }
    throw InputError{"png_level: " + py::repr(level).cast<std::string>() + " must be 0 to " +
                     std::to_string(kMaxPngLevel) + " or 'auto'"};
}

using OptionalPath = std::optional<std::filesystem::path>;

// The files of Frame.write and Writer.write; an ids (linear) file asked of a frame without ids
// (linear colour) is refused, and a linear file not named .pfm or .png.
FramePaths framePaths(const PyFrame& f, const OptionalPath& colorPath, const OptionalPath& depthPath,
                      const OptionalPath& idsPath, const OptionalPath& linearPath) {
    if (idsPath && f.frame.ids.ids.empty())
        throw InputError{"ids: the frame has no ids (make the renderer with ids=True)"};
    if (linearPath && f.frame.linear.rgba.empty())
        throw InputError{"linear: the frame has no linear colour (make the renderer with linear=True)"};
    const auto text = [](const OptionalPath& p) { return p ? p->string() : std::string(); };
    if (linearPath && !linearPathProblem(text(linearPath)).empty())
        throw InputError{"linear " + text(linearPath) + ": " + linearPathProblem(text(linearPath))};
    return {text(colorPath), text(depthPath), text(idsPath), text(linearPath)};
}

void writeFiles(PyFrame& f, const OptionalPath& colorPath, const OptionalPath& depthPath, const OptionalPath& idsPath,
                const OptionalPath& linearPath, const py::object& pngLevel) {
    const FramePaths paths = framePaths(f, colorPath, depthPath, idsPath, linearPath);
    const int level = pngLevelFrom(pngLevel);
    py::gil_scoped_release unlocked;
    take(writeFrame(paths, f.frame, level));
}

// --- the writer --------------------------------------------------------------------------------

// A frugal::FrameWriter: each frame's files encoded and written on threads of their own while
// Python goes on. write() copies the frame's images (its arrays may be changed or kept meanwhile).
struct PyWriter {
    std::optional<FrameWriter> writer;
    Frame spare;  // the memory of a frame written, filled again by the next copy

    PyWriter(int threads, int queue, const py::object& level) {
        writer.emplace(take(FrameWriter::create({.threads = threads, .queue = queue, .pngLevel = pngLevelFrom(level)})));
    }
    ~PyWriter() {
        py::gil_scoped_release unlocked;
        writer.reset();  // waits for the frames given
    }

    FrameWriter& live() {
        if (!writer) throw InputError{"the writer is closed"};
        return *writer;
    }

    void write(PyFrame& f, const OptionalPath& colorPath, const OptionalPath& depthPath, const OptionalPath& idsPath,
               const OptionalPath& linearPath) {
        FrameWriter& w = live();
        const FramePaths paths = framePaths(f, colorPath, depthPath, idsPath, linearPath);
        py::gil_scoped_release unlocked;
        Frame copy = std::move(spare);
        copy.color.width = f.frame.color.width;
        copy.color.height = f.frame.color.height;
        copy.color.rgba.assign(f.frame.color.rgba.begin(), f.frame.color.rgba.end());
        copy.depth = DepthImage{f.frame.depth.width, f.frame.depth.height, std::move(copy.depth.values),
                                f.frame.depth.format, f.frame.depth.znear, f.frame.depth.zfar,
                                f.frame.depth.perspective};
        copy.depth.values.assign(f.frame.depth.values.begin(), f.frame.depth.values.end());
        copy.ids.width = f.frame.ids.width;
        copy.ids.height = f.frame.ids.height;
        copy.ids.ids.assign(f.frame.ids.ids.begin(), f.frame.ids.ids.end());
        copy.linear.width = f.frame.linear.width;
        copy.linear.height = f.frame.linear.height;
        copy.linear.rgba.assign(f.frame.linear.rgba.begin(), f.frame.linear.rgba.end());
        Result<bool> queued = w.write(paths, copy);
        spare = std::move(copy);  // what came back: a written frame's memory, or nothing
        take(std::move(queued));
    }

    void finish() {
        FrameWriter& w = live();
        py::gil_scoped_release unlocked;
        take(w.finish());
    }

    // Waits for the frames given; raises their error unless one is already on its way.
    void close(bool raise) {
        if (!writer) return;
        Result<bool> finished = true;
        {
            py::gil_scoped_release unlocked;
            finished = writer->finish();
            writer.reset();
        }
        if (raise) take(std::move(finished));
    }
};

}  // namespace

// --- the renderer ------------------------------------------------------------------------------

PyRenderer::PyRenderer(PyScene& scene, const py::kwargs& kwargs) {
    const Settings settings = settingsFrom(kwargs);
    Scene copy = scene.built();
    py::gil_scoped_release unlocked;
    Result<Renderer> made = Renderer::create(std::move(copy), settings);
    if (made) made->releaseThread();
    renderer.emplace(take(std::move(made)));
}

void PyRenderer::close() {
    py::gil_scoped_release unlocked;  // a GL context's teardown may wait for its threads
    std::lock_guard<std::mutex> held(lock);
    renderer.reset();
}

Renderer& PyRenderer::live() {
    if (!renderer) throw InputError{"the renderer is closed"};
    return *renderer;
}

PyFrame PyRenderer::render(const std::optional<Camera>& camera, double time, const std::optional<Camera>& nextCamera,
                           const std::optional<double>& nextTime) {
    if (!std::isfinite(time)) throw InputError{"time: " + std::to_string(time) + " is not finite"};
    if (nextTime && !std::isfinite(*nextTime))
        throw InputError{"next_time: " + std::to_string(*nextTime) + " is not finite"};
    PyFrame out;
    {
        py::gil_scoped_release unlocked;
        std::lock_guard<std::mutex> held(lock);
        Renderer& r = live();
        if (nextCamera || nextTime)
            r.setNextFrame(nextCamera.value_or(camera.value_or(Camera{})), nextTime.value_or(time));
        out.frame = pool->take();
        Result<bool> rendered = r.render(camera.value_or(Camera{}), time, out.frame);
        r.releaseThread();
        take(std::move(rendered));
        out.settings = r.settings();
    }
    out.pool = pool;
    return out;
}

void PyRenderer::setTransform(int node, const py::handle& transform) {
    const glm::mat4 m = matrixFrom(transform, "transform");
    std::lock_guard<std::mutex> held(lock);
    take(live().setTransform(node, m));
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
            "linear",
            [](py::object self) -> py::object {
                const LinearImage& l = self.cast<PyFrame&>().frame.linear;
                if (l.rgba.empty()) return py::none();
                return topFirstView(l.rgba.data(), l.width, l.height, 4, self);
            },
            "(H, W, 4) float32 RGBA in linear light, top row first (a view): the colour after tone mapping\n"
            "and before the display encoding, unclamped; None unless the renderer has linear=True (then\n"
            "`color` is its display encoding).")
        .def_property_readonly(
            "stats",
            [](PyFrame& f) {
                if (!f.stats) f.stats = frameStatsObject(f.frame.stats, f.settings);
                return f.stats;
            },
            "frugal.FrameStats: what this frame cost and did (render_ms, readback_ms, cull, reuse, hsr,\n"
            "state_changes, ...); to_dict() is the render JSON's record of it.")
        .def_property_readonly(
            "camera", [](PyFrame& f) { return viewObject(f.frame.view, f.settings); },
            "frugal.View: the camera as resolved for this frame (the render JSON's 'camera') and its 4x4\n"
            "matrices.")
        .def("write", &writeFiles, py::kw_only(), py::arg("color") = py::none(), py::arg("depth") = py::none(),
             py::arg("ids") = py::none(), py::arg("linear") = py::none(), py::arg("png_level") = "auto",
             "Writes the images as frugal render does, as one set (all of them or, on an error, none):\n"
             "colour PNG, depth (.png 16-bit or .pfm float32), ids PNG, linear colour (.pfm float32 rgb or\n"
             ".png 16-bit, clamped); png_level as frugal.Writer's.");
}

void bindRenderer(py::module_& m) {
    py::class_<PyRenderer>(m, "Renderer",
                           "Renderer(scene, **settings): frugal's renderer on a copy of `scene`. The settings are the\n"
                           "command line's options (size=(800, 600), backend='auto', cull='conservative', reuse=True,\n"
                           "order='key', hsr=..., depth_format='d32f', ids=True, ...; frugal.default_settings()),\n"
                           "and settings='settings.json' to start from a settings file (the others win over it).\n"
                           "Usable as a context manager: leaving the block closes it.")
        .def(py::init<PyScene&, const py::kwargs&>(), py::arg("scene"))
        .def("render", &PyRenderer::render, py::arg("camera") = py::none(), py::arg("time") = 0.0, py::kw_only(),
             py::arg("next_camera") = py::none(), py::arg("next_time") = py::none(),
             "The frame at scene time `time` (seconds) through `camera` (default: the scene's first camera,\n"
             "else a view that fits the scene). The GIL is released while it renders.\n"
             "next_camera, next_time: the frame the next call will ask for (either; the other as this one's).\n"
             "With cull='occlusion-ahead' its plan is then made while this frame draws; a next call that asks\n"
             "for another frame is culled as usual (the images never depend on it).")
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
        .def_property_readonly("cull_preparation", [](PyRenderer& r) { return r.live().cullPreparation(); },
                               "frugal.CullPreparation with culling: what preparing it took (ms: sphere, map, cluster, "
                               "hull, total) and the bytes it keeps; else None.")
        .def_property_readonly("state_costs", [](PyRenderer& r) { return r.live().stateCosts(); },
                               "frugal.StateCosts with order paper, greedy or best: the state costs measured (us a "
                               "change, by kind); else None.")
        .def_property_readonly("static_pair_bytes", [](PyRenderer& r) { return r.live().staticPairBytes(); },
                               "With reuse: the bytes of the static pair (one more target); else 0.")
        .def_property_readonly("extra_bytes", [](PyRenderer& r) { return r.live().extraBytes(); },
                               "Memory kept beyond a plain render's: static pair, culling maps and hull, "
                               "hidden-surface polygons.")
        .def("__repr__", [](PyRenderer& r) {
            if (!r.renderer) return std::string("<frugal.Renderer (closed)>");
            const Settings& s = r.renderer->settings();
            return "<frugal.Renderer " + std::to_string(s.width) + "x" + std::to_string(s.height) + " on " +
                   r.renderer->backendName() + ">";
        });
    py::class_<PyWriter>(m, "Writer",
                         "Writer(threads=0, queue=0, png_level='auto'): writes frames' files on threads of its own\n"
                         "while Python renders the next frame, each frame's files as Frame.write does (a set, all or\n"
                         "nothing), in the order given. write() copies the frame's images and returns at once (it waits\n"
                         "only while `queue` frames are held: memory stays flat). The first error (a full disk, a folder\n"
                         "that is not there) stops it and is raised by the next write(), finish() or close(). threads:\n"
                         "0 = one per core (at most 4); queue: 0 = threads + 1; png_level: 0 (stored) to 12, 1 the\n"
                         "run-length encoder, 'auto' the level measured best for each kind of image (docs/writing.md).\n"
                         "Usable as a context manager: leaving the block waits for every frame.")
        .def(py::init<int, int, const py::object&>(), py::kw_only(), py::arg("threads") = 0, py::arg("queue") = 0,
             py::arg("png_level") = "auto")
        .def("write", &PyWriter::write, py::arg("frame"), py::kw_only(), py::arg("color") = py::none(),
             py::arg("depth") = py::none(), py::arg("ids") = py::none(), py::arg("linear") = py::none(),
             "Queues the frame's files: colour PNG, depth (.png 16-bit or .pfm float32), ids PNG, linear\n"
             "colour (.pfm or .png).")
        .def("finish", &PyWriter::finish, "Waits until every frame given is written; raises the first error.")
        .def("close", [](PyWriter& w) { w.close(true); },
             "finish(), then frees the threads; later calls raise InputError.")
        .def("__enter__", [](py::object self) { return self; })
        .def("__exit__", [](PyWriter& w, const py::object& type, const py::object&, const py::object&) {
            w.close(type.is_none());  // an exception already leaving the block is not replaced
        });
}

}  // namespace frugal::python
