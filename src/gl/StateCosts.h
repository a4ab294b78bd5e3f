// Render-state change costs C(s) of paper 004, measured on the backend that runs, not assumed
// (issue 10). Written against the Backend interface alone, so the software backend is measured
// the same way as a GL one (its "changes" cost what its draw set-up does with them: little).
//
// How (measureStateCosts): a 64×64 target and a one-triangle mesh covering a few pixels, so that
// a draw is almost all per-draw work. A round draws `draws` times in one frame and waits for the
// backend (finish); the baseline round repeats one draw exactly, each kind's round alternates
// between two values of that state only:
//   program   a mesh with vertex colours and one without (another shader variant; both rounds
//             switch meshes, the mesh round between two identical meshes, and the program's cost
//             is the difference: program = (colours ↔ plain) − mesh)
//   mesh      two identical meshes (vertex array and buffers)
//   texture   two resident 4×4 textures
//   material  two base colour factors (a uniform)
//   culling   single- and double-sided (face culling on and off)
//   depth     DepthMode Test and Off (the depth test on and off)
// C(kind) = (round time − baseline round time) ÷ draws, the median over `rounds` rounds, kinds
// interleaved within each round so that drift hits all alike; the spread is the range of the
// per-round figures. Where the data lives matters (the paper's texture from disk): also timed once
// each, a 256×256 texture's upload, its first draw (where a GL driver may copy or convert it), and
// a draw in a state combination the backend has not drawn before (llvmpipe compiles a shader
// variant per new combination) against the same draw repeated.
#pragma once

#include <string>
#include <vector>

#include "base/Result.h"
#include "render/Backend.h"

namespace frugal {

struct StateCost {
    std::string kind;        // "program", "mesh", "texture", "material", "culling", "depth"
    double us = 0.0;         // per change, median over rounds (may be ≤ 0 within noise)
    double minUs = 0.0, maxUs = 0.0;  // the range over rounds
};

struct StateCostReport {
    std::string backend, renderer;
    int rounds = 0, draws = 0;
    double drawUs = 0.0;  // one draw with no state change (the baseline), median
    std::vector<StateCost> costs;  // in the order of the list above
    double textureUploadMs = 0.0;      // uploadTexture of a 256×256 RGBA texture
    double textureFirstDrawMs = 0.0;   // the first draw that samples it, to finish
    double textureResidentDrawMs = 0.0;  // the same draw again
    double newCombinationMs = 0.0;     // a draw in a state combination not drawn before, to finish
    double seenCombinationMs = 0.0;    // the same draw again
};

// Measures `backend` (which must have no frame in progress that matters: it draws into a target of
// its own, destroyed after). `rounds` ≥ 1, `draws` ≥ 1. Error: the backend refused the target, a
// mesh or a texture ("state costs: <what> refused").
Result<StateCostReport> measureStateCosts(Backend& backend, int rounds = 9, int draws = 400);

}  // namespace frugal
