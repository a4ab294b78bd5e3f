// frugal.Renderer's keyword arguments: every field of frugal::Settings, named as the command line
// names its flag (`--cull-bins` is cull_bins), and back to a dict.
#pragma once

#include <pybind11/pybind11.h>

#include <frugal/Settings.h>

namespace frugal::python {

namespace py = pybind11;

// Settings from keyword arguments; an unknown name or a value of the wrong form raises InputError
// naming it ("cull: 'x' is not a method (none, sphere, ...)"). Ranges are the Renderer's to check.
// settings=PATH reads a settings file (frugal/Settings.h) first; the other arguments win over it.
Settings settingsFrom(const py::kwargs& kwargs);

// The names settingsFrom takes, with their values in `settings`.
py::dict settingsDict(const Settings& settings);

}  // namespace frugal::python
