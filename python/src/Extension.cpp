// The extension module frugal._frugal: everything defineModule puts in it (Module.cpp). The binding's
// other files are shared with the benchmark's module (bench/python/BenchModule.cpp), which is this
// one plus a C++ loop to compare with.
#include <pybind11/pybind11.h>

#include "Bindings.h"

PYBIND11_MODULE(_frugal, m) { frugal::python::defineModule(m); }
