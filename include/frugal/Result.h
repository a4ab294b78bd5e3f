// Errors and results. frugal never throws on bad input and never aborts on it: a function that can
// fail returns Result<T>, a value or an Error. An error is one line, "<what>: <why, with the
// numbers>" ("bunny.obj: line 12: 'nan' in a v line is not finite"), without the "error: " a command
// line puts before it, and has a kind that says what to do about it.
#pragma once

#include <cassert>
#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>

namespace frugal {

enum class ErrorKind : std::uint8_t {
    BadInput,            // a scene, an image, a setting or a value that cannot be used as given
    BackendUnavailable,  // no backend of the kind asked for can run here (no GL context, no glClipControl)
    OutOfMemory,         // more memory than the process may still take (checked before, or a failed allocation)
    Interrupted,         // SIGINT, SIGTERM or SIGHUP arrived (between frames)
    Io,                  // a file that cannot be read or written
};

// "bad input", "backend unavailable", "out of memory", "interrupted", "i/o".
inline const char* errorKindName(ErrorKind kind) {
    switch (kind) {
        case ErrorKind::BadInput:
            return "bad input";
        case ErrorKind::BackendUnavailable:
            return "backend unavailable";
        case ErrorKind::OutOfMemory:
            return "out of memory";
        case ErrorKind::Interrupted:
            return "interrupted";
        case ErrorKind::Io:
            return "i/o";
    }
    return "?";
}

struct Error {
    std::string message;
    ErrorKind kind = ErrorKind::BadInput;
    // The message starts with the name of a renderer setting as the command line spells it without
    // "--" ("size 16384x16384: needs about 9.7 GB ..."), so that a command line can name its flag.
    bool aboutSetting = false;
};

template <class T>
class Result {
public:
    Result(T value) : value_(std::move(value)) {}      // NOLINT: implicit by design
    Result(Error error) : error_(std::move(error)) {}  // NOLINT
    // A result of a type T can be made from: the value converted, or the same error.
    template <class U, class = std::enable_if_t<!std::is_same_v<T, U> && std::is_constructible_v<T, U&&>>>
    Result(Result<U>&& other) : error_(other.error_) {  // NOLINT
        if (other.value_) value_.emplace(std::move(*other.value_));
    }

    explicit operator bool() const { return value_.has_value(); }
    bool ok() const { return value_.has_value(); }
    T& value() {
        assert(value_);
        return *value_;
    }
    const T& value() const {
        assert(value_);
        return *value_;
    }
    T& operator*() { return value(); }
    const T& operator*() const { return value(); }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }
    // The message, when !ok().
    const std::string& error() const { return error_.message; }
    // The whole error (message, kind), when !ok(): to pass it on as it is.
    const Error& failure() const { return error_; }
    ErrorKind errorKind() const { return error_.kind; }

private:
    template <class>
    friend class Result;
    std::optional<T> value_;
    Error error_;
};

}  // namespace frugal
