// Shader sources from shaders/, embedded at build time by cmake/EmbedShaders.cmake.
#pragma once

namespace frugal::shaders {
// The text of shaders/<name> (e.g. "mesh.vert"), or nullptr if there is no such file.
const char* find(const char* name);
}  // namespace frugal::shaders
