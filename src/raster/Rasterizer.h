// llvmpipe's rasterization rules, as one module (raster) that the software backend (src/software/)
// and the occlusion pass (src/cull/Occlusion.cpp) both build on: vertex stage arithmetic, clipping,
// triangle setup, the fill rule and the depth plane. The software backend adds binning into tiles
// and the per-tile coverage + depth pass; shading is separate (src/software/Shading.h), and the two
// meet in a per-tile "winner" map: which triangle last passed the depth test at each pixel.
//
// What is reproduced, and from where (Mesa 22.3.6, llvmpipe on x86-64). This header is the
// project's statement of the rasterization rules it matches; every rule below is checked against
// the GL backend by tests/software/CoverageGLTest.cpp, which compares coverage and 24-bit depth
// pixel for pixel.
//
// How they were found. A first experiment drew single triangles into FBOs (256×256 and 61×47)
// through EGL surfaceless and compared the read-back with a CPU model: with rules 1–3 below the model
// reproduced llvmpipe's coverage exactly on 320,000 triangles (random vertices, vertices snapped to
// the sub-pixel grid or lying on pixel centres and edges, slivers, triangles far larger than the
// viewport, both windings, perspective triangles crossing the near plane). Its depth was then within
// 7 LSB (98.9 % of pixels exact at 256×256); the evaluation order of the vertex transform (1.), the
// clipper's starting vertex (2.) and the float rounding of the depth product (5.) made it exact.
// Mesa's sources read: lp_setup_tri.c, lp_rast.h, lp_state_setup.c, draw_pipe_clip.c,
// draw_cliptest_tmp.h, draw_pipe_cull.c, draw_pt_vsplit.c. Not covered, because frugal never uses
// them: window-system framebuffers (flipped, bottom_edge_rule = 1), scissored draws, polygon
// offset, depth clamp, a viewport origin other than (0, 0). Multisampling is 6. below.
//
// Two depth formats (frugal/Image.h). D24 is what the rules below describe. D32F is drawn with
// glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE) and GL_GREATER into a 32-bit float buffer (reversed
// Z), and differs in exactly four places, each marked "D32F" below: the clip mask's bit 4 is z < 0,
// the near clip plane is (0, 0, 1, 0), the viewport's depth scale and offset are 1 and 0 instead of
// 0.5 and 0.5, and the depth is stored as the clamped float itself, compared with ">". Everything
// else, the depth plane equation included, is the same arithmetic.
//
// Conventions. Window coordinates y-up, origin bottom-left; pixel (px, py) has its centre at
// (px + 0.5, py + 0.5) and is tested there only (multisampled targets: 6.). Depth is window z in [0, 1] stored
// as 24-bit unsigned integers, 0 near; the test is GL_LESS and writes on pass. Within a tile the
// triangles are rasterized in submission order, so a tie in depth keeps the first triangle drawn.
//
// 1. Vertex stage (draw module's LLVM vertex shader, draw_llvm.c). clip = M·(x, y, z, 1) evaluated per
//    row as ((m0·x + m1·y) + m2·z) + m3 with every product and sum rounded: NIR does not fuse these
//    for llvmpipe. Found by experiment: of eight orderings, fused and unfused, only this one gives
//    llvmpipe's depth bit for bit (coverage cannot tell them apart at 1/256 pixel). The normal matrix
//    (mat3) is applied the same way.
//    Clip mask (generate_clipmask): bit 0 x > w, 1 x + w < 0, 2 y > w, 3 y + w < 0, 4 z + w < 0
//    (D32F: z < 0, clip_halfz), 5 z > w, as LLVM unordered compares (a NaN sets the bit).
//    Viewport (generate_viewport): oow = 1 / w (a true division); xw = fma(x·oow, W/2, W/2),
//    yw = fma(y·oow, H/2, H/2), zw = fma(z·oow, 0.5, 0.5) (D32F: fma(z·oow, 1, 0), the zero-to-one
//    viewport of depth range [0, 1]). lp_build_fmuladd emits llvm.fmuladd, which
//    LLVM fuses when the host CPU has FMA (and it compiles for the host): fused or not is decided
//    from the CPU at run time, like llvmpipe.
// 2. Clipping (draw_pipe_clip.c, do_clip_tri). A triangle whose three masks OR to 0 is drawn as is;
//    AND ≠ 0 drops it; otherwise it is clipped against the planes whose bit is set, in bit order,
//    against (−1,0,0,1), (1,0,0,1), (0,−1,0,1), (0,1,0,1), (0,0,1,1) (D32F: (0,0,1,0)), (0,0,−1,1):
//    no guard band,
//    x and y are clipped too. dp = ((x·a + y·b) + z·c) + w·d; a non-finite dp drops the triangle;
//    dp ≥ 0 is inside. The walk starts at vertex 0 and emits [prev if inside][intersection if the
//    sign changes] for each edge prev → cur, so the output list starts with vertex 0 when it is
//    inside (the order matters: the fan below decides which vertex anchors each plane equation).
//    The new vertex is interpolated from the end closer to the plane: going out (dp < 0) with
//    −dp < dp_prev uses t = dp/(dp − dp_prev) from the current vertex, else t = −dp_prev/(dp −
//    dp_prev) from the previous one, and symmetrically coming in; every component is
//    out + t·(in − out). New vertices get window coordinates from the C code of interp(), unfused:
//    (x · (1/w)) · scale + translate. The polygon is fanned as (v[i−1], v[i], v[0]) (emit_poly,
//    provoking vertex last).
// 2a. Face culling twice (single-sided draws only). The draw module cuts every range of a draw into
//    batches (array draws every 4095 vertices, indexed draws every 1023 indices; draw_pt_vsplit.c,
//    draw_split_tmp.h) and runs its pipeline (clip → cull → setup) only for a batch in which some
//    vertex has a clip mask. There, draw_pipe_cull.c computes det = (x0−x2)(y1−y2) − (y0−y2)(x1−x2)
//    in float from the window coordinates of each (post-clip) triangle and drops it unless det > 0
//    (counter-clockwise in GL's y-up window; a zero det is dropped). Setup then culls again by the
//    fixed-point area (3.). The two disagree only for slivers, where this decides whether a pixel is
//    drawn. Found from a mismatch in tests/software/CoverageGLTest.cpp and checked on batches on
//    either side of the boundaries.
// 3. Setup (lp_setup_tri.c). Fixed point with 8 sub-pixel bits: X = round_even((xw − 0.5)·256) in
//    float. Area = (X0−X1)(Y2−Y0) − (X2−X0)(Y0−Y1) in 64 bits: 0 drops the triangle; area < 0 is a
//    front face (counter-clockwise in GL's y-up window) and swaps v0 and v1; a back face of a
//    single-sided draw is culled. Edges i → i+1: dcdx = Y_i − Y_{i+1}, dcdy = X_i − X_{i+1},
//    c = dcdx·X_i − dcdy·Y_i, plus 1 when dcdx < 0 or (dcdx = 0 and dcdy > 0) (bottom_edge_rule 0,
//    FBOs are not flipped). Pixel (px, py) is covered when c − 256·dcdx·px + 256·dcdy·py ≥ 1 on all
//    three edges, i.e. k − dcdx·px + dcdy·py ≥ 0 with k = ⌊(c − 1)/256⌋, which is what is stored.
// 4. Plane equations (lp_state_setup.c, init_args + calc_coef4; float, every operation rounded):
//    x0c = x0 − 0.5, y0c = y0 − 0.5; dx01 = x0 − x1, dy01 = y0 − y1, dx20 = x2 − x0, dy20 = y2 − y0;
//    ooa = 1/(dx01·dy20 − dy01·dx20); dadx = (a0 − a1)(dy20·ooa) − (a2 − a0)(dy01·ooa);
//    dady = (a2 − a0)(dx01·ooa) − (a0 − a1)(dx20·ooa); a(0,0) = a0 − (dadx·x0c + dady·y0c).
//    v0, v1, v2 are the setup order (after the swap above).
// 5. Depth (lp_bld_interp.c attribs_update_simple; lp_bld_depth.c; lp_bld_conv.c
//    lp_build_clamped_float_to_unsigned_norm with 24 = mantissa + 1 bits): at pixel (px, py),
//    z = fma(dzdy, py, fma(dzdx, px, a)) with px, py the integer pixel coordinates (the −0.5 above
//    puts the sample at the centre), clamped to [0, 1], stored as round_even(z · 16777215.0f) with
//    the product rounded to float first (D32F: the clamped float is stored, and the test is
//    z > stored). With all of the above the depth buffer is identical. Two
//    details decide the last bits (measured against llvmpipe): rounding the product in double
//    instead of float costs up to 1 LSB; starting the clipper's output list anywhere but at
//    vertex 0 (2.) makes another vertex anchor the plane of each fan triangle, and clipped
//    slivers then differ by hundreds of LSB.
//
// 6. Multisampling (llvmpipe supports 4 samples; lp_rast.c lp_sample_pos_4x, lp_scene.c,
//    lp_rast_tri_tmp.h under MULTISAMPLE, lp_setup_tri.c, lp_state_setup.c, lp_bld_interp.c). Sample s
//    sits at (px, py) + kSamplePositions[s]: (0.375, 0.125), (0.875, 0.375), (0.125, 0.625), (0.625,
//    0.875), in fixed point (96, 32), (224, 96), (32, 160), (160, 224). Three things change:
//    - setup's pixel offset is 0, not 0.5: X = round_even(x·256) (3.), and the planes' x0c = x0,
//      y0c = y0 (4.);
//    - coverage per sample: the edge constant becomes c + sy·dcdy − sx·dcdx (sx, sy the sample's
//      fixed position), so sample s of (px, py) is covered when ⌊(c − 1 + sy·dcdy − sx·dcdx)/256⌋
//      − dcdx·px + dcdy·py ≥ 0. A multisampled triangle's Edge::k holds c − 1 itself, and the
//      kernel derives each sample's constant;
//    - depth per sample, at the sample's position: z = fma(dzdy, py + sy, fma(dzdx, px + sx, a))
//      (px + sx, py + sy exact in float), tested and stored per sample. The fragment shader runs
//      once per pixel: its varyings at the pixel's centre, a = fma(dady, py + 0.5, fma(dadx, px +
//      0.5, a0)), and its colour goes to every sample the triangle covers and passes there.
//    The resolve (glBlitFramebuffer to one sample, u_blitter's shaders): colour is the samples'
//    mean, summed in float from sample 0 and scaled by 1/4; depth and ids (an integer format) are
//    sample 0's.
//
// Where this departs: a triangle whose window coordinates are not finite or whose fixed-point
// coordinates leave ±2^26 (262144 pixels; clipping keeps every vertex of ordinary input within the
// viewport, so only absurd inputs such as clip coordinates near 1e20 get there) is dropped.
// llvmpipe converts such values to INT32_MIN and rasterizes whatever the wrapped 32-bit arithmetic
// gives. CoverageGLTest.DegenerateInputMatchesLlvmpipe checks NaN, Inf, w = 0 and 1e20..3e38
// coordinates: identical images, no crash, no hang.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include <frugal/Image.h>

namespace frugal::raster {

inline constexpr int kTileLog2 = 6;
inline constexpr int kTileSize = 1 << kTileLog2;  // 64 × 64 pixels, llvmpipe's tile size
// The varyings, mesh.vert's outputs: normal xyz, colour rgba, uv, world position xyz, tangent xyz,
// bitangent xyz.
inline constexpr int kAttributes = 18;

// A vertex as triangle setup and shading read it: window position, 1/w_clip, and the varyings.
struct SetupVertex {
    float x, y, z, oow;
    float a[kAttributes];
};

// Edge in pixel units: a pixel is inside when k − dx·px + dy·py ≥ 0 (see 3. above). Multisampled
// (6. above): k is c − 1 in 1/256 pixel, from which each sample's constant is made.
struct Edge {
    std::int64_t k;
    std::int32_t dx, dy;
};

struct Triangle {
    Edge e[3];
    float z0, dzdx, dzdy;         // depth plane at pixel (0, 0), per pixel
    std::int32_t x0, y0, x1, y1;  // inclusive pixel bounds, inside the target
    const SetupVertex* v[3];      // setup order
    std::uint32_t draw;           // index of the draw in the frame's list
    std::uint32_t id;             // triangle id written to the id buffer
    std::uint32_t front;          // 1: front face (gl_FrontFacing)
    bool writesId;                // the draw writes ids (FrameParams::writeIds when it was made)
    bool depthTest;               // DepthMode::Test; false: every covered pixel passes, no depth written
    // 0: a triangle. kPointShape or kSegmentShape: a point or a segment (raster/PointsLines.h), whose
    // record (sw::ShapeRecord) begins with the three vertices v points to; e, z0, dzdx, dzdy unused.
    std::uint8_t shape = 0;
};
inline constexpr std::uint8_t kPointShape = 1, kSegmentShape = 2;

// Multisampling (6. above): llvmpipe's standard positions of 4 samples, in pixels and in setup's
// fixed point.
inline constexpr int kMaxSamples = 4;
inline constexpr float kSamplePositions[kMaxSamples][2] = {
    {0.375f, 0.125f}, {0.875f, 0.375f}, {0.125f, 0.625f}, {0.625f, 0.875f}};
inline constexpr int kSampleFixed[kMaxSamples][2] = {{96, 32}, {224, 96}, {32, 160}, {160, 224}};

struct Viewport {
    int width = 0, height = 0;
    int samples = 1;                       // 1, or kMaxSamples (6. above)
    float sx = 0, tx = 0, sy = 0, ty = 0;  // W/2, W/2, H/2, H/2
    float sz = 0.5f, tz = 0.5f;            // depth scale and offset: 0.5, 0.5 (D32F: 1, 0)
    bool halfZ = false;                    // D32F's zero-to-one clip space (near plane z ≥ 0)
};

Viewport makeViewport(int width, int height, DepthFormat format = DepthFormat::D24, int samples = 1);

// Setup's pixel offset: 0.5 (the pixel's centre is its sample), 0 when multisampled (6. above).
inline float pixelOffset(const Viewport& viewport) { return viewport.samples > 1 ? 0.0f : 0.5f; }

// Whether this CPU has FMA, and so whether llvmpipe's JIT fuses the viewport's multiply-adds (1.).
bool cpuHasFma();

// Window coordinates of a clip-space vertex made by the clipper: unfused, as the C code of
// draw_pipe_clip.c interp() computes them.
SetupVertex clippedWindowVertex(const glm::vec4& clip, const Viewport& viewport);

// Clip-mask bits of a clip-space position (1. above); `halfZ`: the zero-to-one clip space.
unsigned clipMask(const glm::vec4& clip, bool halfZ);

// The draw module's cull stage for a triangle in a batch that runs the pipeline (2a. above): true
// when it passes the triangle on (front-facing by the float determinant, or NaN).
inline bool drawModuleKeepsFront(const SetupVertex* v0, const SetupVertex* v1, const SetupVertex* v2) {
    const float ex = v0->x - v2->x, ey = v0->y - v2->y;
    const float fx = v1->x - v2->x, fy = v1->y - v2->y;
    const float det = ex * fy - ey * fx;
    return det > 0.0f || std::isnan(det);
}

// Setup of one triangle in the order given (v0, v1, v2 as the pipeline delivers them). Returns
// false when the triangle is dropped (degenerate, culled, outside the target, or not representable).
bool setupTriangle(const SetupVertex* v0, const SetupVertex* v1, const SetupVertex* v2, bool cullBack,
                   const Viewport& viewport, Triangle* out);

// setupTriangle in its three steps, for callers that keep fixed-point positions or need the depth
// plane only of some triangles (cull/Occlusion.cpp):
// - fixedPosition: a window position in setup's fixed point, round_even((x − offset)·256), offset
//   pixelOffset(); false when it is not representable (|…| ≥ 2^26, or NaN);
// - setupEdges: from the fixed-point positions in the order given, the edges, bounds and facing
//   (3. above). Dropped, or the order the edges were set up in: Swapped for a front face (v0 and
//   v1 exchanged, in X and Y too);
// - setupDepthPlane: the depth plane (4. above) of the vertices in that order, x0c = x0 − offset.
// (fixedPosition and setupEdges are inline, below: integer arithmetic and one rounding each.)
enum class SetupOrder { Dropped, Given, Swapped };
inline bool fixedPosition(float x, float y, std::int64_t* X, std::int64_t* Y, float offset = 0.5f);
inline SetupOrder setupEdges(std::int64_t X[3], std::int64_t Y[3], bool cullBack, const Viewport& viewport,
                             Triangle* out);
void setupDepthPlane(const SetupVertex* v0, const SetupVertex* v1, const SetupVertex* v2, Triangle* out,
                     float offset = 0.5f);

// Stable storage for vertices made by the clipper (pointers stay valid until clear()).
class VertexPool {
public:
    SetupVertex* add();
    void clear() { used_ = 0; }

private:
    static constexpr std::size_t kBlock = 1024;
    std::vector<std::vector<SetupVertex>> blocks_;
    std::size_t used_ = 0;  // vertices handed out
};

// Clips one triangle whose masks do not rule it in or out (2. above) and emits the fan's triangles
// through `emit(v0, v1, v2)`. `clip` are the clip-space positions of v0..v2, `in` their setup
// vertices (window position and varyings; the varyings are interpolated in clip space).
template <class Emit>
void clipTriangle(const glm::vec4* const clip[3], const SetupVertex* const in[3], unsigned mask,
                  const Viewport& viewport, VertexPool& pool, Emit&& emit);

// The triangles of one stretch of submission order, binned by tile. Triangles are appended in order;
// close() sorts the bin entries by tile (stably) so each tile reads its triangles in order.
struct Segment {
    std::vector<Triangle> triangles;
    std::vector<std::uint32_t> binTile;      // bin entry → tile index
    std::vector<std::uint32_t> binTriangle;  // bin entry → triangle index
    std::vector<std::uint32_t> tileStart;    // after close(): entries of tile t are [tileStart[t], tileStart[t+1])
    std::vector<std::uint32_t> sorted;       // after close(): triangle indices by tile
    VertexPool pool;                         // vertices made by the clipper
    bool closed = false;

    void reset() {
        triangles.clear();
        binTile.clear();
        binTriangle.clear();
        tileStart.clear();
        sorted.clear();
        pool.clear();
        closed = false;
    }
    // Bins triangle `index` into every tile its bounds touch (tilesX tiles per row).
    void bin(std::uint32_t index, int tilesX);
    void close(int tileCount);
};

// ---------------------------------------------------------------------------------------------
// Implementation of setup's fixed-point part (inline: the occlusion pass runs it per triangle).

namespace detail {
// Round to nearest even, like CVTPS2DQ in calc_fixed_position (|f| < 2^26 here). CVTSS2SI is
// baseline SSE on x86-64, where nearbyint would be a library call.
inline std::int64_t roundEven(float f) {
#if defined(__x86_64__)
    return _mm_cvtss_si32(_mm_set_ss(f));
#else
    return std::int64_t(std::nearbyint(f));
#endif
}

// Floor and ceiling of a / 256 for any sign (C++20 >> on negative values is arithmetic).
inline std::int64_t floorDiv256(std::int64_t a) { return a >> 8; }
inline std::int64_t ceilDiv256(std::int64_t a) { return -((-a) >> 8); }
}  // namespace detail

inline bool fixedPosition(float x, float y, std::int64_t* X, std::int64_t* Y, float offset) {
    constexpr float kLimit = 67108864.0f;  // 2^26: see "Where this departs" in Rasterizer.h
    // lp_setup_tri.c calc_fixed_position: (pos - pixel_offset) * FIXED_ONE, then CVTPS2DQ.
    const float fx = (x - offset) * 256.0f;
    const float fy = (y - offset) * 256.0f;
    if (!(std::fabs(fx) < kLimit) || !(std::fabs(fy) < kLimit)) return false;  // also NaN
    *X = detail::roundEven(fx);
    *Y = detail::roundEven(fy);
    return true;
}

inline SetupOrder setupEdges(std::int64_t X[3], std::int64_t Y[3], bool cullBack, const Viewport& viewport, Triangle* out) {
    const std::int64_t area = (X[0] - X[1]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[0] - Y[1]);
    if (area == 0) return SetupOrder::Dropped;
    const bool front = area < 0;
    if (cullBack && !front) return SetupOrder::Dropped;
    if (front) {
        // lp_setup_tri.c triangle_both/triangle_cw: do_triangle_ccw(v1, v0, v2).
        std::swap(X[0], X[1]);
        std::swap(Y[0], Y[1]);
    }

    // Pixels with a sample (the centre (256·px, 256·py); multisampled, (256·px, 256·py) plus 32 to
    // 224 on either axis) within the vertices' fixed-point bounds.
    const bool multi = viewport.samples > 1;
    const std::int64_t lo = multi ? 32 : 0, hi = multi ? 224 : 0;
    const std::int64_t minX = std::min({X[0], X[1], X[2]}), maxX = std::max({X[0], X[1], X[2]});
    const std::int64_t minY = std::min({Y[0], Y[1], Y[2]}), maxY = std::max({Y[0], Y[1], Y[2]});
    const std::int64_t x0 = std::max<std::int64_t>(detail::ceilDiv256(minX - hi), 0);
    const std::int64_t x1 = std::min<std::int64_t>(detail::floorDiv256(maxX - lo), viewport.width - 1);
    const std::int64_t y0 = std::max<std::int64_t>(detail::ceilDiv256(minY - hi), 0);
    const std::int64_t y1 = std::min<std::int64_t>(detail::floorDiv256(maxY - lo), viewport.height - 1);
    if (x0 > x1 || y0 > y1) return SetupOrder::Dropped;

    Triangle& t = *out;
    for (int i = 0; i < 3; ++i) {
        const int j = i == 2 ? 0 : i + 1;
        const std::int64_t dcdx = Y[i] - Y[j];
        const std::int64_t dcdy = X[i] - X[j];
        std::int64_t c = dcdx * X[i] - dcdy * Y[i];
        if (dcdx < 0 || (dcdx == 0 && dcdy > 0)) c += 1;
        // c − 256·dcdx·px + 256·dcdy·py ≥ 1  ⇔  dcdx·px − dcdy·py ≤ ⌊(c − 1)/256⌋.
        t.e[i].k = multi ? c - 1 : detail::floorDiv256(c - 1);
        t.e[i].dx = std::int32_t(dcdx);
        t.e[i].dy = std::int32_t(dcdy);
    }
    t.x0 = std::int32_t(x0);
    t.x1 = std::int32_t(x1);
    t.y0 = std::int32_t(y0);
    t.y1 = std::int32_t(y1);
    t.front = front ? 1u : 0u;
    return front ? SetupOrder::Swapped : SetupOrder::Given;
}

// ---------------------------------------------------------------------------------------------
// Implementation of the clipper (a template so the emit callback inlines).

namespace detail {
// dp = plane · v, summed left to right like draw_pipe_clip.c dot4.
inline float planeDistance(int plane, const glm::vec4& v, bool halfZ) {
    static constexpr float kPlanes[7][4] = {{-1, 0, 0, 1}, {1, 0, 0, 1},  {0, -1, 0, 1}, {0, 1, 0, 1},
                                            {0, 0, 1, 1},  {0, 0, -1, 1}, {0, 0, 1, 0}};
    const float* p = kPlanes[plane == 4 && halfZ ? 6 : plane];
    return ((v.x * p[0] + v.y * p[1]) + v.z * p[2]) + v.w * p[3];
}

struct ClipNode {
    glm::vec4 clip;
    const SetupVertex* vertex;
};

// out + t·(in − out) for the position and every varying; window coordinates from the result.
ClipNode interpolate(const ClipNode& out, float t, const ClipNode& in, const Viewport& viewport, VertexPool& pool);
}  // namespace detail

template <class Emit>
void clipTriangle(const glm::vec4* const clip[3], const SetupVertex* const in[3], unsigned mask,
                  const Viewport& viewport, VertexPool& pool, Emit&& emit) {
    // At most 3 + 6 vertices after six planes; one slot more for the wrap-around copy.
    constexpr int kMax = 16;
    detail::ClipNode bufferA[kMax], bufferB[kMax];
    detail::ClipNode* inList = bufferA;
    detail::ClipNode* outList = bufferB;
    int n = 3;
    for (int i = 0; i < 3; ++i) inList[i] = {*clip[i], in[i]};

    while (mask != 0 && n >= 3) {
        const int plane = __builtin_ctz(mask);
        mask &= mask - 1;
        if (n >= kMax - 1) return;
        inList[n] = inList[0];
        float dpPrev = detail::planeDistance(plane, inList[0].clip, viewport.halfZ);
        if (!std::isfinite(dpPrev)) return;
        int count = 0;
        for (int i = 1; i <= n; ++i) {
            const detail::ClipNode& prev = inList[i - 1];
            const detail::ClipNode& cur = inList[i];
            const float dp = detail::planeDistance(plane, cur.clip, viewport.halfZ);
            if (!std::isfinite(dp)) return;
            bool differentSign;
            if (dpPrev >= 0.0f) {
                outList[count++] = prev;
                differentSign = dp < 0.0f;
            } else {
                differentSign = !(dp < 0.0f);
            }
            if (differentSign) {
                if (count >= kMax - 1) return;
                const float denom = dp - dpPrev;
                if (dp < 0.0f) {  // going out
                    outList[count++] = -dp < dpPrev ? detail::interpolate(cur, dp / denom, prev, viewport, pool)
                                                    : detail::interpolate(prev, -dpPrev / denom, cur, viewport, pool);
                } else {  // coming back in
                    outList[count++] = -dpPrev < dp ? detail::interpolate(prev, -dpPrev / denom, cur, viewport, pool)
                                                    : detail::interpolate(cur, dp / denom, prev, viewport, pool);
                }
            }
            dpPrev = dp;
        }
        std::swap(inList, outList);
        n = count;
    }
    for (int i = 2; i < n; ++i) emit(inList[i - 1].vertex, inList[i].vertex, inList[0].vertex);
}

}  // namespace frugal::raster
