// frugal._frugal: the library's entry point (frugal/Renderer.h) for Python. Scenes (loaded or built
// from numpy arrays), cameras, a renderer whose keyword arguments are the command line's options,
// and frames whose images are numpy arrays. The GIL is released while anything renders, loads or
// writes; errors are exceptions under frugal.Error, one class per frugal::ErrorKind. This file: the
// exception classes and the module's contents (defineModule); SceneBindings.cpp, RenderBindings.cpp
// and StatsBindings.cpp: the classes; Extension.cpp: the extension _frugal itself.
#include <string>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <frugal/Settings.h>
#include <frugal/Version.h>

#include "Arrays.h"
#include "Bindings.h"
#include "Settings.h"

namespace frugal::python {

namespace {

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

}  // namespace

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

void defineModule(py::module_& m) {
    m.doc() = "frugal: an offscreen OpenGL renderer that does only the work a scene requires.";
    m.attr("__version__") = version();
    defineErrors(m);
    bindStats(m);
    bindScene(m);
    bindLoad(m);
    bindCamera(m);
    bindFrame(m);
    bindRenderer(m);
    m.def("settings_names", [] { return py::list(settingsDict(Settings{}).attr("keys")()); },
          "The keyword arguments frugal.Renderer takes.");
    m.def("default_settings", [] { return settingsDict(Settings{}); }, "Every setting with its default.");
    m.def("settings_schema", &settingsSchema,
          "Every setting as a dict: name (the keyword), option (the command line's flag, or None), key (in a "
          "settings file), kind (switch, whole, pair, choice, colour), default, help, choices, range, expected (what "
          "a refusal says a value is not), conflicts (the settings it may not go with).");
    m.def("settings", [](const py::kwargs& kwargs) { return settingsDict(settingsFrom(kwargs)); },
          "Every setting as frugal.Renderer(scene, **kwargs) would take them (settings='file.json' first, the others "
          "over it), checked as it checks them: raises InputError on a value out of its range or settings that may "
          "not go together.");
}

}  // namespace frugal::python
