#include "software/Pipeline.h"

#include <algorithm>
#include <cassert>
#include <functional>
#include <iterator>
#include <new>

#include "pipeline/IndexRanges.h"

#if !defined(__clang__)  // Clang: -ffp-contract=off (CMakeLists.txt)
#pragma GCC optimize("fp-contract=off")
#endif

namespace frugal::sw {

namespace {

// The draw module cuts each (merged) range into batches and runs its pipeline stages, face culling
// among them, only for the batches in which a vertex needs clipping (Rasterizer.h, 2a). Batch sizes,
// in triangles: the id pass draws arrays, split every 4095 vertices (max_vertices 4096, trimmed to
// whole triangles, draw_split_tmp.h); the indexed pass is split every 1023 indices (vsplit
// SEGMENT_SIZE 1024). Both measured at the boundary (CoverageGLTest.DrawModuleCullsOnlyInClippedBatches).
constexpr std::uint32_t kArrayBatch = 4095 / 3;
constexpr std::uint32_t kIndexedBatch = 1023 / 3;

constexpr std::size_t kVertexChunk = 4096;   // vertices per vertex-stage task
constexpr std::uint64_t kSetupChunk = 2048;  // triangles per setup task, at least

}  // namespace

Pipeline::Pipeline(int threads, bool simd, span::Interp interp)
    : kernels_(selectKernels(simd)), fused_(cpuHasFma()), interp_(interp), pool_(threads) {
    tiles_.resize(std::size_t(pool_.size()));
    for (auto& tile : tiles_) tile = std::make_unique<TileState>();
    if (interp_ != span::Interp::Exact) interpScratch_.resize(std::size_t(pool_.size()));
}

Segment& Pipeline::newSegment() {
    if (segmentCount_ == segments_.size()) segments_.push_back(std::make_unique<Segment>());
    Segment& s = *segments_[segmentCount_++];
    s.reset();
    return s;
}

Pipeline::DrawRecord& Pipeline::newDraw() {
    if (drawCount_ == draws_.size()) draws_.push_back(std::make_unique<DrawRecord>());
    return *draws_[drawCount_++];
}

// The vertex stage for the vertices the draw's runs use, each once.
void Pipeline::transformVertices(SoftwareMesh& mesh, const VertexJob& job, const std::vector<Run>& runs,
                                 std::uint64_t triangles) {
    const std::size_t vertices = mesh.positions.size();
    if (triangles * mesh.corners >= vertices / 2) {
        // Most of the mesh: every vertex, in parallel chunks.
        const std::size_t chunks = (vertices + kVertexChunk - 1) / kVertexChunk;
        pool_.run(chunks, [&](std::size_t c, int) {
            kernels_.transform(job, c * kVertexChunk, std::min(vertices, (c + 1) * kVertexChunk));
        });
        return;
    }
    // A few ranges of a big mesh (a culled draw list): only the vertices they use.
    const std::uint64_t serial = ++drawSerial_;
    for (const Run& run : runs)
        for (std::uint32_t t = run.first; t < run.end; ++t)
            for (std::uint32_t k = 0; k < mesh.corners; ++k) {
                const std::uint32_t v = mesh.indices[std::size_t(t) * mesh.corners + k];
                if (mesh.stamp[v] == serial) continue;
                mesh.stamp[v] = serial;
                kernels_.transform(job, v, v + 1);
            }
}

// Clips, sets up and bins `count` triangles of the draw, starting `skip` triangles into its runs.
void Pipeline::setup(const SetupJob& job, std::uint64_t skip, std::uint64_t count, Segment& segment) {
    const int tilesX = (job.viewport.width + kTileSize - 1) / kTileSize;
    const SoftwareMesh& mesh = *job.mesh;
    const DrawRecord& record = *job.record;
    const std::vector<Run>& runs = *job.runs;
    const std::uint32_t* indices = mesh.indices.data();
    const SetupVertex* vertices = record.vertices.data();
    const auto emit = [&](const SetupVertex* a, const SetupVertex* b, const SetupVertex* c, std::uint32_t id,
                          bool drawModuleCull) {
        if (drawModuleCull && !drawModuleKeepsFront(a, b, c)) return;
        Triangle t;
        if (!setupTriangle(a, b, c, job.cullBack, job.viewport, &t)) return;
        t.draw = job.drawIndex;
        t.id = id;
        t.writesId = record.shading.writeIds;
        t.depthTest = record.shading.depthTest;
        segment.triangles.push_back(t);
        segment.bin(std::uint32_t(segment.triangles.size() - 1), tilesX);
    };
    for (std::size_t r = 0; r < runs.size() && count > 0; ++r) {
        const std::uint64_t length = runs[r].end - runs[r].first;
        if (skip >= length) {
            skip -= length;
            continue;
        }
        const auto first = std::uint32_t(runs[r].first + skip);
        const auto end = std::uint32_t(std::min<std::uint64_t>(runs[r].end, first + count));
        skip = 0;
        count -= end - first;
        for (std::uint32_t tri = first; tri < end; ++tri) {
            const std::uint32_t i0 = indices[3 * std::size_t(tri)], i1 = indices[3 * std::size_t(tri) + 1],
                                i2 = indices[3 * std::size_t(tri) + 2];
            const unsigned m0 = record.mask[i0], m1 = record.mask[i1], m2 = record.mask[i2];
            const std::uint32_t id = job.firstId + mesh.triangleSource[tri];  // 32-bit wrap, as in mesh.vert
            const bool drawModuleCull =
                job.cullBack && (*job.clippedBatch)[runs[r].batch + (tri - runs[r].first) / job.batchSize];
            if ((m0 | m1 | m2) == 0) {
                emit(&vertices[i0], &vertices[i1], &vertices[i2], id, drawModuleCull);
            } else if ((m0 & m1 & m2) == 0) {
                const glm::vec4* clip[3] = {&record.clip[i0], &record.clip[i1], &record.clip[i2]};
                const SetupVertex* in[3] = {&vertices[i0], &vertices[i1], &vertices[i2]};
                clipTriangle(clip, in, m0 | m1 | m2, job.viewport, segment.pool,
                             [&](const SetupVertex* a, const SetupVertex* b, const SetupVertex* c) {
                                 emit(a, b, c, id, drawModuleCull);
                             });
            }
        }
    }
}

void Pipeline::draw(SoftwareMesh& mesh, int width, int height, const DrawInput& input,
                    std::span<const IndexRange> ranges) {
    assert((!pending() || (width == width_ && height == height_)) && "Pipeline::draw: flush before changing targets");
    // The merged ranges (pipeline/IndexRanges.h), as the GL backend submits them: they are what the
    // draw module splits into batches.
    std::vector<IndexRange> merged;
    const std::uint64_t triangles = normalizeRanges(ranges, mesh.triangles, merged);
    std::vector<Run> runs;
    runs.reserve(merged.size());
    for (const IndexRange& range : merged) runs.push_back({range.firstTriangle, range.firstTriangle + range.triangleCount});
    if (triangles == 0) return;
    width_ = width;
    height_ = height;

    const auto drawIndex = std::uint32_t(drawCount_);
    DrawRecord& record = newDraw();
    const std::size_t vertices = mesh.positions.size();
    try {
        record.vertices.resize(vertices);
        record.clip.resize(vertices);
        record.mask.resize(vertices);
    } catch (const std::bad_alloc&) {
        --drawCount_;
        assert(false && "draw: out of memory");
        return;
    }
    record.shading = input.shading;

    VertexJob vertexJob;
    vertexJob.positions = mesh.positions.data();
    vertexJob.normals = mesh.normals.empty() ? nullptr : mesh.normals.data();
    vertexJob.colors = mesh.colors.empty() ? nullptr : mesh.colors.data();
    vertexJob.uvs = mesh.uvs.empty() ? nullptr : mesh.uvs.data();
    vertexJob.tangents = record.shading.tangentSpace() && !mesh.tangents.empty() ? mesh.tangents.data() : nullptr;
    if (vertexJob.tangents == nullptr)  // no basis to read them in
        record.shading.normalMap = record.shading.clearcoatNormalMap = nullptr;
    vertexJob.mvp = input.mvp;
    vertexJob.normalMatrix = input.normalMatrix;
    vertexJob.model = input.model;
    vertexJob.uvTransform = input.uvTransform;
    vertexJob.viewport = makeViewport(width, height, input.depthFormat, input.samples);
    vertexJob.out = record.vertices.data();
    vertexJob.clip = record.clip.data();
    vertexJob.mask = record.mask.data();
    transformVertices(mesh, vertexJob, runs, triangles);

    if (mesh.corners != 3) {  // points or segments: no faces, and few enough to set up here
        const SetupJob job{&mesh, &record, vertexJob.viewport, drawIndex, input.firstId, 0, false, &runs, nullptr};
        setupShapes(job, record, triangles, segmentCount_ > 0 ? *segments_[segmentCount_ - 1] : newSegment());
        return;
    }

    // Which draw-module batches run the pipeline (this only matters when back faces are culled).
    const bool cullBack = !input.doubleSided;
    const std::uint32_t batchSize = input.shading.writeIds ? kArrayBatch : kIndexedBatch;
    std::vector<std::uint8_t> clippedBatch;
    for (Run& run : runs) {
        run.batch = std::uint32_t(clippedBatch.size());
        clippedBatch.resize(clippedBatch.size() + (run.end - run.first + batchSize - 1) / batchSize, 0);
        if (!cullBack) continue;
        const std::uint32_t* index = mesh.indices.data() + std::size_t(run.first) * 3;
        for (std::uint32_t tri = run.first; tri < run.end; ++tri, index += 3)
            if ((record.mask[index[0]] | record.mask[index[1]] | record.mask[index[2]]) != 0)
                clippedBatch[run.batch + (tri - run.first) / batchSize] = 1;
    }

    const SetupJob job{&mesh,    &record, vertexJob.viewport, drawIndex, input.firstId, batchSize,
                       cullBack, &runs,   &clippedBatch};
    if (pool_.size() > 1 && triangles >= 2 * kSetupChunk) {
        // In parallel: chunk c goes to its own segment, and segments stay in submission order.
        const auto chunks = std::size_t(
            std::min<std::uint64_t>((triangles + kSetupChunk - 1) / kSetupChunk, std::uint64_t(pool_.size()) * 4));
        std::vector<Segment*> chunkSegments(chunks);
        for (Segment*& s : chunkSegments) s = &newSegment();
        pool_.run(chunks, [&](std::size_t c, int) {
            const std::uint64_t begin = triangles * c / chunks, end = triangles * (c + 1) / chunks;
            setup(job, begin, end - begin, *chunkSegments[c]);
        });
    } else {
        setup(job, 0, triangles, segmentCount_ > 0 ? *segments_[segmentCount_ - 1] : newSegment());
    }
}

void Pipeline::setupShapes(const SetupJob& job, DrawRecord& record, std::uint64_t primitives, Segment& segment) {
    const int tilesX = (job.viewport.width + kTileSize - 1) / kTileSize;
    const SoftwareMesh& mesh = *job.mesh;
    const bool points = mesh.corners == 1;
    record.shapes.clear();
    try {
        record.shapes.reserve(std::size_t(primitives));  // Triangle::v points into it: no reallocation
    } catch (const std::bad_alloc&) {
        assert(false && "draw: out of memory");
        return;
    }
    // The vertex made by the clipper at t from `out` toward `in` (raster/PointsLines.h, 2.): the
    // triangle clipper's interpolation.
    const auto clipped = [&](std::uint32_t out, std::uint32_t in, float t) {
        return *detail::interpolate({record.clip[out], &record.vertices[out]}, t,
                                    {record.clip[in], &record.vertices[in]}, job.viewport, segment.pool)
                    .vertex;
    };
    for (const Run& run : *job.runs)
        for (std::uint32_t p = run.first; p < run.end; ++p) {
            const std::uint32_t* index = mesh.indices.data() + std::size_t(p) * mesh.corners;
            ShapeRecord shape;
            if (points) {
                if (record.mask[index[0]] != 0) continue;  // drawn only when its centre is inside
                const SetupVertex& v = record.vertices[index[0]];
                if (!setupPoint(v, job.viewport, &shape.setup)) continue;
                // Shading's planes: three corners with the point's values, so every varying is constant.
                shape.corner[0] = shape.corner[1] = shape.corner[2] = v;
                shape.corner[1].x += 1.0f;
                shape.corner[2].y += 1.0f;
            } else {
                const std::uint32_t i0 = index[0], i1 = index[1];
                float t0 = 0.0f, t1 = 0.0f;
                if (!clipSegment(record.clip[i0], record.clip[i1], record.mask[i0], record.mask[i1], job.viewport.halfZ,
                                 &t0, &t1))
                    continue;
                const SetupVertex a = record.mask[i0] != 0 ? clipped(i0, i1, t0) : record.vertices[i0];
                const SetupVertex b = record.mask[i1] != 0 ? clipped(i1, i0, t1) : record.vertices[i1];
                if (!setupSegment(a, b, job.viewport, &shape.setup)) continue;
                // Shading's planes, as llvmpipe's line setup makes them: from the segment's ends and
                // a third corner with the first end's values, a pixel across the minor axis when
                // single-sampled (the varyings follow the major axis only), square to the segment
                // with 4 samples (they follow the segment); there its planes are made with half a
                // pixel of offset while the rasterizer takes none, so they are read half a pixel up
                // and right (raster/PointsLines.h, 7.): the corners move half a pixel the other way.
                shape.corner[0] = a;
                shape.corner[1] = b;
                shape.corner[2] = a;
                if (job.viewport.samples == 1) {
                    (shape.setup.xMajor ? shape.corner[2].y : shape.corner[2].x) += 1.0f;
                } else {
                    shape.corner[2].x -= b.y - a.y;
                    shape.corner[2].y += b.x - a.x;
                    for (SetupVertex& corner : shape.corner) corner.x -= 0.5f, corner.y -= 0.5f;
                }
            }
            const ShapeRecord& kept = record.shapes.emplace_back(shape);
            Triangle t{};
            t.x0 = kept.setup.x0, t.y0 = kept.setup.y0, t.x1 = kept.setup.x1, t.y1 = kept.setup.y1;
            t.v[0] = &kept.corner[0], t.v[1] = &kept.corner[1], t.v[2] = &kept.corner[2];
            t.draw = job.drawIndex;
            t.id = job.firstId + mesh.triangleSource[p];  // 32-bit wrap, as in mesh.vert
            t.front = 1;                                  // gl_FrontFacing is true for points and lines
            t.writesId = record.shading.writeIds;
            t.depthTest = record.shading.depthTest;
            t.shape = points ? kPointShape : kSegmentShape;
            segment.triangles.push_back(t);
            segment.bin(std::uint32_t(segment.triangles.size() - 1), tilesX);
        }
}

void Pipeline::rasterShape(const Triangle& t, TileState& tile) const {
    const ShapeSetup& shape = shapeOf(t).setup;
    const int x0 = std::max(t.x0, tile.x0), x1 = std::min(t.x1, tile.x1 - 1);
    const int y0 = std::max(t.y0, tile.y0), y1 = std::min(t.y1, tile.y1 - 1);
    const TargetView& target = tile.target;
    const int samples = target.samples;
    const bool reversed = target.depthFormat == DepthFormat::D32F;
    const std::size_t stride = std::size_t(target.stride);
    std::uint32_t myIndex = kNoWinner;
    for (int sample = 0; sample < samples; ++sample) {
        const std::size_t plane = std::size_t(sample) * target.sampleStride;
        const float sx = samples > 1 ? kSamplePositions[sample][0] : 0.0f;
        const float sy = samples > 1 ? kSamplePositions[sample][1] : 0.0f;
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                if (!shapeCovers(shape, x, y, sample, samples)) continue;
                const std::size_t at = plane + std::size_t(y) * stride + std::size_t(x);
                if (t.depthTest) {  // nearer passes: D24 "<", D32F (reversed) ">"
                    const std::uint32_t z =
                        storedDepth(shapeDepth(shape, float(x) + sx, float(y) + sy, fused_), target.depthFormat);
                    if (!(reversed ? z > target.depth[at] : target.depth[at] > z)) continue;
                    target.depth[at] = z;
                }
                if (myIndex == kNoWinner) {
                    myIndex = std::uint32_t(tile.won.size());
                    tile.won.push_back(&t);
                }
                tile.winner[sample * TileState::kPlane + (y - tile.y0) * kTileSize + (x - tile.x0)] = myIndex;
                if (t.writesId) target.ids[at] = t.id;
            }
    }
}

namespace {
constexpr std::size_t kInlineFlushTriangles = 256;
}  // namespace

void Pipeline::flush(const TargetView& target) {
    if (segmentCount_ == 0) {
        drawCount_ = 0;
        return;
    }
    assert(target.width == width_ && target.height == height_ && "Pipeline::flush: not the target drawn for");
    const int tilesX = (target.width + kTileSize - 1) / kTileSize;
    const int tilesY = (target.height + kTileSize - 1) / kTileSize;
    const int tileCount = tilesX * tilesY;
    // A small flush (a few hundred triangles: a reuse frame's redraws) runs on the calling thread:
    // waking the workers twice costs more than the work. Tiles are independent, so the result is
    // the same either way.
    std::size_t pending = 0;
    for (std::size_t s = 0; s < segmentCount_; ++s) pending += segments_[s]->triangles.size();
    const auto run = [&](std::size_t count, const std::function<void(std::size_t, int)>& fn) {
        if (pending < kInlineFlushTriangles) {
            for (std::size_t i = 0; i < count; ++i) fn(i, 0);
        } else {
            pool_.run(count, fn);
        }
    };
    run(segmentCount_, [&](std::size_t s, int) { segments_[s]->close(tileCount); });
    for (InterpScratch& scratch : interpScratch_)
        if (scratch.values.size() < std::size_t(target.width)) scratch.values.resize(std::size_t(target.width));
    run(std::size_t(tileCount), [&](std::size_t tileIndex, int worker) {
        bool any = false;
        for (std::size_t s = 0; s < segmentCount_ && !any; ++s)
            any = segments_[s]->tileStart[tileIndex + 1] > segments_[s]->tileStart[tileIndex];
        if (!any) return;
        TileState& tile = *tiles_[std::size_t(worker)];
        tile.target = target;
        tile.x0 = int(tileIndex % std::size_t(tilesX)) * kTileSize;
        tile.y0 = int(tileIndex / std::size_t(tilesX)) * kTileSize;
        tile.x1 = std::min(tile.x0 + kTileSize, target.width);
        tile.y1 = std::min(tile.y0 + kTileSize, target.height);
        tile.won.clear();
        std::fill_n(tile.winner, target.samples * TileState::kPlane, kNoWinner);
        InterpScratch* scratch = interpScratch_.empty() ? nullptr : &interpScratch_[std::size_t(worker)];
        const auto rasterize = [&](const Triangle& t) {
            // The slow path (InterpRaster.h): span-interpolated depth, one pixel at a time.
            if (t.shape != 0)
                rasterShape(t, tile);
            else if (scratch != nullptr && t.depthTest)
                rasterInterp(t, tile, interp_, fused_, *scratch);
            else
                kernels_.raster(t, tile);
        };
        for (std::size_t s = 0; s < segmentCount_; ++s) {
            const Segment& segment = *segments_[s];
            for (std::uint32_t i = segment.tileStart[tileIndex]; i < segment.tileStart[tileIndex + 1]; ++i) {
                const Triangle& t = segment.triangles[segment.sorted[i]];
                const DrawShading& shading = draws_[t.draw]->shading;
                if (shading.alphaMode == AlphaMode::Opaque)
                    rasterize(t);
                else
                    rasterizeAlone(t, shading, tile, rasterize);
            }
        }
        shadePending(tile);
    });
    for (InterpScratch& scratch : interpScratch_) {
        interpStats_.spans += scratch.stats.spans;
        interpStats_.pixels += scratch.stats.pixels;
        interpStats_.overflow += scratch.stats.overflow;
        interpStats_.overflowBits |= scratch.stats.overflowBits;
        scratch.stats = {};
    }
    discard();
}

void Pipeline::shadePending(TileState& tile) const {
    if (tile.won.empty()) return;
    int x0 = tile.x1, y0 = tile.y1, x1 = tile.x0 - 1, y1 = tile.y0 - 1;
    for (std::uint32_t w = 0; w < tile.won.size(); ++w) {
        const Triangle& t = *tile.won[w];
        kernels_.shade(w, draws_[t.draw]->shading, tile);
        x0 = std::min(x0, t.x0), y0 = std::min(y0, t.y0), x1 = std::max(x1, t.x1), y1 = std::max(y1, t.y1);
    }
    tile.won.clear();
    forgetWinners(tile, x0, y0, x1, y1);
}

void Pipeline::forgetWinners(TileState& tile, int x0, int y0, int x1, int y1) {
    x0 = std::max(x0, tile.x0), y0 = std::max(y0, tile.y0);
    x1 = std::min(x1, tile.x1 - 1), y1 = std::min(y1, tile.y1 - 1);
    for (int sample = 0; sample < tile.target.samples; ++sample)
        for (int y = y0; y <= y1; ++y) {
            std::uint32_t* row = tile.winner + sample * TileState::kPlane + (y - tile.y0) * kTileSize;
            std::fill(row + (x0 - tile.x0), row + (x1 - tile.x0 + 1), kNoWinner);
        }
}

template <class Rasterize>
void Pipeline::rasterizeAlone(const Triangle& t, const DrawShading& shading, TileState& tile,
                              const Rasterize& rasterize) const {
    shadePending(tile);  // a blend reads the colour below; a later depth test sees what came before
    const int x0 = std::max(t.x0, tile.x0), y0 = std::max(t.y0, tile.y0);
    const int x1 = std::min(t.x1, tile.x1 - 1), y1 = std::min(t.y1, tile.y1 - 1);
    if (x0 > x1 || y0 > y1) return;
    const TargetView& target = tile.target;
    const bool masked = shading.alphaMode == AlphaMode::Mask;
    const bool ids = t.writesId && target.ids != nullptr;
    const std::size_t width = std::size_t(x1 - x0 + 1), rows = std::size_t(y1 - y0 + 1);
    // Where sample `sample`'s row y of the rectangle is in the target and in `saved`.
    const auto targetAt = [&](int sample, int y) {
        return std::size_t(sample) * target.sampleStride + std::size_t(y) * std::size_t(target.stride) +
               std::size_t(x0);
    };
    const auto savedAt = [&](int sample, int y) {
        return 2 * width * (std::size_t(sample) * rows + std::size_t(y - y0));
    };
    if (masked) {  // depth and ids as they are, for the samples the mask discards
        tile.saved.resize(2 * width * rows * std::size_t(target.samples));
        for (int sample = 0; sample < target.samples; ++sample)
            for (int y = y0; y <= y1; ++y) {
                std::uint32_t* out = tile.saved.data() + savedAt(sample, y);
                std::copy_n(target.depth + targetAt(sample, y), width, out);
                if (ids) std::copy_n(target.ids + targetAt(sample, y), width, out + width);
            }
    }
    rasterize(t);
    if (tile.won.empty()) return;
    kernels_.shade(0, shading, tile);
    tile.won.clear();
    for (int sample = 0; sample < target.samples; ++sample)
        for (int y = y0; y <= y1; ++y) {
            std::uint32_t* row = tile.winner + sample * TileState::kPlane + (y - tile.y0) * kTileSize + (x0 - tile.x0);
            const std::size_t at = targetAt(sample, y), from = savedAt(sample, y);
            for (std::size_t x = 0; x < width; ++x) {
                if (masked && row[x] == kKilled) {
                    target.depth[at + x] = tile.saved[from + x];
                    if (ids) target.ids[at + x] = tile.saved[from + width + x];
                }
                row[x] = kNoWinner;
            }
        }
}

void Pipeline::discard() {
    for (std::size_t s = 0; s < segmentCount_; ++s) segments_[s]->reset();
    segmentCount_ = 0;
    drawCount_ = 0;
}

}  // namespace frugal::sw
