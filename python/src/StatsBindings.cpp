// What a frame cost and did (frugal/Stats.h), the camera it was drawn with (frugal/Camera.h's View)
// and what a renderer prepared, as typed Python objects: frugal.FrameStats and its parts, frugal.View,
// frugal.StateCosts, frugal.CullPreparation.
//
// Each class is a table of read-only attributes named as the render JSON's keys (docs/cli.md), with
// its units, so that `frame.stats.cull.pvs` is the record's "pvs"; a part the frame does not have is
// None. The same table makes to_dict(), which is the render JSON's object (a frame's record without
// "frame", "file" and the write times), and __repr__. Where the record depends on a setting (the
// hidden-surface mode's name, the oracle's missing "ranges", occlusion-ahead's fields), the object
// carries that setting beside the library's struct.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <frugal/Camera.h>
#include <frugal/Renderer.h>
#include <frugal/Settings.h>
#include <frugal/Stats.h>

#include "Arrays.h"
#include "Bindings.h"

namespace frugal::python {

// The library's structs with the settings their record depends on.
struct PyOcclusionStats {
    OcclusionFrameStats stats;
    bool ahead = false;  // cull occlusion-ahead: the record has "ahead" and "ahead_wait_ms"
};
struct PyCullStats {
    CullStats stats;
    bool ranges = true;  // not the oracle, which submits no index ranges
    bool ahead = false;
};
struct PyHsrStats {
    HsrStats stats;
    Hsr mode = Hsr::ZBuffer;
};
struct PyInterpStats {
    InterpStats stats;
    DepthInterp mode = DepthInterp::Exact;
};
struct PyFrameStats {
    FrameStats stats;
    Cull cull = Cull::None;
    Hsr hsr = Hsr::ZBuffer;
    DepthInterp interp = DepthInterp::Exact;
};
struct PyView {
    View view;
    int width = 0, height = 0;  // the settings' image size
};

namespace {

// Where an attribute goes in to_dict(): always (None as None), only when it is not None, or its
// own to_dict() merged in (the render JSON writes a frame's culling as keys of the frame's record).
enum class Key { Always, WhenSet, Merged };

template <class T>
struct Attribute {
    std::string name;
    std::function<py::object(const T&)> get;
    Key key;
    bool shown;  // in __repr__ (not the matrices)
};

// A value as the render JSON holds it: an object's to_dict(), a tuple as a list.
py::object plain(const py::object& value) {
    if (py::hasattr(value, "to_dict")) return value.attr("to_dict")();
    if (py::isinstance<py::tuple>(value)) {
        py::list out;
        for (const py::handle item : value) out.append(plain(py::reinterpret_borrow<py::object>(item)));
        return out;
    }
    return value;
}

// A C++ value as Python's (a Python object as it is).
template <class V>
py::object toPython(V&& value) {
    if constexpr (std::is_base_of_v<py::handle, std::decay_t<V>>) return py::reinterpret_borrow<py::object>(value);
    else return py::cast(std::forward<V>(value));
}

// A class of read-only attributes, declared in a chain of attr() calls; to_dict() and __repr__ are
// made from them when the chain's statement ends (the destructor: it may raise, as pybind11 may).
template <class T>
class Record {
public:
    Record(py::module_& m, const char* name, const char* doc)
        : class_(m, name, doc), name_(name), attributes_(std::make_shared<std::vector<Attribute<T>>>()) {}

    Record(const Record&) = delete;
    Record& operator=(const Record&) = delete;

    template <class Get>
    Record& attr(const char* name, Get get, const char* doc, Key key = Key::Always, bool shown = true) {
        std::function<py::object(const T&)> value = [get](const T& t) { return toPython(get(t)); };
        attributes_->push_back({name, value, key, shown});
        class_.def_property_readonly(name, [value](const T& t) { return value(t); }, doc);
        return *this;
    }

    ~Record() noexcept(false) {
        const auto attributes = attributes_;
        class_.def(
            "to_dict",
            [attributes](const T& t) {
                py::dict d;
                for (const Attribute<T>& a : *attributes) {
                    const py::object value = a.get(t);
                    if (value.is_none()) {
                        if (a.key == Key::Always) d[py::str(a.name)] = py::none();
                    } else if (a.key == Key::Merged) {
                        d.attr("update")(value.attr("to_dict")());
                    } else {
                        d[py::str(a.name)] = plain(value);
                    }
                }
                return d;
            },
            "The render JSON's object (docs/cli.md): plain dicts, lists and numbers.");
        class_.def("__repr__", [attributes, name = name_](const T& t) {
            std::string out = "frugal." + name + "(";
            bool first = true;
            for (const Attribute<T>& a : *attributes) {
                if (!a.shown) continue;
                out += (first ? "" : ", ") + a.name + "=" + py::repr(a.get(t)).template cast<std::string>();
                first = false;
            }
            return out + ")";
        });
    }

private:
    py::class_<T> class_;
    std::string name_;
    std::shared_ptr<std::vector<Attribute<T>>> attributes_;
};

py::tuple vec3(const glm::vec3& v) { return py::make_tuple(v.x, v.y, v.z); }

}  // namespace

void bindStats(py::module_& m) {
    Record<StateChanges>(m, "StateChanges",
                         "The state changes the backend issued for one frame, by kind (GL: the calls its state "
                         "cache let through; software: the draws alone).")
        .attr("draws", [](const StateChanges& c) { return c.draws; }, "draw calls")
        .attr("programs", [](const StateChanges& c) { return c.programs; }, "program binds (a shader variant)")
        .attr("meshes", [](const StateChanges& c) { return c.meshes; }, "vertex array binds")
        .attr("textures", [](const StateChanges& c) { return c.textures; }, "texture binds")
        .attr("toggles", [](const StateChanges& c) { return c.toggles; },
              "glEnable / glDisable: face culling, depth test, scissor")
        .attr("uniforms", [](const StateChanges& c) { return c.uniforms; },
              "uniform uploads: transforms, material, lighting, first id");

    Record<PyOcclusionStats>(m, "OcclusionFrameStats",
                             "The occlusion pass of one frame (cull occlusion and occlusion-ahead).")
        .attr("ran", [](const PyOcclusionStats& o) { return o.stats.ran; },
              "whether it ran (it skips itself where it does not pay)")
        .attr("ms", [](const PyOcclusionStats& o) { return o.stats.ms; },
              "its time, ms (within cull_ms unless the plan was made ahead)")
        .attr("triangles_hidden", [](const PyOcclusionStats& o) { return o.stats.trianglesHidden; },
              "triangles of the conservative plan it dropped")
        .attr("ahead", [](const PyOcclusionStats& o) { return o.ahead ? std::optional<bool>(o.stats.ahead) : std::nullopt; },
              "occlusion-ahead: whether the plan was made while the frame before drew; else None", Key::WhenSet)
        .attr("ahead_wait_ms",
              [](const PyOcclusionStats& o) { return o.ahead ? std::optional<double>(o.stats.aheadWaitMs) : std::nullopt; },
              "occlusion-ahead: what this frame waited after its draw for the next frame's plan, ms (within "
              "render_ms); else None",
              Key::WhenSet);

    Record<PyCullStats>(m, "CullStats",
                        "Culling in one frame (a cull other than none). The render JSON writes these keys in the "
                        "frame's record itself, and so does FrameStats.to_dict().")
        .attr("tos", [](const PyCullStats& c) { return c.stats.tos; }, "the scene's triangles")
        .attr("pvs", [](const PyCullStats& c) { return c.stats.pvs; },
              "the triangles submitted (the oracle: its visible set)")
        .attr("cull_ms", [](const PyCullStats& c) { return c.stats.ms; },
              "culling, ms (the oracle: its id pass, read-back and scene; not in render_ms)")
        .attr("ranges", [](const PyCullStats& c) { return c.ranges ? std::optional<std::size_t>(c.stats.ranges) : std::nullopt; },
              "index ranges submitted; None for the oracle", Key::WhenSet)
        .attr("occlusion",
              [](const PyCullStats& c) {
                  return c.stats.occlusion ? std::optional<PyOcclusionStats>(PyOcclusionStats{*c.stats.occlusion, c.ahead})
                                           : std::nullopt;
              },
              "the occlusion pass (cull occlusion and occlusion-ahead); else None", Key::WhenSet);

    Record<ReuseCounts>(m, "ReuseCounts", "A count per reuse state: dynamic or static before and now.")
        .attr("p_dd", [](const ReuseCounts& c) { return c.dd; }, "dynamic then and now")
        .attr("p_ds", [](const ReuseCounts& c) { return c.ds; }, "dynamic then, static now")
        .attr("p_sd", [](const ReuseCounts& c) { return c.sd; }, "static then, dynamic now")
        .attr("p_ss", [](const ReuseCounts& c) { return c.ss; }, "static then and now");

    Record<ReuseStats>(m, "ReuseStats",
                       "Temporal reuse in one frame (reuse=True): the mode, its reason, what was copied, cleared and "
                       "drawn again.")
        .attr("mode", [](const ReuseStats& s) { return std::string(toString(s.mode)); }, "full, rebuild or reuse")
        .attr("reason", [](const ReuseStats& s) { return s.reason; }, "why this mode: 'camera moved', ...")
        .attr("p_dd", [](const ReuseStats& s) { return s.triangles.dd; }, "triangles of instances dynamic then and now")
        .attr("p_ds", [](const ReuseStats& s) { return s.triangles.ds; }, "triangles dynamic then, static now")
        .attr("p_sd", [](const ReuseStats& s) { return s.triangles.sd; }, "triangles static then, dynamic now")
        .attr("p_ss", [](const ReuseStats& s) { return s.triangles.ss; }, "triangles static then and now")
        .attr("instances", [](const ReuseStats& s) { return s.instances; }, "instances per state")
        .attr("copied_px", [](const ReuseStats& s) { return s.copiedPx; }, "pixels copied between the targets")
        .attr("cleared_px", [](const ReuseStats& s) { return s.clearedPx; }, "pixels cleared")
        .attr("redrawn_tris", [](const ReuseStats& s) { return s.redrawnTris; }, "every triangle this frame drew")
        .attr("static_redrawn_tris", [](const ReuseStats& s) { return s.staticRedrawnTris; },
              "of those, static ones drawn again")
        .attr("rects", [](const ReuseStats& s) { return s.rects; }, "clear and copy rectangles issued")
        .attr("plan_ms", [](const ReuseStats& s) { return s.planMs; }, "the whole plan, ms")
        .attr("overlap_ms", [](const ReuseStats& s) { return s.overlapMs; }, "grid marking and overlap tests, ms")
        .attr("extent_ms", [](const ReuseStats& s) { return s.extentMs; }, "extents of the instances that moved, ms");

    Record<PyHsrStats>(m, "HsrStats", "A hidden-surface mode's plan in one frame (an hsr other than zbuffer).")
        .attr("mode", [](const PyHsrStats& h) { return std::string(toString(h.mode)); }, "the hsr setting")
        .attr("polygons", [](const PyHsrStats& h) { return h.stats.polygons; },
              "listed polygons (in view, not clearly back-facing)")
        .attr("zbuffered_polygons", [](const PyHsrStats& h) { return h.stats.zbuffered(h.mode); },
              "polygons drawn with the depth test")
        .attr("zbuffered_share", [](const PyHsrStats& h) { return h.stats.zbufferedShare(h.mode); },
              "their share: 0 for depthsort")
        .attr("draws", [](const PyHsrStats& h) { return h.stats.draws; }, "draw commands in the plan")
        .attr("plan_ms", [](const PyHsrStats& h) { return h.stats.ms; }, "extents, sort, flags and the list, ms");

    Record<PyInterpStats>(m, "InterpStats",
                          "The software backend's span interpolator in one frame (interp other than exact).")
        .attr("mode", [](const PyInterpStats& i) { return std::string(toString(i.mode)); }, "the interp setting")
        .attr("spans", [](const PyInterpStats& i) { return i.stats.spans; }, "covered runs filled")
        .attr("overflow", [](const PyInterpStats& i) { return i.stats.overflow; },
              "runs whose 24-bit depth overflowed and was clamped");

    Record<PyFrameStats>(m, "FrameStats",
                         "What one frame cost and did. to_dict() is the render JSON's record of the frame (without "
                         "frame, file and the write times), culling's keys at its top level.")
        .attr("time", [](const PyFrameStats& f) { return f.stats.time; }, "scene time, seconds")
        .attr("render_ms", [](const PyFrameStats& f) { return f.stats.renderMs; },
              "culling, planning and drawing until the backend finished, ms")
        .attr("readback_ms", [](const PyFrameStats& f) { return f.stats.readbackMs; }, "reading the images back, ms")
        .attr("cull",
              [](const PyFrameStats& f) {
                  const CullTraits& traits = traitsOf(f.cull);
                  return f.stats.cull ? std::optional<PyCullStats>(PyCullStats{*f.stats.cull, !traits.idPass, traits.ahead})
                                      : std::nullopt;
              },
              "culling (a cull other than none); else None", Key::Merged)
        .attr("reuse", [](const PyFrameStats& f) { return f.stats.reuse; }, "temporal reuse (reuse=True); else None",
              Key::WhenSet)
        .attr("hsr",
              [](const PyFrameStats& f) {
                  return f.stats.hsr ? std::optional<PyHsrStats>(PyHsrStats{*f.stats.hsr, f.hsr}) : std::nullopt;
              },
              "the hidden-surface plan (an hsr other than zbuffer); else None", Key::WhenSet)
        .attr("state_changes", [](const PyFrameStats& f) { return f.stats.stateChanges; },
              "what the backend issued for this frame")
        .attr("interp",
              [](const PyFrameStats& f) {
                  return f.stats.interp ? std::optional<PyInterpStats>(PyInterpStats{*f.stats.interp, f.interp})
                                        : std::nullopt;
              },
              "the span interpolator (software backend, interp other than exact); else None", Key::WhenSet)
        .attr("refined_state_costs_us", [](const PyFrameStats& f) { return f.stats.refinedCostsUs; },
              "a cost-driven order's state costs (us a change, by kind: Renderer.state_costs.kinds) as the cost round "
              "run between the frame before and this one left them; else None",
              Key::WhenSet)
        .attr("refine_ms",
              [](const PyFrameStats& f) {
                  return f.stats.refinedCostsUs ? std::optional<double>(f.stats.refineMs) : std::nullopt;
              },
              "that cost round's time, ms (outside every other timing); else None", Key::WhenSet);

    Record<PyView>(m, "View",
                   "The camera as resolved for one frame: where it came from, its planes and aspect ratios (the "
                   "render JSON's 'camera'), and its 4x4 matrices.")
        .attr("source", [](const PyView& v) { return v.view.source; },
              "'scene camera 0 'name'', 'eye/target', 'auto (fit bounds)', ...")
        .attr("eye", [](const PyView& v) { return vec3(v.view.eye); }, "(x, y, z), world space")
        .attr("forward", [](const PyView& v) { return vec3(v.view.forward); }, "the view direction, unit length")
        .attr("perspective", [](const PyView& v) { return v.view.perspective; }, "False: orthographic")
        .attr("yfov_degrees", [](const PyView& v) { return glm::degrees(v.view.yfov); },
              "vertical field of view, degrees (perspective)")
        .attr("znear", [](const PyView& v) { return v.view.znear; }, "the near plane drawn with")
        .attr("zfar", [](const PyView& v) { return v.view.zfar; }, "the far plane drawn with (0: infinite)")
        .attr("depth_range", [](const PyView& v) { return std::string(depthRangeName(v.view.depthRange)); },
              "fit (planes moved in to the scene) or file (as given)")
        .attr("given_znear", [](const PyView& v) { return v.view.givenNear; }, "the camera's near plane, before the fit")
        .attr("given_zfar", [](const PyView& v) { return v.view.givenFar; }, "the camera's far plane, before the fit")
        .attr("depth_format", [](const PyView& v) { return std::string(depthFormatName(v.view.depthFormat)); },
              "d24 or d32f")
        .attr("aspect_ratio", [](const PyView& v) { return v.view.aspect; }, "width / height of the projection")
        .attr("file_aspect_ratio",
              [](const PyView& v) { return v.view.fileAspect > 0.0f ? std::optional<float>(v.view.fileAspect) : std::nullopt; },
              "the scene camera's own aspect ratio; else None")
        .attr("aspect_ratio_differs",
              [](const PyView& v) { return aspectDiffers(v.view.fileAspect, v.width, v.height); },
              "the scene camera's aspect ratio is not the image's (the picture keeps the vertical extent)")
        .attr("view_matrix", [](const PyView& v) { return matrixArray(v.view.view); },
              "4x4 float32 world-to-camera matrix, row-major as numpy prints it (a copy)", Key::Always, false)
        .attr("projection_matrix", [](const PyView& v) { return matrixArray(v.view.projection); },
              "4x4 float32 projection (OpenGL clip space), row-major (a copy)", Key::Always, false);

    Record<StateCosts>(m, "StateCosts",
                       "The state-change costs a cost-driven order uses (order paper, greedy, best), measured on the "
                       "backend and refined between frames (the render JSON's 'state_costs').")
        .attr("kinds", [](const StateCosts& c) { return c.kinds; },
              "program, mesh, texture, material, culling, depth")
        .attr("start_us", [](const StateCosts& c) { return c.startUs; }, "the first measurement, us a change by kind")
        .attr("us", [](const StateCosts& c) { return c.us; }, "now: the interquartile mean of the last 32 rounds")
        .attr("rounds", [](const StateCosts& c) { return c.rounds; }, "cost rounds run")
        .attr("refine_every", [](const StateCosts& c) { return c.refineEvery; }, "frames between two rounds");

    Record<Renderer::CullPreparation>(m, "CullPreparation",
                                      "What preparing the culling took when the renderer was made, and what it keeps.")
        .attr("sphere_ms", [](const Renderer::CullPreparation& p) { return p.sphereMs; }, "bounding spheres, ms")
        .attr("map_ms", [](const Renderer::CullPreparation& p) { return p.mapMs; }, "the per-mesh maps, ms")
        .attr("cluster_ms", [](const Renderer::CullPreparation& p) { return p.clusterMs; }, "clusters, ms")
        .attr("hull_ms", [](const Renderer::CullPreparation& p) { return p.hullMs; }, "convex hulls, ms (paper)")
        .attr("total_ms", [](const Renderer::CullPreparation& p) { return p.totalMs; }, "all of it, ms")
        .attr("hull", [](const Renderer::CullPreparation& p) { return p.hull; }, "whether hulls were built (paper)")
        .attr("bytes", [](const Renderer::CullPreparation& p) { return p.bytes; },
              "the maps and the hulls' vertices kept");
}

py::object frameStatsObject(const FrameStats& stats, const Settings& settings) {
    return py::cast(PyFrameStats{stats, settings.cull, settings.hsr, settings.interp});
}

py::object viewObject(const View& view, const Settings& settings) {
    return py::cast(PyView{view, settings.width, settings.height});
}

}  // namespace frugal::python
