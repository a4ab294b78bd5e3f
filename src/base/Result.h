// Result<T>: a value or a one-line error message. Loaders and the CLI return these instead of
// throwing: bad input is data, not a contract violation (see STYLE.md, "Errors").
#pragma once

#include <cassert>
#include <optional>
#include <string>
#include <utility>

namespace frugal {

struct Error {
    std::string message;  // "<who/what>: <why, with the numbers>", without the "error: " prefix
};

template <class T>
class Result {
public:
    Result(T value) : value_(std::move(value)) {}  // NOLINT: implicit by design
    Result(Error error) : error_(std::move(error.message)) {}  // NOLINT

    explicit operator bool() const { return value_.has_value(); }
    bool ok() const { return value_.has_value(); }
    T& value() { assert(value_); return *value_; }
    const T& value() const { assert(value_); return *value_; }
    T& operator*() { return value(); }
    const T& operator*() const { return value(); }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }
    const std::string& error() const { return error_; }

private:
    std::optional<T> value_;
    std::string error_;
};

}  // namespace frugal
