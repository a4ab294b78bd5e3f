// The reports of `frugal info`: what a scene holds (and what frugal does not model), with the depth
// precision each camera gets; and the state-change costs measured on a backend.
#pragma once

#include <string>

#include <frugal/Result.h>
#include <frugal/Scene.h>
#include <frugal/Settings.h>
#include <frugal/Stats.h>

namespace frugal {

// Nodes, meshes, instances, triangles, materials, textures, the scene's detail (the length 1 % of
// its triangle edges are shorter than), cameras with the depth each format and range separates at
// the scene's far side (a warning where that is coarser than the detail), animations, bounds at
// time 0, what is not modelled and the loader's warnings; one item a line. A camera with an aspect
// ratio is judged at the size whose longer side is `longSide` (the command line's default), the
// others at 800x600.
std::string sceneInfoText(const Scene& scene, int longSide);

// The state costs measured on settings.backend (with settings.threads), as `frugal info
// --state-costs` prints them and as JSON. Errors: "backend auto: <why>" (BackendUnavailable, about
// a setting), the measurement's.
struct StateCostsOutput {
    std::string text, json;
};
Result<StateCostsOutput> stateCostsReport(const Settings& settings);

// "order best: state costs on egl-surfaceless (us): program 8.3, mesh 0.1, ..." (no newline).
std::string stateCostsLine(Order order, const std::string& backendName, const StateCosts& costs);

}  // namespace frugal
