// Helpers shared by the file loaders (internal to src/scene/, not installed).
// Loader checks read as straight-line code: a helper throws Failure, and the loader's entry point
// catches it (and anything else) and returns an Error. No exception leaves a loader.
#pragma once

#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

#include "base/Result.h"
#include "scene/Scene.h"

namespace frugal::load {

struct Failure {
    std::string message;
};

template <class... Args>
std::string cat(const Args&... args) {
    std::ostringstream out;
    (out << ... << args);
    return out.str();
}

template <class... Args>
[[noreturn]] void fail(const Args&... args) {
    throw Failure{cat(args...)};
}

// Text from the file (names, URIs, library messages) goes into one-line messages: control characters
// become spaces, bytes that are not UTF-8 become '?', runs of spaces collapse, and it is capped.
std::string oneLine(std::string_view text, std::size_t maxLength = 200);

// The whole file; fails with "no such file", "is a directory, not a file", "cannot open ...".
std::string readFile(const std::string& path);

// Runs a loader body and turns every exception into "<path>: <why>": the one place where a
// loader's failures become an Error.
template <class Body>
Result<Scene> guard(const std::string& path, Body&& body) {
    try {
        return body();
    } catch (const Failure& failure) {
        return Error{path + ": " + failure.message};
    } catch (const std::bad_alloc&) {
        return Error{path + ": out of memory"};
    } catch (const std::exception& e) {
        return Error{path + ": " + oneLine(e.what())};
    } catch (...) {
        return Error{path + ": unexpected error"};
    }
}

}  // namespace frugal::load
