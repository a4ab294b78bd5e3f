// The software backend's draw queue: from a draw call to pixels. draw() runs the vertex stage on the
// vertices the draw uses (each once), clips, sets up and bins the triangles (Rasterizer.h), in
// parallel chunks for large draws; flush() rasterizes and shades everything pending, one 64×64 tile
// per thread at a time (Kernels.h). The order of submission is kept: chunks become segments in
// order, and every tile walks the segments in order. An interp other than Exact rasterizes
// depth-tested triangles through the slow path of software/InterpRaster.h instead of the kernels.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "base/ThreadPool.h"
#include "pipeline/Backend.h"
#include "raster/PointsLines.h"
#include "raster/Rasterizer.h"
#include "software/InterpRaster.h"
#include "software/Kernels.h"
#include "software/Shading.h"
#include "span/Interp.h"

namespace frugal::sw {

// A mesh as uploaded (validated by the backend, as the GL backend validates it).
struct SoftwareMesh {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec4> colors;
    std::vector<glm::vec2> uvs;
    std::vector<glm::vec4> tangents;
    std::vector<std::uint32_t> indices, triangleSource;  // triangleSource filled in (t when the mesh had none)
    std::uint32_t triangles = 0;                         // primitives (Mesh::topology)
    std::uint32_t corners = 3;                           // vertices a primitive: 3, 2 (segments) or 1 (points)
    std::vector<std::uint64_t> stamp;  // per vertex: the draw that last transformed it (partial draws)
};

// A point or a segment as the tiles rasterize it (Triangle::shape): shading reads `corner` as a
// triangle's vertices, planes that give the shape's varyings (a segment's along its major axis and
// constant across, a point's constant), and the tiles rasterize `setup` (raster/PointsLines.h).
struct ShapeRecord {
    SetupVertex corner[3];  // first: Triangle::v points here
    ShapeSetup setup;
};
inline const ShapeRecord& shapeOf(const Triangle& t) { return *reinterpret_cast<const ShapeRecord*>(t.v[0]); }

struct DrawInput {
    glm::mat4 mvp{1.0f};           // (projection · view) · model, as GlBackend::draw computes it
    glm::mat3 normalMatrix{1.0f};  // inverseTranspose(mat3(model))
    glm::mat4 model{1.0f};
    glm::mat3 uvTransform{1.0f};
    DrawShading shading;
    std::uint32_t firstId = 1;
    bool doubleSided = false;
    DepthFormat depthFormat = DepthFormat::D24;  // the target's
    int samples = 1;                             // the target's (Rasterizer.h, 6.)
};

class Pipeline {
public:
    Pipeline(int threads, bool simd, span::Interp interp = span::Interp::Exact);

    int threads() const { return pool_.size(); }
    const char* kernelName() const { return kernels_.name; }
    bool fusedViewport() const { return fused_; }
    span::Interp interp() const { return interp_; }
    // The slow path's counters, summed over every flush so far (zero in Exact mode).
    const InterpCounters& interpStats() const { return interpStats_; }
    ThreadPool& pool() { return pool_; }

    // Queues `ranges` of `mesh` for a target of `width` × `height`. Every draw queued until the next
    // flush() must be for the same target.
    void draw(SoftwareMesh& mesh, int width, int height, const DrawInput& input, std::span<const IndexRange> ranges);
    bool pending() const { return segmentCount_ > 0; }
    // Rasterizes what is queued into `target` (nothing pending: nothing to do) and empties the queue.
    void flush(const TargetView& target);
    // Forgets what is queued (its target is going away).
    void discard();

private:
    struct Run {
        std::uint32_t first, end;  // triangles [first, end)
        std::uint32_t batch = 0;   // index of the run's first draw-module batch in the batch flags
    };
    struct DrawRecord {  // one draw's vertices and shading, alive until the flush
        std::vector<SetupVertex> vertices;
        std::vector<glm::vec4> clip;
        std::vector<std::uint8_t> mask;
        std::vector<ShapeRecord> shapes;  // a draw of points or segments: one a primitive set up
        DrawShading shading;
    };
    struct SetupJob {  // what every setup chunk of one draw shares
        const SoftwareMesh* mesh;
        const DrawRecord* record;
        Viewport viewport;
        std::uint32_t drawIndex, firstId, batchSize;
        bool cullBack;
        const std::vector<Run>* runs;
        const std::vector<std::uint8_t>* clippedBatch;
    };

    // Shades the triangles that won pixels of the tile and forgets them (its winners: kNoWinner).
    void shadePending(TileState& tile) const;
    static void forgetWinners(TileState& tile, int x0, int y0, int x1, int y1);
    // A triangle of a masked or blended draw: what is pending shaded first, then it alone rasterized
    // (by `rasterize`) and shaded; where the mask discarded its fragment, depth and id put back.
    template <class Rasterize>
    void rasterizeAlone(const Triangle& t, const DrawShading& shading, TileState& tile,
                        const Rasterize& rasterize) const;
    void transformVertices(SoftwareMesh& mesh, const VertexJob& job, const std::vector<Run>& runs,
                           std::uint64_t triangles);
    void setup(const SetupJob& job, std::uint64_t skip, std::uint64_t count, Segment& segment);
    // Clips, sets up and bins a draw's points or segments (on this thread: they are few).
    void setupShapes(const SetupJob& job, DrawRecord& record, std::uint64_t primitives, Segment& segment);
    // Coverage and depth test of a point or segment within the tile (the kernels' raster() for
    // shapes); records winners.
    void rasterShape(const Triangle& t, TileState& tile) const;
    Segment& newSegment();
    DrawRecord& newDraw();

    const Kernels& kernels_;
    const bool fused_;
    const span::Interp interp_;
    ThreadPool pool_;
    std::vector<std::unique_ptr<TileState>> tiles_;  // one per thread
    std::vector<InterpScratch> interpScratch_;       // one per thread; used when interp_ != Exact
    InterpCounters interpStats_;
    std::uint64_t drawSerial_ = 0;

    // Queued work; records and segments are reused from flush to flush.
    std::vector<std::unique_ptr<DrawRecord>> draws_;
    std::size_t drawCount_ = 0;
    std::vector<std::unique_ptr<Segment>> segments_;
    std::size_t segmentCount_ = 0;
    int width_ = 0, height_ = 0;  // of the target the queue is for
};

}  // namespace frugal::sw
