// Errors and results. frugal never throws on bad input and never aborts on it: a function that can
// fail returns Result<T>, a value or an Error (reaching for the value of an error is the caller's
// mistake, and throws: BadResultAccess). An error is one line, "<what>: <why, with the
// numbers>" ("bunny.obj: line 12: 'nan' in a v line is not finite"), without the "error: " a command
// line puts before it, and has a kind that says what to do about it.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
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

struct Error {
    std::string message;
    ErrorKind kind = ErrorKind::BadInput;
    // The message starts with the name of a renderer setting as the command line spells it without
    // "--" ("size 16384x16384: needs about 9.7 GB ..."), so that a command line can name its flag.
    bool aboutSetting = false;
};

// What Result::value() (and * and ->) throws when the result holds an error: asking for a value
// that is not there is a mistake in the calling code, not bad input, so it fails loudly in every
// build, as std::optional::value() does, instead of reading memory that holds no value. what() is
// "frugal::Result::value() on an error: <the error's message>"; error() is the error itself.
class BadResultAccess : public std::logic_error {
public:
    explicit BadResultAccess(Error error)
        : std::logic_error("frugal::Result::value() on an error: " + error.message), error_(std::move(error)) {}
    const Error& error() const { return error_; }

private:
    Error error_;
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
    // The value; on an error, throws BadResultAccess (check ok() first).
    T& value() {
        if (!value_) throw BadResultAccess(error_);
        return *value_;
    }
    const T& value() const {
        if (!value_) throw BadResultAccess(error_);
        return *value_;
    }
    T& operator*() { return value(); }
    const T& operator*() const { return value(); }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }
    // The error, when !ok(): its message (one line), its kind, whether it is about a setting.
    const Error& error() const { return error_; }

private:
    template <class>
    friend class Result;
    std::optional<T> value_;
    Error error_;
};

}  // namespace frugal
