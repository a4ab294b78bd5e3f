// Camera-path files: a JSON list of cameras, [{"eye":[x,y,z],"target":[x,y,z],"up":[x,y,z],"fov":deg}, ...]
// ("up" and "fov" optional; {"views": [...]} is accepted too). `frugal cull-report --camera-path`
// takes each entry as a view; `frugal render` and `frugal reuse-bench` take entry i for frame A + i
// of --frames A:B and hold the last entry after the list ends (two equal entries = a still camera).
#pragma once

#include <string>
#include <vector>

#include <frugal/Result.h>

#include "render/Camera.h"

namespace frugal {

// Errors name the flag, the file and the entry: "--camera-path F: entry 3: eye: expected 3 numbers".
Result<std::vector<Camera>> readCameraPath(const std::string& path);

}  // namespace frugal
