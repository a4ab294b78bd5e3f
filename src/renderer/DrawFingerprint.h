// A frame's draws as one number (FrameStats::drawFingerprint): what the backend was asked to do, in
// order. `frugal report` compares it with the plain render's to find methods that changed nothing
// (an order of a single draw, a cull that keeps every triangle): their draws are the plain render's.
#pragma once

#include <cstdint>

#include "pipeline/Plan.h"

namespace frugal {

// The fingerprint of a frame plan: each step's op and targets; a clear's and a copy's rectangles; a
// draw's commands as runs of triangles (instance, depth mode, first triangle, count), adjacent ranges
// of one instance with one depth mode joined into one run, empty ones left out, so a list that splits
// the same triangles differently has the same fingerprint. `seed` holds what changes how the backend
// draws the same calls (the interpolator). Never 0.
std::uint64_t drawFingerprint(const FramePlan& plan, std::uint64_t seed);

// The same for the usual frame (SceneRenderer::renderFrame): the whole width × height target cleared,
// then `list` drawn into it; equal to the fingerprint of that two-step plan.
std::uint64_t drawFingerprint(const DrawList& list, int width, int height, std::uint64_t seed);

}  // namespace frugal
