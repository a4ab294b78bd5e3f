// Culling methods: for one view, which index ranges of which instances may be visible (a DrawList,
// pipeline/Plan.h). Plans only: nothing here calls GL or a backend, so both backends execute the same
// plan and tests run on the CPU.
//
// Methods (`--cull`):
//   none          every triangle (today's render).
//   sphere        whole instances whose bounding sphere meets the frustum.
//   backface      every triangle tested on the CPU: frustum, and facing for single-sided materials.
//   cones         meshoptimizer meshlets (clusters) with their bounds and normal cones, kept whole.
//   paper         paper 002 as written: sphere outside → nothing; partly inside → the bins whose patch
//                 of the bounding sphere lies inside the frustum on the camera's side; wholly inside →
//                 the bins between the convex hull's left and right maximum-side-factor vertices by
//                 azimuth about the camera's up axis. It misses triangles by design (reported).
//   conservative  never drops a triangle that can own a pixel: clusters are culled whole when their
//                 box is outside the frustum or their cone faces away, kept whole when inside and
//                 facing, and tested triangle by triangle otherwise (the same exact tests as backface).
//   occlusion     conservative's clusters less those hidden behind others that are drawn anyway,
//                 tested against a depth buffer of occluders rasterized on the CPU (cull/Occlusion.h);
//                 exact like conservative. It needs the target (cull's `target`); without one it
//                 is conservative.
//   occlusion-ahead  occlusion's plan; on a sequence the renderer makes it on a thread of its own
//                 while the frame before draws (cull/CullAhead.h). cull() makes it as occlusion does.
//   oracle        exactly the frame's really visible set; it needs the frame's id image, so it is not
//                 a plan made here (renderer/Oracle.h: makeOracle). cull() gives the full list.
// Facing follows GL: a triangle of a single-sided material is drawn when counter-clockwise in window
// space; a mirroring transform (negative determinant) swaps the sides. Every "drop" decision has a
// margin of float rounding on its side, so an undecided triangle (edge-on, zero area, not a number) is
// kept. None of the methods uses history: each view is culled from scratch. (occlusion's policy of
// skipping itself after passes that did not pay looks back at earlier calls; that changes its plan,
// never the image.)
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include <frugal/Scene.h>
#include <frugal/Settings.h>

#include "cull/Occlusion.h"
#include "cull/SphereMap.h"
#include "pipeline/Camera.h"
#include "pipeline/Plan.h"

namespace frugal {

// How the paper method classified an instance's bounding sphere against the frustum.
enum class SphereClass { Outside, Partial, Whole };

class SceneCuller {
public:
    // Builds each mesh's map and puts its triangles in the map's order (reorderTriangles): call it
    // before the scene is uploaded. Meshes shared by several instances are prepared once.
    static SceneCuller prepare(Scene& scene, const MapParams& params = {});

    // The plan of `method` for one frame: node transforms `world`, camera `view` (pipeline/Camera.h).
    // Instances in scene order; instances with nothing to draw are left out.
    // `target`: the size and rules of the target drawn into (occlusion only).
    DrawList cull(Cull method, const Scene& scene, const std::vector<glm::mat4>& world, const View& view,
                  const OcclusionTarget& target = {}) const;

    // What the last occlusion cull did (cull(Cull::Occlusion, ...)), and its buffer as an image.
    const OcclusionCuller& occlusion() const { return occlusion_; }

    // How the paper method sees instance `instance` in this frame.
    SphereClass classify(const Scene& scene, int instance, const std::vector<glm::mat4>& world,
                         const View& view) const;

    const std::vector<MeshMap>& maps() const { return maps_; }
    PrepStats totals() const;  // summed over meshes

private:
    DrawList cullOcclusion(const Scene& scene, const std::vector<glm::mat4>& world, const View& view,
                           const OcclusionTarget& target) const;

    std::vector<MeshMap> maps_;
    // Per mesh, the union of its clusters' boxes: an instance inside the frustum (or outside) with
    // it needs no test of its clusters' boxes.
    std::vector<std::pair<glm::vec3, glm::vec3>> meshBoxes_;
    // Per bin: sample directions of the bin's cell (unit vectors, kBinSamples each); the same for
    // every mesh, since they depend on the bin counts only.
    std::vector<glm::vec3> binSamples_;
    // The occlusion pass's buffers, kept from view to view (cull is const: one culler serves one
    // renderer, which calls it from one thread at a time).
    mutable OcclusionCuller occlusion_;
    // The conservative plan that occlusion starts from, made in pieces side by side (cullOcclusion);
    // each on cache lines of its own.
    struct alignas(64) ConservativePiece {
        std::vector<KeptCluster> kept;
        std::vector<IndexRange> ranges;
    };
    mutable std::vector<ConservativePiece> pieces_;
    mutable std::vector<std::size_t> clusterStart_;  // per instance: its first cluster, counting over all
};

// Triangles a list submits, counted as the backends execute ranges (pipeline/IndexRanges.h).
std::size_t submittedTriangles(const Scene& scene, const DrawList& list);

}  // namespace frugal
