// What the harnesses add to a stage (renderer/Stage.h): one opened on a backend kind among several,
// where a kind this machine lacks is skipped rather than an error, and targets of their own that go
// with their scope.
#pragma once

#include <optional>
#include <string>

#include <frugal/Result.h>
#include <frugal/Settings.h>

#include "render/Backend.h"
#include "renderer/Stage.h"

namespace frugal {

// Stage::open(settings) where a backend that does not open here is no error: the result is then
// empty and `unavailable` gets openBackend's reason ("no usable GL context: ..."), without the
// "backend KIND: " Stage::open puts before it. Every other failure (the depth format, the memory,
// the target's size) is the error, as Stage::open gives it.
Result<std::optional<Stage>> openStageIfAvailable(const Settings& settings, std::string& unavailable);

// A target of `backend` (kNoHandle: none), destroyed when this goes or is reset. It must go before
// the backend: declare it after the stage that owns the backend.
class OwnedTarget {
public:
    explicit OwnedTarget(Backend& backend, TargetHandle handle = kNoHandle) : backend_(backend), handle_(handle) {}
    ~OwnedTarget() { reset(kNoHandle); }
    OwnedTarget(const OwnedTarget&) = delete;
    OwnedTarget& operator=(const OwnedTarget&) = delete;

    TargetHandle get() const { return handle_; }
    void reset(TargetHandle handle) {
        if (handle_ != kNoHandle) backend_.destroyTarget(handle_);
        handle_ = handle;
    }

private:
    Backend& backend_;
    TargetHandle handle_;
};

}  // namespace frugal
