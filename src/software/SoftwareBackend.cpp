// The software Backend: targets, meshes and textures in memory, draws through the rasterizer
// (Rasterizer.h) and the kernels (Kernels.h), clears and copies as Mesa performs them (Shading.h).
#include "software/SoftwareBackend.h"

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <cstring>
#include <glm/gtc/matrix_inverse.hpp>
#include <new>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "software/Kernels.h"
#include "software/Rasterizer.h"
#include "software/Shading.h"
#include "software/ThreadPool.h"

#pragma GCC optimize("fp-contract=off")

namespace frugal {

namespace {

using sw::Segment;
using sw::SetupVertex;
using sw::Triangle;

// Same limits as the GL backend on llvmpipe (GL_MAX_RENDERBUFFER_SIZE, GL_MAX_TEXTURE_SIZE).
constexpr int kMaxSize = 16384;

struct SwTarget {
    int width = 0, height = 0, stride = 0;
    std::vector<std::uint32_t> color, depth, ids;

    sw::TargetView view() {
        return {color.data(), depth.data(), ids.data(), width, height, stride};
    }
};

struct SwMesh {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec4> colors;
    std::vector<glm::vec2> uvs;
    std::vector<std::uint32_t> indices, triangleSource;
    std::uint32_t triangles = 0;
    std::vector<std::uint64_t> stamp;  // per vertex: the draw that last transformed it (partial draws)
};

// One draw's transformed vertices and shading parameters, alive until the frame is rasterized.
struct DrawRecord {
    std::vector<SetupVertex> vertices;
    std::vector<glm::vec4> clip;
    std::vector<std::uint8_t> mask;
    sw::DrawShading shading;
};

// Handles are slot index + 1, as in the GL backend; freed slots are reused.
template <class T>
class Slots {
public:
    std::uint32_t add(T value) {
        if (!free_.empty()) {
            const std::uint32_t index = free_.back();
            free_.pop_back();
            items_[index] = std::make_unique<T>(std::move(value));
            return index + 1;
        }
        items_.push_back(std::make_unique<T>(std::move(value)));
        return std::uint32_t(items_.size());
    }
    T* find(std::uint32_t handle) {
        if (handle == kNoHandle || handle > items_.size()) return nullptr;
        return items_[handle - 1].get();
    }
    void remove(std::uint32_t handle) {
        if (find(handle) == nullptr) return;
        items_[handle - 1].reset();
        free_.push_back(handle - 1);
    }

private:
    std::vector<std::unique_ptr<T>> items_;
    std::vector<std::uint32_t> free_;
};

Rect clipRect(const Rect& rect, int width, int height) {
    const int x0 = std::max(rect.x, 0), y0 = std::max(rect.y, 0);
    const int x1 = std::min(rect.x + std::max(rect.width, 0), width);
    const int y1 = std::min(rect.y + std::max(rect.height, 0), height);
    return Rect{x0, y0, std::max(x1 - x0, 0), std::max(y1 - y0, 0)};
}

struct Run {
    std::uint32_t first, end;  // triangles [first, end)
    std::uint32_t batch = 0;   // index of the run's first draw-module batch in the draw's batch flags
};

// The draw module cuts each (merged) range into batches and runs its pipeline stages, face culling
// among them, only for the batches in which a vertex needs clipping (Rasterizer.h, 2a). Batch sizes,
// in triangles: the id pass draws arrays, split every 4095 vertices (max_vertices 4096, trimmed to
// whole triangles, draw_split_tmp.h); the indexed pass is split every 1023 indices (vsplit
// SEGMENT_SIZE 1024).
constexpr std::uint32_t kArrayBatch = 4095 / 3;
constexpr std::uint32_t kIndexedBatch = 1023 / 3;

class SoftwareBackend final : public Backend {
public:
    explicit SoftwareBackend(const SoftwareOptions& options)
        : kernels_(sw::selectKernels(options.simd)),
          fused_(sw::cpuHasFma()),
          pool_(options.threads > 0 ? options.threads : int(std::max(1u, std::thread::hardware_concurrency()))) {
        tiles_.resize(std::size_t(pool_.size()));
        for (auto& tile : tiles_) tile = std::make_unique<sw::TileState>();
    }

    std::string name() const override { return "software"; }
    std::string renderer() const override {
        return std::string("frugal software rasterizer (llvmpipe rules, ") + kernels_.name + " kernels, " +
               std::to_string(pool_.size()) + (pool_.size() == 1 ? " thread)" : " threads)");
    }
    int maxTargetSize() const override { return kMaxSize; }

    TargetHandle createTarget(int width, int height) override;
    void destroyTarget(TargetHandle target) override;
    MeshHandle uploadMesh(const Mesh& mesh) override;
    TextureHandle uploadTexture(const Texture& texture) override;
    void beginFrame(TargetHandle target, const FrameParams& frame) override;
    void draw(const DrawParams& params, std::span<const IndexRange> ranges) override;
    void clear(TargetHandle target, const Rect& rect, const glm::vec4& color, float depth) override;
    void copy(TargetHandle from, TargetHandle to, const Rect& rect, bool color, bool depth, bool ids) override;
    Buffers readBack(TargetHandle target) override;
    void finish() override { flush(); }

private:
    void transformVertices(SwMesh& mesh, const sw::VertexJob& job, const std::vector<Run>& runs,
                           std::uint64_t triangles);
    void setupRuns(const SwMesh& mesh, const DrawRecord& record, const sw::Viewport& viewport,
                   std::uint32_t drawIndex, std::uint32_t firstId, bool cullBack, const std::vector<Run>& runs,
                   std::uint32_t batchSize, const std::vector<std::uint8_t>& clippedBatch, std::uint64_t skip,
                   std::uint64_t count, Segment& segment);
    Segment& newSegment();
    DrawRecord& newDraw();
    void flush();

    const sw::Kernels& kernels_;
    const bool fused_;
    sw::ThreadPool pool_;
    std::vector<std::unique_ptr<sw::TileState>> tiles_;  // one per thread

    Slots<SwTarget> targets_;
    Slots<SwMesh> meshes_;
    Slots<sw::SoftwareTexture> textures_;

    TargetHandle frameTarget_ = kNoHandle;
    FrameParams frame_;
    glm::mat4 viewProjection_{1.0f};
    std::uint64_t drawSerial_ = 0;

    // Pending work, all for frameTarget_. Records and segments are reused from frame to frame.
    std::vector<std::unique_ptr<DrawRecord>> draws_;
    std::size_t drawCount_ = 0;
    std::vector<std::unique_ptr<Segment>> segments_;
    std::size_t segmentCount_ = 0;
};

TargetHandle SoftwareBackend::createTarget(int width, int height) {
    if (width <= 0 || height <= 0 || width > kMaxSize || height > kMaxSize) return kNoHandle;
    SwTarget t;
    t.width = width;
    t.height = height;
    t.stride = (width + 7) & ~7;
    const std::size_t pixels = std::size_t(t.stride) * std::size_t(height);
    try {
        // Contents defined from the start, like the GL backend: transparent black, far depth, id 0.
        t.color.assign(pixels, 0u);
        t.depth.assign(pixels, sw::clearDepthWhole(1.0f));
        t.ids.assign(pixels, 0u);
    } catch (const std::bad_alloc&) {
        return kNoHandle;
    }
    return targets_.add(std::move(t));
}

void SoftwareBackend::destroyTarget(TargetHandle target) {
    if (targets_.find(target) == nullptr) return;
    if (target == frameTarget_) {
        flush();
        frameTarget_ = kNoHandle;
    }
    targets_.remove(target);
}

MeshHandle SoftwareBackend::uploadMesh(const Mesh& mesh) {
    // The GL backend's validation, so both backends accept and refuse the same meshes.
    const std::size_t vertices = mesh.positions.size();
    const std::size_t triangles = mesh.indices.size() / 3;
    const auto fits = [vertices](std::size_t n) { return n == 0 || n == vertices; };
    if (mesh.indices.size() % 3 != 0 || !fits(mesh.normals.size()) || !fits(mesh.colors.size()) ||
        !fits(mesh.uvs.size()) || vertices > 0xFFFFFFFFu || triangles > 0x7FFFFFFFu / 3 ||
        (!mesh.triangleSource.empty() && mesh.triangleSource.size() != triangles))
        return kNoHandle;
    for (std::uint32_t index : mesh.indices)
        if (index >= vertices) return kNoHandle;
    SwMesh m;
    try {
        m.positions = mesh.positions;
        m.normals = mesh.normals;
        m.colors = mesh.colors;
        m.uvs = mesh.uvs;
        m.indices = mesh.indices;
        m.triangles = std::uint32_t(triangles);
        m.triangleSource = mesh.triangleSource;
        if (m.triangleSource.empty()) {
            m.triangleSource.resize(triangles);
            for (std::uint32_t t = 0; t < m.triangles; ++t) m.triangleSource[t] = t;
        }
        m.stamp.assign(vertices, 0);
    } catch (const std::bad_alloc&) {
        return kNoHandle;
    }
    return meshes_.add(std::move(m));
}

TextureHandle SoftwareBackend::uploadTexture(const Texture& texture) {
    if (texture.width <= 0 || texture.height <= 0 || texture.width > kMaxSize || texture.height > kMaxSize ||
        texture.rgba.size() != std::size_t(texture.width) * std::size_t(texture.height) * 4)
        return kNoHandle;
    sw::SoftwareTexture t;
    t.width = texture.width;
    t.height = texture.height;
    t.filter = texture.filter;
    t.wrapS = texture.wrapS;
    t.wrapT = texture.wrapT;
    const auto simple = [](Wrap w) { return w == Wrap::Repeat || w == Wrap::ClampToEdge; };
    t.aos = simple(t.wrapS) && simple(t.wrapT);
    try {
        t.texels.resize(std::size_t(t.width) * std::size_t(t.height));
    } catch (const std::bad_alloc&) {
        return kNoHandle;
    }
    std::memcpy(t.texels.data(), texture.rgba.data(), texture.rgba.size());  // little-endian: R is the low byte
    return textures_.add(std::move(t));
}

void SoftwareBackend::beginFrame(TargetHandle target, const FrameParams& frame) {
    assert(targets_.find(target) != nullptr && "beginFrame: no such target");
    if (targets_.find(target) == nullptr) return;
    if (target != frameTarget_) flush();
    frameTarget_ = target;
    frame_ = frame;
    viewProjection_ = frame.projection * frame.view;  // as GlBackend::beginFrame, in float with glm
}

Segment& SoftwareBackend::newSegment() {
    if (segmentCount_ == segments_.size()) segments_.push_back(std::make_unique<Segment>());
    Segment& s = *segments_[segmentCount_++];
    s.reset();
    return s;
}

DrawRecord& SoftwareBackend::newDraw() {
    if (drawCount_ == draws_.size()) draws_.push_back(std::make_unique<DrawRecord>());
    return *draws_[drawCount_++];
}

// The vertex stage for the vertices the draw's runs use.
void SoftwareBackend::transformVertices(SwMesh& mesh, const sw::VertexJob& job, const std::vector<Run>& runs,
                                        std::uint64_t triangles) {
    const std::size_t vertices = mesh.positions.size();
    if (triangles * 3 >= vertices / 2) {
        // Most of the mesh: every vertex once, in parallel chunks.
        constexpr std::size_t kChunk = 4096;
        const std::size_t chunks = (vertices + kChunk - 1) / kChunk;
        pool_.run(chunks, [&](std::size_t c, int) {
            kernels_.transform(job, c * kChunk, std::min(vertices, (c + 1) * kChunk));
        });
        return;
    }
    // A few ranges of a big mesh: only the vertices they use.
    const std::uint64_t serial = ++drawSerial_;
    for (const Run& run : runs)
        for (std::uint32_t t = run.first; t < run.end; ++t)
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t v = mesh.indices[std::size_t(t) * 3 + k];
                if (mesh.stamp[v] == serial) continue;
                mesh.stamp[v] = serial;
                kernels_.transform(job, v, v + 1);
            }
}

// Clips, sets up and bins `count` triangles of the draw, starting `skip` triangles into its runs.
void SoftwareBackend::setupRuns(const SwMesh& mesh, const DrawRecord& record, const sw::Viewport& viewport,
                                std::uint32_t drawIndex, std::uint32_t firstId, bool cullBack,
                                const std::vector<Run>& runs, std::uint32_t batchSize,
                                const std::vector<std::uint8_t>& clippedBatch, std::uint64_t skip,
                                std::uint64_t count, Segment& segment) {
    const int tilesX = (viewport.width + sw::kTileSize - 1) / sw::kTileSize;
    const std::uint32_t* indices = mesh.indices.data();
    const SetupVertex* vertices = record.vertices.data();
    const auto emit = [&](const SetupVertex* a, const SetupVertex* b, const SetupVertex* c, std::uint32_t id,
                          bool drawModuleCull) {
        if (drawModuleCull && !sw::drawModuleKeepsFront(a, b, c)) return;
        Triangle t;
        if (!sw::setupTriangle(a, b, c, cullBack, viewport, &t)) return;
        t.draw = drawIndex;
        t.id = id;
        t.writesId = record.shading.writeIds;
        segment.triangles.push_back(t);
        segment.bin(std::uint32_t(segment.triangles.size() - 1), tilesX);
    };
    for (std::size_t r = 0; r < runs.size() && count > 0; ++r) {
        const std::uint64_t length = runs[r].end - runs[r].first;
        if (skip >= length) {
            skip -= length;
            continue;
        }
        const std::uint32_t first = std::uint32_t(runs[r].first + skip);
        const std::uint32_t end = std::uint32_t(std::min<std::uint64_t>(runs[r].end, first + count));
        skip = 0;
        count -= end - first;
        for (std::uint32_t tri = first; tri < end; ++tri) {
            const std::uint32_t i0 = indices[3 * std::size_t(tri)], i1 = indices[3 * std::size_t(tri) + 1],
                                i2 = indices[3 * std::size_t(tri) + 2];
            const unsigned m0 = record.mask[i0], m1 = record.mask[i1], m2 = record.mask[i2];
            const std::uint32_t id = firstId + mesh.triangleSource[tri];  // 32-bit wrap, as in mesh.vert
            const bool drawModuleCull = cullBack && clippedBatch[runs[r].batch + (tri - runs[r].first) / batchSize];
            if ((m0 | m1 | m2) == 0) {
                emit(&vertices[i0], &vertices[i1], &vertices[i2], id, drawModuleCull);
            } else if ((m0 & m1 & m2) == 0) {
                const glm::vec4* clip[3] = {&record.clip[i0], &record.clip[i1], &record.clip[i2]};
                const SetupVertex* in[3] = {&vertices[i0], &vertices[i1], &vertices[i2]};
                sw::clipTriangle(clip, in, m0 | m1 | m2, viewport, segment.pool,
                                 [&](const SetupVertex* a, const SetupVertex* b, const SetupVertex* c) {
                                     emit(a, b, c, id, drawModuleCull);
                                 });
            }
        }
    }
}

void SoftwareBackend::draw(const DrawParams& params, std::span<const IndexRange> ranges) {
    SwTarget* target = targets_.find(frameTarget_);
    SwMesh* mesh = meshes_.find(params.mesh);
    assert(target != nullptr && "draw: no beginFrame, or its target was destroyed");
    assert(mesh != nullptr && "draw: no such mesh");
    if (target == nullptr || mesh == nullptr) return;

    // Ranges in the order given, clamped to the mesh, adjacent ones merged (as the GL backend: the
    // merged ranges are what the draw module splits into batches).
    std::vector<Run> runs;
    std::uint64_t triangles = 0;
    for (const IndexRange& range : ranges) {
        assert(std::uint64_t(range.firstTriangle) + range.triangleCount <= mesh->triangles &&
               "draw: index range past the end of the mesh");
        const std::uint32_t first = std::min(range.firstTriangle, mesh->triangles);
        const std::uint32_t end = first + std::min(range.triangleCount, mesh->triangles - first);
        if (end == first) continue;
        triangles += end - first;
        if (!runs.empty() && runs.back().end == first)
            runs.back().end = end;
        else
            runs.push_back({first, end});
    }
    if (triangles == 0) return;

    const auto drawIndex = std::uint32_t(drawCount_);
    DrawRecord& record = newDraw();
    const std::size_t vertices = mesh->positions.size();
    try {
        record.vertices.resize(vertices);
        record.clip.resize(vertices);
        record.mask.resize(vertices);
    } catch (const std::bad_alloc&) {
        --drawCount_;
        assert(false && "draw: out of memory");
        return;
    }

    sw::DrawShading& shading = record.shading;
    shading.factor = params.baseColorFactor;
    shading.texture = params.texture != kNoHandle ? textures_.find(params.texture) : nullptr;
    assert((params.texture == kNoHandle || shading.texture != nullptr) && "draw: no such texture");
    shading.toLight = frame_.lighting.toLight;
    shading.ambient = frame_.lighting.ambient;
    shading.diffuse = frame_.lighting.diffuse;
    shading.writeIds = frame_.writeIds;

    sw::VertexJob job;
    job.positions = mesh->positions.data();
    job.normals = mesh->normals.empty() ? nullptr : mesh->normals.data();
    job.colors = mesh->colors.empty() ? nullptr : mesh->colors.data();
    job.uvs = mesh->uvs.empty() ? nullptr : mesh->uvs.data();
    job.mvp = viewProjection_ * params.model;  // as GlBackend::draw
    job.normalMatrix = glm::inverseTranspose(glm::mat3(params.model));
    job.viewport = sw::makeViewport(target->width, target->height);
    job.out = record.vertices.data();
    job.clip = record.clip.data();
    job.mask = record.mask.data();
    transformVertices(*mesh, job, runs, triangles);

    const bool cullBack = !params.doubleSided;
    // Which draw-module batches run the pipeline (only matters when culling).
    const std::uint32_t batchSize = frame_.writeIds ? kArrayBatch : kIndexedBatch;
    std::vector<std::uint8_t> clippedBatch;
    for (Run& run : runs) {
        run.batch = std::uint32_t(clippedBatch.size());
        clippedBatch.resize(clippedBatch.size() + (run.end - run.first + batchSize - 1) / batchSize, 0);
        if (!cullBack) continue;
        const std::uint32_t* index = mesh->indices.data() + std::size_t(run.first) * 3;
        for (std::uint32_t tri = run.first; tri < run.end; ++tri, index += 3)
            if ((record.mask[index[0]] | record.mask[index[1]] | record.mask[index[2]]) != 0)
                clippedBatch[run.batch + (tri - run.first) / batchSize] = 1;
    }
    constexpr std::uint64_t kChunk = 2048;
    if (pool_.size() > 1 && triangles >= 2 * kChunk) {
        // Setup in parallel: chunk c goes to its own segment, segments stay in submission order.
        const std::size_t chunks = std::size_t(std::min<std::uint64_t>((triangles + kChunk - 1) / kChunk,
                                                                       std::uint64_t(pool_.size()) * 4));
        std::vector<Segment*> chunkSegments(chunks);
        for (Segment*& s : chunkSegments) s = &newSegment();
        pool_.run(chunks, [&](std::size_t c, int) {
            const std::uint64_t begin = triangles * c / chunks, end = triangles * (c + 1) / chunks;
            setupRuns(*mesh, record, job.viewport, drawIndex, params.firstId, cullBack, runs, batchSize, clippedBatch,
                      begin, end - begin, *chunkSegments[c]);
        });
    } else {
        Segment& segment = segmentCount_ > 0 ? *segments_[segmentCount_ - 1] : newSegment();
        setupRuns(*mesh, record, job.viewport, drawIndex, params.firstId, cullBack, runs, batchSize, clippedBatch, 0,
                  triangles, segment);
    }
}

void SoftwareBackend::flush() {
    if (segmentCount_ == 0) {
        drawCount_ = 0;
        return;
    }
    SwTarget* target = targets_.find(frameTarget_);
    if (target != nullptr) {
        const int tilesX = (target->width + sw::kTileSize - 1) / sw::kTileSize;
        const int tilesY = (target->height + sw::kTileSize - 1) / sw::kTileSize;
        const int tileCount = tilesX * tilesY;
        pool_.run(segmentCount_, [&](std::size_t s, int) { segments_[s]->close(tileCount); });
        const sw::TargetView view = target->view();
        pool_.run(std::size_t(tileCount), [&](std::size_t tileIndex, int worker) {
            bool any = false;
            for (std::size_t s = 0; s < segmentCount_ && !any; ++s)
                any = segments_[s]->tileStart[tileIndex + 1] > segments_[s]->tileStart[tileIndex];
            if (!any) return;
            sw::TileState& tile = *tiles_[std::size_t(worker)];
            tile.target = view;
            tile.x0 = int(tileIndex % std::size_t(tilesX)) * sw::kTileSize;
            tile.y0 = int(tileIndex / std::size_t(tilesX)) * sw::kTileSize;
            tile.x1 = std::min(tile.x0 + sw::kTileSize, target->width);
            tile.y1 = std::min(tile.y0 + sw::kTileSize, target->height);
            tile.won.clear();
            std::fill(std::begin(tile.winner), std::end(tile.winner), sw::kNoWinner);
            for (std::size_t s = 0; s < segmentCount_; ++s) {
                const Segment& segment = *segments_[s];
                for (std::uint32_t i = segment.tileStart[tileIndex]; i < segment.tileStart[tileIndex + 1]; ++i)
                    kernels_.raster(segment.triangles[segment.sorted[i]], tile);
            }
            for (std::uint32_t w = 0; w < tile.won.size(); ++w)
                kernels_.shade(w, draws_[tile.won[w]->draw]->shading, tile);
        });
    }
    for (std::size_t s = 0; s < segmentCount_; ++s) segments_[s]->reset();
    segmentCount_ = 0;
    drawCount_ = 0;
}

void SoftwareBackend::clear(TargetHandle target, const Rect& rect, const glm::vec4& color, float depth) {
    SwTarget* t = targets_.find(target);
    assert(t != nullptr && "clear: no such target");
    if (t == nullptr) return;
    flush();
    const Rect r = clipRect(rect, t->width, t->height);
    if (r.empty()) return;
    // Mesa clears the whole target with pipe->clear and a part of it with a quad (Shading.h).
    const bool whole = r.x == 0 && r.y == 0 && r.width == t->width && r.height == t->height;
    const std::uint32_t c = sw::packColor(color);
    const std::uint32_t z = whole ? sw::clearDepthWhole(depth) : sw::clearDepthQuad(depth, fused_);
    for (int y = r.y; y < r.y + r.height; ++y) {
        const std::size_t row = std::size_t(y) * std::size_t(t->stride) + std::size_t(r.x);
        std::fill_n(t->color.begin() + std::ptrdiff_t(row), r.width, c);
        std::fill_n(t->depth.begin() + std::ptrdiff_t(row), r.width, z);
        std::fill_n(t->ids.begin() + std::ptrdiff_t(row), r.width, 0u);
    }
}

void SoftwareBackend::copy(TargetHandle from, TargetHandle to, const Rect& rect, bool color, bool depth, bool ids) {
    SwTarget* source = targets_.find(from);
    SwTarget* dest = targets_.find(to);
    assert(source != nullptr && dest != nullptr && "copy: no such target");
    if (source == nullptr || dest == nullptr || from == to) return;
    assert(source->width == dest->width && source->height == dest->height && "copy: targets differ in size");
    const Rect r = clipRect(clipRect(rect, source->width, source->height), dest->width, dest->height);
    if (r.empty() || !(color || depth || ids)) return;
    flush();
    const auto rows = [&](const std::vector<std::uint32_t>& a, std::vector<std::uint32_t>& b) {
        for (int y = r.y; y < r.y + r.height; ++y)
            std::memcpy(b.data() + std::size_t(y) * dest->stride + r.x, a.data() + std::size_t(y) * source->stride + r.x,
                        std::size_t(r.width) * sizeof(std::uint32_t));
    };
    if (color) rows(source->color, dest->color);
    if (depth) rows(source->depth, dest->depth);
    if (ids) rows(source->ids, dest->ids);
}

Buffers SoftwareBackend::readBack(TargetHandle target) {
    Buffers out;
    SwTarget* t = targets_.find(target);
    assert(t != nullptr && "readBack: no such target");
    if (t == nullptr) return out;
    flush();
    out.width = t->width;
    out.height = t->height;
    out.rgba.resize(out.pixelCount() * 4);
    out.depth.resize(out.pixelCount());
    out.ids.resize(out.pixelCount());
    for (int y = 0; y < t->height; ++y) {
        const std::size_t from = std::size_t(y) * std::size_t(t->stride), to = std::size_t(y) * std::size_t(t->width);
        std::memcpy(out.rgba.data() + to * 4, t->color.data() + from, std::size_t(t->width) * 4);
        std::memcpy(out.depth.data() + to, t->depth.data() + from, std::size_t(t->width) * 4);
        std::memcpy(out.ids.data() + to, t->ids.data() + from, std::size_t(t->width) * 4);
    }
    return out;
}

}  // namespace

std::unique_ptr<Backend> makeSoftwareBackend(const SoftwareOptions& options) {
    return std::make_unique<SoftwareBackend>(options);
}

}  // namespace frugal
