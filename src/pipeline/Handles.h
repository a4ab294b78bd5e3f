// Handle tables for backend objects (targets, meshes, textures). A handle is slot index + 1, so
// kNoHandle (0) is never handed out; freed slots are reused. Objects live behind unique_ptr: their
// addresses stay valid while other objects are added or removed (the software backend keeps
// pointers to meshes and textures in draws that are not rasterized yet).
#pragma once

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace frugal {

// `H` is the handle type (pipeline/Backend.h: TargetHandle, MeshHandle, TextureHandle).
template <class T, class H>
class HandleTable {
public:
    H add(T value) {
        auto item = std::make_unique<T>(std::move(value));
        if (!free_.empty()) {
            const std::uint32_t index = free_.back();
            free_.pop_back();
            items_[index] = std::move(item);
            return H{index + 1};
        }
        items_.push_back(std::move(item));
        return H{std::uint32_t(items_.size())};
    }
    // nullptr for kNoHandle, a handle never handed out, or one removed.
    T* find(H handle) const {
        if (handle.id == 0 || handle.id > items_.size()) return nullptr;
        return items_[handle.id - 1].get();
    }
    void remove(H handle) {
        if (find(handle) == nullptr) return;
        items_[handle.id - 1].reset();
        free_.push_back(handle.id - 1);
    }
    template <class F>
    void forEach(F&& f) {
        for (const std::unique_ptr<T>& item : items_)
            if (item) f(*item);
    }

private:
    std::vector<std::unique_ptr<T>> items_;
    std::vector<std::uint32_t> free_;
};

}  // namespace frugal
