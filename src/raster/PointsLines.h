// llvmpipe's rules for points and line segments (Mesa 22.3.6, desktop GL core context, an FBO with a
// depth buffer, point size and line width 1, no smoothing or stipple, the vertex stage not writing
// gl_PointSize): what the software backend draws for a mesh of Topology::Points or Lines, as
// Rasterizer.h is for triangles. Transcribed from Mesa's sources (draw_pipe_clip.c clip_point and
// clip_line, lp_setup_point.c, lp_setup_line.c, lp_rast_tri_tmp.h, lp_setup_tri.c's binning) and
// checked against llvmpipe on 576,000 random draws (points and the three line modes, 1 and 4
// samples, window coordinates on and off the sub-pixel grid, on pixel centres and edges, on the
// viewport's edges, w near 0 and negative, beyond near and far, zero-length and 1e-7-long segments,
// exact 45°): coverage and depth equal bit for bit. tests/software/PointsLinesGLTest.cpp holds it.
//
// 1. Vertex stage, window coordinates, clip mask: as triangles (Rasterizer.h, 1.).
// 2. Clipping. A point is drawn only when its clip mask is 0 (its centre inside every plane, near
//    and far included); a point on the edge (x = ±w) is drawn; there is no partial point. A segment
//    with both masks 0 is set up with the vertex stage's window coordinates; one whose masks share
//    a bit is dropped; otherwise, for each bit of mask0 | mask1 in increasing order, against planes
//    (−1,0,0,1), (1,0,0,1), (0,−1,0,1), (0,1,0,1), (0,0,1,1) (D32F: (0,0,1,0)), (0,0,−1,1):
//    dp = ((x·a + y·b) + z·c) + w·d at each end (non-finite: dropped); dp1 < 0: t1 = max(t1,
//    dp1/(dp1 − dp0)); dp0 < 0: t0 = max(t0, dp0/(dp0 − dp1)); t0 + t1 ≥ 1: dropped. Each end with a
//    non-zero mask becomes v + t·(other − v) (per component), its window coordinates by the C code of
//    interp() (Rasterizer.h's clippedWindowVertex); the other keeps the vertex stage's.
// 3. Fixed point: snap(a) = round half away from zero of 256·a (util_iround: f ≥ 0 ? int(f + 0.5f) :
//    int(f − 0.5f), the add in float), not the triangles' round-half-even. A sample at fixed (X, Y)
//    is inside a plane (c, dcdx, dcdy) when c − dcdx·X + dcdy·Y > 0; X = 256·px single-sampled (the
//    0.5 is taken from the vertices), X = 256·px + sample offset with 4 samples (Rasterizer.h, 6.).
// 4. Points: fw = max(256, snap(size)); X0 = snap(x − po) − fw/2, X1 = X0 + fw (po = 0.5, 0 with 4
//    samples), the same in y: a sample is covered when X0 ≤ X < X1 and Y0 ≤ Y < Y1. Its depth is
//    the vertex's window z, constant. (Size 1, one sample: exactly one pixel; x = 10.0 lands in
//    pixel 9, 10.5 in 10.)
// 5. Segments, one sample ("diamond exit", lp_setup_line.c with rectangular lines off): x-major
//    when |dx| ≥ |dy|; each end's offset from its pixel's centre decides whether the end pixel is
//    drawn (the start is when the end lies inside its pixel's diamond, the end is not); an end whose
//    decision differs from what the plain quad would give is moved along the segment to its pixel's
//    edge; then a parallelogram one pixel across the minor axis (±128 in fixed point) from end to
//    end, its four edges planes with the top-left fill rule. In a strip the shared pixel is drawn
//    once, by the later segment. A segment with dx² + dy² = 0 is dropped.
// 6. Segments, 4 samples (rectangular lines): the rectangle from end to end, half a pixel each side
//    (tx = snap(−dy·s), ty = snap(dx·s), s = 0.5/sqrt(dx² + dy²)), no end rule. Its bounding box
//    (ceil of the low corner) holding no pixel centre drops it; otherwise every sample of every
//    pixel of the 64×64 tiles that the box meets is tested (llvmpipe bins the segment by tile and
//    rasterizes whole tiles), so samples just outside the box are drawn within those tiles.
// 7. Segment depth: a plane from the ends before any swap, area = dx² + dy²: one sample, along the
//    major axis only, dzdx = (dz·(dx·(1 + (dy/dx)²)))·(1/area) and dzdy = 0 (x-major; y-major the
//    other way round); 4 samples, dzdx = (dz·dx)·(1/area), dzdy = (dz·dy)·(1/area); then
//    z0 = z1 − (dzdx·(x1 − 0.5) + dzdy·(y1 − 0.5)) (0.5 even with 4 samples), evaluated as
//    fma(dzdy, y, fma(dzdx, x, z0)) at the pixel (px, py) or the sample (px + sx, py + sy); stored
//    as triangles' depth is (Rasterizer.h, 5.).
// Flat values come from a segment's second vertex, a point's own: frugal's ids are the same at
// both ends, so which one does not matter.
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

#include "raster/Rasterizer.h"

namespace frugal::raster {

// A point or a segment set up for rasterization: its planes, the pixels to test, its depth plane.
struct ShapeSetup {
    struct Plane {
        std::int64_t c, dcdx, dcdy;  // fixed point, 3. above
    };
    Plane planes[4];
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // inclusive pixels to test, inside the target
    float z0 = 0.0f, dzdx = 0.0f, dzdy = 0.0f;
    bool xMajor = true;  // a segment's major axis (shading's planes follow it)
};

// The sample at pixel (px, py), sample `sample` (0 when single-sampled), is covered by `shape`.
inline bool shapeCovers(const ShapeSetup& shape, int px, int py, int sample, int samples) {
    std::int64_t X = std::int64_t(px) * 256, Y = std::int64_t(py) * 256;
    if (samples > 1) {
        X += kSampleFixed[sample][0];
        Y += kSampleFixed[sample][1];
    }
    for (const ShapeSetup::Plane& p : shape.planes)
        if (p.c - p.dcdx * X + p.dcdy * Y <= 0) return false;
    return true;
}

// The depth of `shape` at a pixel's sample (7.; a point's z0 alone), with the CPU's fusing.
inline float shapeDepth(const ShapeSetup& shape, float x, float y, bool fused) {
    if (fused) return std::fma(shape.dzdy, y, std::fma(shape.dzdx, x, shape.z0));
    return shape.dzdy * y + (shape.dzdx * x + shape.z0);
}

// A point at window position `v` (size 1) in a target of `viewport`; false: nothing to draw.
bool setupPoint(const SetupVertex& v, const Viewport& viewport, ShapeSetup* out);
// A segment between window positions a and b (after clipping); false: nothing to draw.
bool setupSegment(const SetupVertex& a, const SetupVertex& b, const Viewport& viewport, ShapeSetup* out);

// Clips the segment (clip0, clip1) (2.): false when it is dropped; else t0 and t1, how far each end
// moves toward the other (0: kept as it is).
bool clipSegment(const glm::vec4& clip0, const glm::vec4& clip1, unsigned mask0, unsigned mask1, bool halfZ, float* t0,
                 float* t1);

}  // namespace frugal::raster
