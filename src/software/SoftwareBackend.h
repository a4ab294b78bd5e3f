// The software reference backend: renders what the GL backend renders, with the rules of Mesa's
// llvmpipe (../shared/LLVMPIPE-RULES.md), so that every GL image can be compared with it.
//
// Same targets, formats and operations as render/Backend.h; the rules it reproduces, and their
// sources, are written down in software/Rasterizer.h (coverage, clipping, depth) and
// software/Shading.h (varyings, shading, textures, clears). Measured against the GL backend on
// llvmpipe (tests/software/): coverage and 24-bit depth identical, ids identical, colour within 1.
//
// Work is deferred like llvmpipe's: draw() runs the vertex stage and triangle setup and bins the
// triangles into 64×64 tiles; clear, copy, readBack, finish, destroyTarget and a beginFrame on
// another target rasterize what is pending, one tile per thread at a time.
#pragma once

#include <memory>

#include "render/Backend.h"

namespace frugal {

struct SoftwareOptions {
    int threads = 0;    // threads in all, the caller included; 0 = as many as the machine has cores
    bool simd = true;   // false: the portable kernels even when the CPU has AVX2 (same results; tests)
};

std::unique_ptr<Backend> makeSoftwareBackend(const SoftwareOptions& options = {});

}  // namespace frugal
