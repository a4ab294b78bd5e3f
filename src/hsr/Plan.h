// Hidden-surface modes (paper 003): a frame's draw list reordered and given per-draw depth modes.
//
//   zbuffer:   the list as it is, every draw depth-tested (the exact render, the default);
//   depthsort: the painter's method: polygons back to front by average depth, no depth test;
//   adaptive:  the paper's adaptive z-buffer (Fig. 7): the same order, and every polygon whose x, y
//              and z extents overlap another's is flagged; unflagged polygons are drawn without
//              reading or writing depth, flagged ones with the z-buffer.
//   adaptive-convex: adaptive, except that two front faces of one instance of a convex solid are
//              never flagged against each other (ours, not the paper's; see below).
//
// Polygons are hsr/Polygons.h's (a cube face is one), their extents the union of their triangles'
// (hsr/Order.h), their depth the mean of their triangles' average depths (a mean of the polygon's
// vertex depths, which is all the argument below needs). Polygons are ordered as hsr/Order.h's
// backToFront orders them, flagged by hsr/Flags.h's grid. Nothing here knows a backend: the plan
// is a DrawList whose commands carry a DepthMode.
//
// When adaptive equals the z-buffer, and when it cannot. Take a pixel p and, among the fragments
// drawn there, the one the z-buffer keeps: the nearest, from polygon A.
// - A unflagged: every other polygon covering p has a box that meets A's, so (A not flagged) a z
//   range disjoint from A's; its fragment at p lies behind A's, so its whole range does, and so does
//   its average depth: it is drawn before A. A is drawn last at p and keeps it.
// - A flagged: the unflagged polygons covering p are drawn before A (as above). The depth buffer
//   at p holds the nearest flagged fragment drawn so far (unflagged draws write no depth), which
//   is not nearer than A's; A passes if it is farther, and no later flagged fragment passes A.
// So adaptive equals the z-buffer in colour and ids wherever the nearest fragment at a pixel is
// strictly nearer than every other one. Where two flagged fragments tie in 24-bit depth (coplanar
// overlapping polygons, or two polygons that meet along a line, on the line) the z-buffer keeps the
// one submitted first, adaptive the one drawn first. The argument above only needs the order
// between flagged and unflagged polygons, so each run of consecutive flagged polygons in the
// sorted order is drawn in submission order: ties then resolve as in the z-buffer, except between
// flagged polygons in different runs (an unflagged polygon sorted between them), the one case in
// which adaptive can differ from the z-buffer. (A frame whose polygons are all flagged is drawn in
// submission order: the z-buffer render itself.) The cases:
// - interpenetrating polygons: their boxes and z ranges overlap, both are flagged, the z-buffer
//   resolves them (exact but for ties on the line where they meet);
// - polygons crossing the eye plane (near-plane clipping, hsr/Order.h) get the whole screen and
//   z [0, 1]: they are flagged with every polygon they meet; exact, never faster;
// - ties in average depth between polygons that overlap are drawn in submission order (stable);
//   unflagged ones never tie in depth at a pixel (disjoint ranges, kZMargin apart).
// Why kZMargin: two polygons whose vertex z ranges are apart by less than a 24-bit step could still
// tie or swap after the rasterizer's plane evaluation and rounding; the margin makes them overlap
// in z, so they are flagged and z-buffered.
// adaptive-convex. The paper flags the faces of one cube against each other (two faces that share an
// edge share its pixels and its depths), so on its own scene every face of a cube showing two or
// three faces is flagged. Yet two front faces of a convex solid never cover one pixel: a ray from
// the eye enters the solid once, through a face turned towards the eye. So a pair of clearly
// front-facing polygons (hsr/Order.h) of one single-sided instance of a mesh that bounds a convex
// solid (hsr/Polygons.h) needs no order between them, and the argument above holds with such pairs
// left out of the flag test: in it, "every other polygon covering p" never includes one of them.
// Nearly edge-on faces of the solid are not exempt (not clearly front-facing). What this assumes of
// the rasterizers: the shared edges of the solid's front faces stay shared after snapping to the
// sub-pixel grid (they do: both faces snap the same vertices), so the fill rule gives each pixel
// to one face.
// The depth image of depthsort and adaptive is not the z-buffer's: it holds the flagged polygons'
// depths only (far elsewhere); colour and ids are the result.
//
// Blended surfaces (AlphaMode::Blend) are drawn after every other one, with the z-buffer, in the
// order the z-buffer render gives them (SceneRenderer::draw); the modes order the rest. So that each
// blended fragment is tested against the nearest opaque depth, every polygon whose pixel box meets
// a blended polygon's is flagged (the blended polygon's z range counts as everything), in every
// mode, depthsort too; then at a pixel a blended polygon covers, every opaque polygon is z-buffered
// and the argument above gives the z-buffer's colour and depth there before the blend. Masked
// surfaces (AlphaMode::Mask) need nothing: a discarded fragment writes nothing in either method.
//
// depthsort is exact only where no two overlapping polygons need each other's depth; its errors
// (cyclic overlaps, interpenetration, a large polygon behind a small one with a nearer average)
// are what `frugal-lab hsr-bench` counts.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <frugal/Scene.h>
#include <frugal/Stats.h>

#include "hsr/Polygons.h"
#include "pipeline/Backend.h"
#include "pipeline/Plan.h"

namespace frugal::hsr {

using Mode = frugal::Hsr;  // frugal/Settings.h: its names are toString's

using PlanStats = HsrStats;  // frugal/Stats.h

class Planner {
public:
    // Groups every mesh's triangles into polygons (once; the scene must outlive the planner).
    explicit Planner(const Scene& scene);

    // The frame's list in `mode` (zbuffer: `list` itself). `world`: Scene::worldTransforms.
    DrawList plan(Mode mode, const FrameParams& frame, const std::vector<glm::mat4>& world, const DrawList& list,
                  int width, int height, PlanStats* stats = nullptr) const;

    const MeshPolygons& polygons(int mesh) const { return polygons_[std::size_t(mesh)]; }
    std::size_t polygonCount() const;  // over all instances
    std::size_t bytes() const;         // what the planner keeps: each triangle's polygon, each instance's first

private:
    const Scene* scene_;
    std::vector<MeshPolygons> polygons_;           // per mesh
    std::vector<std::uint32_t> firstPolygon_;      // per instance: its polygons' first global number
};

}  // namespace frugal::hsr
