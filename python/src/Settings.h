// frugal.Renderer's keyword arguments: every field of frugal::Settings, named as the command line
// names its flag (`--cull-bins` is cull_bins), and back to a dict.
#pragma once

#include <pybind11/pybind11.h>

#include <frugal/Settings.h>

namespace frugal::python {

namespace py = pybind11;

// Settings from keyword arguments, checked as a whole (settingsProblem): an unknown name, a value
// that is not what the setting takes ("cull: 'x' is not a method (none, sphere, ...)") or settings
// that may not go together ("reuse=True with cull='oracle': ...") raise InputError.
// settings=PATH reads a settings file (frugal/Settings.h) first; the other arguments win over it.
Settings settingsFrom(const py::kwargs& kwargs);

// The names settingsFrom takes, with their values in `settings`.
py::dict settingsDict(const Settings& settings);

// The schema as Python sees it: a list of dicts, one a setting, in the settings file's order.
py::list settingsSchema();

}  // namespace frugal::python
