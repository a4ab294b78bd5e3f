// Helpers shared by the file loaders (internal to src/scene/, not installed).
// Loader checks read as straight-line code: a helper throws Failure, and the loader's entry point
// catches it (and anything else) and returns an Error. No exception leaves a loader.
#pragma once

#include <new>
#include <sstream>
#include <stdexcept>
#include <string>

#include <frugal/Result.h>
#include <frugal/Scene.h>

#include "base/Format.h"  // oneLine: text from the file in messages

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

// A path as messages quote it: whole, but printable (a file name can hold a line break).
inline std::string shownPath(const std::string& path) { return oneLine(path, path.size()); }

// The whole file; fails with "no such file", "is a directory, not a file", "cannot open ...".
std::string readFile(const std::string& path);

// Runs a loader body and turns every exception into "<path>: <why>": the one place where a
// loader's failures become an Error.
template <class Body>
Result<Scene> guard(const std::string& path, Body&& body) {
    try {
        return body();
    } catch (const Failure& failure) {
        return Error{shownPath(path) + ": " + failure.message};
    } catch (const std::bad_alloc&) {
        return Error{shownPath(path) + ": out of memory"};
    } catch (const std::exception& e) {
        return Error{shownPath(path) + ": " + oneLine(e.what())};
    } catch (...) {
        return Error{shownPath(path) + ": unexpected error"};
    }
}

}  // namespace frugal::load
