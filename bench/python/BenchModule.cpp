// frugal_bench: everything frugal._frugal has (the same binding, python/src) plus cpp_loop, the C++
// loop bench/python/overhead.py compares Python's with. A benchmark's module, never installed: the
// module users import keeps no benchmark hook. Import it instead of frugal, not beside it (both
// register the same classes).
#include <chrono>
#include <mutex>
#include <optional>
#include <vector>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "Arrays.h"
#include "Bindings.h"
#include "RenderBindings.h"

namespace frugal::python {
namespace {

// `frames` renders through the same renderer into one Frame (as a C++ program does best), without
// Python between them; the wall time of each, in milliseconds, with the context released after
// each as render() does.
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
        if (!rendered) failed = rendered.error();
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    if (failed) throw Failure{*failed};
    return ms;
}

}  // namespace
}  // namespace frugal::python

PYBIND11_MODULE(frugal_bench, m) {
    using namespace frugal::python;
    defineModule(m);
    m.doc() = "frugal_bench: frugal's binding (the classes and functions of frugal) plus cpp_loop, for "
              "bench/python/overhead.py. Import it instead of frugal, not beside it.";
    m.def("cpp_loop", &cppLoop, py::arg("renderer"), py::arg("camera"), py::arg("time"), py::arg("frames"),
          "`frames` renders of `renderer` through `camera` at `time` in a C++ loop into one Frame, each followed "
          "by the context release render() does: the wall time of each, ms.");
}
