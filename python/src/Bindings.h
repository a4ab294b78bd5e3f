// What the binding's files share: frugal errors on their way to Python, the scene object, and the
// functions that bind each part of the module (Module.cpp calls them in turn).
#pragma once

#include <pybind11/pybind11.h>

#include <frugal/Camera.h>
#include <frugal/Result.h>
#include <frugal/Scene.h>
#include <frugal/Settings.h>
#include <frugal/Stats.h>

namespace frugal::python {

namespace py = pybind11;

// A frugal::Error on its way to Python (defineErrors' translator picks the class by its kind).
struct Failure {
    Error error;
};

template <class T>
T take(Result<T>&& result) {
    if (!result) throw Failure{result.error()};
    return std::move(*result);
}

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

void defineModule(py::module_& m);  // Module.cpp: all of frugal._frugal, each part below in turn
void defineErrors(py::module_& m);  // Module.cpp: frugal.Error and a class a kind
void bindStats(py::module_& m);     // StatsBindings.cpp: FrameStats and its parts, View, StateCosts, CullPreparation
void bindScene(py::module_& m);     // SceneBindings.cpp: Scene
void bindLoad(py::module_& m);      // SceneBindings.cpp: load
void bindCamera(py::module_& m);    // SceneBindings.cpp: Camera
void bindFrame(py::module_& m);     // RenderBindings.cpp: Frame
void bindRenderer(py::module_& m);  // RenderBindings.cpp: Renderer

// A frame's statistics and the camera it was drawn with as bindStats' objects (frugal.FrameStats,
// frugal.View); the renderer's settings say what of them the render JSON's record shows.
py::object frameStatsObject(const FrameStats& stats, const Settings& settings);
py::object viewObject(const View& view, const Settings& settings);

}  // namespace frugal::python
