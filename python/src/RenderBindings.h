// frugal.Renderer and frugal.Frame as C++ types: what RenderBindings.cpp binds, and what a module
// built for a benchmark (bench/python/BenchModule.cpp) reaches through them.
#pragma once

#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include <pybind11/pybind11.h>

#include <frugal/Renderer.h>

#include "Bindings.h"

namespace frugal::python {

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

// One frugal::Renderer, used by one thread at a time (the lock), with its context released after
// every call so that the next may come from another thread. close() frees it before the garbage
// collector would.
struct PyRenderer {
    std::optional<Renderer> renderer;
    std::mutex lock;
    std::shared_ptr<FramePool> pool = std::make_shared<FramePool>();

    PyRenderer(PyScene& scene, const py::kwargs& kwargs);
    ~PyRenderer() { close(); }

    void close();

    // The renderer, or InputError once closed. Callers hold the lock where it renders.
    Renderer& live();

    PyFrame render(const std::optional<Camera>& camera, double time, const std::optional<Camera>& nextCamera,
                   const std::optional<double>& nextTime);

    void setTransform(int node, const py::handle& transform);
};

}  // namespace frugal::python
