#include <frugal/Version.h>

#ifndef FRUGAL_VERSION
#error "FRUGAL_VERSION is defined by CMakeLists.txt from the project's version"
#endif

namespace frugal {

const char* version() { return FRUGAL_VERSION; }

}  // namespace frugal
