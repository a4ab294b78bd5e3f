// The software reference backend: renders what the GL backend renders, with the rules of Mesa's
// llvmpipe (stated in raster/Rasterizer.h), so that every GL image can be compared with it.
//
// Same targets, formats and operations as pipeline/Backend.h. The rules it reproduces, with their
// sources in Mesa 22.3 and the experiments that settled what the sources leave open, are written
// down in raster/Rasterizer.h (vertex stage, clipping, culling, coverage, depth) and
// software/Shading.h (varyings, shading, textures, colour conversion, clears). Measured against the
// GL backend on llvmpipe by tests/software/: coverage, 24-bit depth, ids and colour identical on
// every test (random and degenerate triangles, whole scenes, textures, clear/copy sequences).
//
// Work is deferred like llvmpipe's: draw() runs the vertex stage (each vertex once, in parallel
// chunks) and triangle setup (in parallel chunks for large draws) and bins the triangles into 64×64
// tiles; clear, copy, readBack, finish, destroyTarget and a beginFrame on another target rasterize
// what is pending, one tile per thread at a time, with AVX2 kernels when the CPU has AVX2 and FMA.
//
// Depth interpolation (SoftwareOptions::interp). Exact, the default, is the above: every fragment's
// depth from the plane equation, llvmpipe's bits. Span and Dda are a separate slow path
// (software/InterpRaster.h) that models paper 001's scan-line hardware for depth only: each covered
// run of a triangle's row gets its two ends from the plane, as Exact computes them, and its pixels
// from span::fillSpan (the midpoint-subdivision engine, or add-and-shift), 24 bits wide; the depth
// test and write use those values. Colour is not interpolated along the span: frugal shades per
// fragment (Shading.h), not Gouraud, so a colour changes only where a depth test flips.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include "pipeline/Backend.h"
#include "span/Interp.h"

namespace frugal {

struct SoftwareOptions {
    int threads = 0;   // threads in all, the caller included; 0 = as many as the machine has cores
    bool simd = true;  // false: the portable kernels even when the CPU has AVX2 (same results; tests)
    span::Interp interp = span::Interp::Exact;  // depth along a span (above); not Exact: the slow path
};

std::unique_ptr<Backend> makeSoftwareBackend(const SoftwareOptions& options = {});

// The interpolation slow path's counters: a frame's InterpStats (frugal/Stats.h) and which of the
// span engine's outputs overflowed (span/Engine.h OverflowBits of every call, or'ed).
struct InterpCounters {
    std::uint64_t spans = 0, pixels = 0, overflow = 0;  // as InterpStats
    std::uint8_t overflowBits = 0;
};

// The counters since a backend made by makeSoftwareBackend was made (all zero in Exact mode);
// nothing for any other backend. Read them after readBack or finish (pending draws are not
// rasterized yet).
std::optional<InterpCounters> softwareInterpStats(const Backend& backend);

}  // namespace frugal
