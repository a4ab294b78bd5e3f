// The library's version, as the CMake project declares it (project(frugal VERSION ...)).
#pragma once

namespace frugal {

// "MAJOR.MINOR.PATCH" of the library linked: the same string `frugal --version` prints.
const char* version();

}  // namespace frugal
