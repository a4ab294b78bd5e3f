// The oracle of culling: a frame's really visible set (an id pass of the full render), drawn from
// index buffers of its own. A lower bound on what any culling method can submit, not a shortcut.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <frugal/Result.h>
#include <frugal/Scene.h>

#include "pipeline/SceneRenderer.h"
#include "cull/VisibleSet.h"

namespace frugal {

struct Oracle {
    TriangleSet rvs;
    std::unique_ptr<Scene> scene;  // stable address: the renderer points to it
    std::optional<SceneRenderer> renderer;
    double ms = 0.0;  // id pass + read-back + set + oracle scene (upload excluded)
};

// Draws `frame` whole with ids into `target` (its contents are overwritten), then builds the oracle.
// With blended surfaces (AlphaMode::Blend) it draws a second frame without them: the visible set is
// what either frame's ids show (the full one's, and what lies behind the blended surfaces), and the
// oracle keeps every blended instance whole.
// Error: the visible set's ("id N at pixel ... belongs to no triangle") or a refused upload.
Result<Oracle> makeOracle(SceneRenderer& full, TargetHandle target, int width, int height, FrameParams frame,
                          const std::vector<glm::mat4>& world, const glm::vec4& background);

}  // namespace frugal
