// The software reference backend: renders what the GL backend renders, with the rules of Mesa's
// llvmpipe (stated in software/Rasterizer.h), so that every GL image can be compared with it.
//
// Same targets, formats and operations as render/Backend.h. The rules it reproduces, with their
// sources in Mesa 22.3 and the experiments that settled what the sources leave open, are written
// down in software/Rasterizer.h (vertex stage, clipping, culling, coverage, depth) and
// software/Shading.h (varyings, shading, textures, colour conversion, clears). Measured against the
// GL backend on llvmpipe by tests/software/: coverage, 24-bit depth, ids and colour identical on
// every test (random and degenerate triangles, whole scenes, textures, clear/copy sequences).
//
// Work is deferred like llvmpipe's: draw() runs the vertex stage (each vertex once, in parallel
// chunks) and triangle setup (in parallel chunks for large draws) and bins the triangles into 64×64
// tiles; clear, copy, readBack, finish, destroyTarget and a beginFrame on another target rasterize
// what is pending, one tile per thread at a time, with AVX2 kernels when the CPU has AVX2 and FMA.
#pragma once

#include <memory>

#include "render/Backend.h"

namespace frugal {

struct SoftwareOptions {
    int threads = 0;   // threads in all, the caller included; 0 = as many as the machine has cores
    bool simd = true;  // false: the portable kernels even when the CPU has AVX2 (same results; tests)
};

std::unique_ptr<Backend> makeSoftwareBackend(const SoftwareOptions& options = {});

}  // namespace frugal
