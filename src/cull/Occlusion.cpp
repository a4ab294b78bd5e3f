// Occlusion culling on the CPU: see Occlusion.h for the method and what makes it exact.
#include "cull/Occlusion.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <thread>

#include "base/ThreadPool.h"
#include "cull/OcclusionKernels.h"
#include "pipeline/IndexRanges.h"
#include "raster/Rasterizer.h"

// The vertex transform below reproduces the software backend's (Kernels.inl transform): every
// product and sum rounded on its own, the viewport fused only where the CPU fuses it.
#if !defined(__clang__)  // Clang: -ffp-contract=off (CMakeLists.txt)
#pragma GCC optimize("fp-contract=off")
#endif

namespace frugal {

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kBlockLog2 = 3;  // 8 × 8 pixel blocks keep the farthest occluder depth of their pixels
constexpr int kBlock = 1 << kBlockLog2;
constexpr float kOpen = std::numeric_limits<float>::infinity();  // no occluder at this pixel
constexpr double kUnit = 1.0 / 16777216.0;                       // 2^-24: float's unit roundoff

// Below this many submitted triangles the pass costs more than the draw it could save (measured on
// llvmpipe: docs/occlusion.md).
constexpr std::size_t kMinTriangles = 4096;
// What a submitted triangle costs the draw (its vertices, clipping, setup and binning; the pixels
// it does not own cost nothing), measured with three bunnies at 800 × 600 on 2 cores: the draw
// time of the conservative plan less the oracle's, over the triangles between them
// (docs/occlusion.md). A GPU takes a triangle in about a nanosecond: the pass never pays there.
constexpr double kLlvmpipeNsPerTriangle = 110.0;
// What llvmpipe spends on each draw of a plan besides its triangles: the runs of a glMultiDrawElements
// are draws of their own to it. Measured on 4,000 dominoes (12 triangles each, a draw per instance
// of 1 to 6 runs) from three views, the conservative plan's draw time less the occlusion plan's
// over the draws between them, after the triangles' share: 1.0 to 2.1 µs; the lowest is taken, as a
// pass credited with more than it saves runs where it does not pay (docs/occlusion.md). On the
// software backend and a GPU it is not measured, and not counted.
constexpr double kLlvmpipeNsPerDraw = 1000.0;
constexpr double kSoftwareNsPerTriangle = 30.0;
constexpr double kGpuNsPerTriangle = 1.0;
// After a pass that did not pay, the next 1, 2, 4, ... (at most kMaxBackOff) calls skip it, unless
// their plan has more than kBackOffGrowth times its triangles.
constexpr int kMaxBackOff = 16;
constexpr double kBackOffGrowth = 1.25;
// How long the threads prepare() wakes wait for the pass: making the conservative plan of a large
// scene takes about a millisecond.
constexpr std::chrono::microseconds kWarmFor{3000};

// A cluster in the order of the pass.
// A cluster in the order of the pass, or all the kept clusters of an instance of a small mesh
// (kGroupTriangles): one box, one test and one matrix for a domino, not one for each of its faces.
struct Item {
    float nearest = 0;           // far-ness bound of the box's nearest point (less every margin)
    std::int32_t x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // pixels it may reach, inclusive; x0 > x1: none
    std::uint32_t kept = 0;      // its first kept cluster (index into them)
    std::uint32_t count = 1;     // and how many, all of one instance
    bool testable = false;       // false: reaches the near plane or is not finite, always kept
};

// An instance of a mesh of at most this many triangles is one item, whatever its clusters.
constexpr std::size_t kGroupTriangles = 256;

// Items are gathered into the plan in pieces of this many, side by side.
constexpr std::size_t kPieceItems = 64;

// What one piece of the items leaves of the plan: its ranges (firstRange of its clusters counts
// from the piece's first range) and its counts. A cache line of its own: pieces are filled side by
// side, and a vector's end pointer shared with another thread's costs more than the gathering.
struct alignas(64) Piece {
    std::vector<IndexRange> ranges;
    std::size_t tested = 0, hidden = 0, triangles = 0;
};

// What every band's walk reads.
struct Walk {
    const Scene& scene;
    const std::vector<MeshMap>& maps;
    const std::vector<glm::mat4>& world;
    const glm::mat4& viewProjection;
    const std::vector<KeptCluster>& kept;
    const std::vector<IndexRange>& ranges;
};

// Rows [y0, y1] of the buffer (whole 8-row blocks), walked by one thread.
struct Band {
    int y0 = 0, y1 = -1;
    std::vector<std::uint8_t> seen;  // per triangle slot: 1 when this band may see it (or must keep it)
    // The current cluster's vertices, transformed (occlusion::WindowArrays), and its triangles'
    // quick verdicts (occlusion::Verdict).
    std::vector<float> x, y, z;
    std::vector<std::int32_t> fx, fy;
    std::vector<std::uint8_t> verdict;
    // What the quick test gives of kSmall triangles (occlusion::SmallTriangles).
    std::vector<std::int32_t> smallX0, smallY0;
    std::vector<std::uint8_t> covered, occludes;
    std::vector<float> lo, hi;
    // And of kMedium ones.
    std::vector<std::int32_t> smallX1, smallY1, edge;
    std::vector<float> plane;

    occlusion::WindowArrays window() { return {x.data(), y.data(), z.data(), fx.data(), fy.data()}; }
    occlusion::SmallTriangles small() {
        return {smallX0.data(), smallY0.data(), covered.data(), occludes.data(), lo.data(), hi.data(),
                std::uint32_t(verdict.size()), smallX1.data(), smallY1.data(), edge.data(), plane.data()};
    }
    void reserve(std::size_t vertices, std::size_t triangles) {
        if (x.size() < vertices) x.resize(vertices), y.resize(vertices), z.resize(vertices), fx.resize(vertices), fy.resize(vertices);
        if (verdict.size() < triangles) {
            verdict.resize(triangles), smallX0.resize(triangles), smallY0.resize(triangles);
            covered.resize(triangles), occludes.resize(triangles), lo.resize(4 * triangles), hi.resize(4 * triangles);
            smallX1.resize(triangles), smallY1.resize(triangles), edge.resize(9 * triangles), plane.resize(4 * triangles);
        }
    }
};

// The vertex stage of the software backend for positions only (Kernels.inl transform): every
// product and sum rounded on its own; the viewport's multiply-add fused or not as llvmpipe does it
// on this CPU (`kFused`). occlusion::transformAvx2 is the same, eight at a time.
template <bool kFused>
inline __attribute__((always_inline)) void transformBody(const glm::mat4& m, const float* px, const float* py,
                                                         const float* pz, std::uint32_t count, const raster::Viewport& vp,
                                                         const occlusion::WindowArrays& out) {
    for (std::uint32_t i = 0; i < count; ++i) {
        glm::vec4 c;
        for (int r = 0; r < 4; ++r) c[r] = ((m[0][r] * px[i] + m[1][r] * py[i]) + m[2][r] * pz[i]) + m[3][r];
        const float oow = 1.0f / c.w;
        const float nx = c.x * oow, ny = c.y * oow, nz = c.z * oow;
        if constexpr (kFused) {
            out.x[i] = std::fma(nx, vp.sx, vp.tx);
            out.y[i] = std::fma(ny, vp.sy, vp.ty);
            out.z[i] = std::fma(nz, vp.sz, vp.tz);
        } else {
            out.x[i] = nx * vp.sx + vp.tx;
            out.y[i] = ny * vp.sy + vp.ty;
            out.z[i] = nz * vp.sz + vp.tz;
        }
        std::int64_t fx = 0, fy = 0;
        const bool usable = raster::clipMask(c, vp.halfZ) == 0 && raster::fixedPosition(out.x[i], out.y[i], &fx, &fy);
        out.fx[i] = usable ? std::int32_t(fx) : occlusion::kUnfixed;  // |fx|, |fy| < 2^26
        out.fy[i] = usable ? std::int32_t(fy) : occlusion::kUnfixed;
    }
}

// The fused flavour, compiled for FMA so that std::fma is one instruction (it is called only when
// the CPU has FMA: raster::cpuHasFma()).
#if defined(__x86_64__)
__attribute__((target("fma")))
#endif
void transformFused(const glm::mat4& m, const float* px, const float* py, const float* pz, std::uint32_t count,
                    const raster::Viewport& vp, const occlusion::WindowArrays& out) {
    transformBody<true>(m, px, py, pz, count, vp, out);
}

// Bit k: byte k of the 64 at `flags` (each below 128) is not 0.
inline std::uint64_t keptMask(const std::uint8_t* flags) {
    std::uint64_t m = 0;
#if defined(__x86_64__)
    for (int q = 0; q < 4; ++q) {
        const __m128i bytes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(flags + 16 * q));
        const int bits = _mm_movemask_epi8(_mm_cmpgt_epi8(bytes, _mm_setzero_si128()));
        m |= std::uint64_t(std::uint32_t(bits)) << (16 * q);
    }
#else
    for (int k = 0; k < 64; ++k) m |= std::uint64_t(flags[k] != 0) << k;
#endif
    return m;
}

// The draws a plan makes on `target`: per instance, one draw() of its ranges (adjacent ones joined,
// as the plan's draw list joins them), which the backend makes one draw, or one per range
// (Backend::RangeGathering). A long plan costs a few tens of microseconds here.
std::int64_t planDraws(const OcclusionTarget& target, const std::vector<KeptCluster>& kept,
                       const std::vector<IndexRange>& ranges) {
    std::int64_t draws = 0;
    for (std::size_t k = 0; k < kept.size();) {
        const std::uint32_t instance = kept[k].instance;
        std::uint64_t runs = 0, triangles = 0;
        std::uint32_t end = std::numeric_limits<std::uint32_t>::max();  // one past the last run's last triangle
        for (; k < kept.size() && kept[k].instance == instance; ++k)
            for (std::uint32_t r = 0; r < kept[k].rangeCount; ++r) {
                const IndexRange& range = ranges[kept[k].firstRange + r];
                if (range.triangleCount == 0) continue;
                if (range.firstTriangle != end) ++runs;
                end = range.firstTriangle + range.triangleCount;
                triangles += range.triangleCount;
            }
        draws += std::int64_t(target.gathering.drawsOf(runs, triangles));
    }
    return draws;
}

}  // namespace

struct OcclusionCuller::State {
    OcclusionStats stats;
    int width = 0, height = 0, blocksX = 0, blocksY = 0;
    bool halfZ = false;
    raster::Viewport viewport;
    bool fused = raster::cpuHasFma();
    bool avx2 = occlusion::cpuHasAvx2();  // and simd: the AVX2 loops
    bool simd = true;
    // And the quick test looks the corners up with AVX-512 permutes (clusters of at most 64 vertices).
    bool avx512 = occlusion::cpuHasAvx512();
    bool lookups = true;
    bool exactRules = true;  // the draw rasterizes by llvmpipe's rules: triangles are tested one by one
    int backOff = 0, skipLeft = 0;  // calls to skip after passes that did not pay
    std::size_t failedPlanned = 0;  // the plan's triangles in the last pass that did not pay
    std::size_t lastPlanned = 0;    // the plan's triangles in the last call
    bool warm = false;              // prepare() woke the threads, which spin until run() ends
    // Far-ness: window depth for D24 (0 near), its negation for D32F (reversed: 1 near), so that
    // "nearer" is "smaller" for both. depth: per pixel (row 0 at the bottom, window y), an upper
    // bound of what the frame's depth buffer ends with; blockMax: per block, the farthest of those.
    std::vector<float> depth, blockMax;
    std::vector<std::uint8_t> blockDirty;
    std::size_t maxVertices = 0;  // of a cluster of any mesh walked, rounded up to 8, and 8 more
    std::vector<Item> items;               // the kept clusters, nearest first
    std::vector<std::uint32_t> slots;      // per item: its first triangle slot (and one past the last)
    std::vector<Band> bands;
    std::vector<Piece> pieces;             // the plan, gathered piece by piece (gather)
    std::unique_ptr<ThreadPool> threads;
    // For one thread (occlusion-ahead's pass, beside the draw): the caller alone, kept apart so that
    // alternating with the pass on every core does not start and stop the other pool's threads.
    std::unique_ptr<ThreadPool> single;

    // The threads prepare() woke go back to sleep.
    void rest() {
        if (warm && threads) threads->rest();
        warm = false;
    }

    // The walk's threads: `count`, or every core (at most 8) for 0.
    ThreadPool& pool(int count) {
        // (hardware_concurrency() reads a file on Linux: tens of microseconds, asked once.)
        static const int cores = int(std::clamp(std::thread::hardware_concurrency(), 1u, 8u));
        const int wanted = count > 0 ? std::min(count, 64) : cores;
        if (wanted == 1) {
            if (!single) single = std::make_unique<ThreadPool>(1);
            return *single;
        }
        if (!threads || threads->size() != wanted) threads = std::make_unique<ThreadPool>(wanted);
        return *threads;
    }

    // One band per thread, split where the clusters' triangles (by the middle row of their
    // rectangles) are shared out evenly, on block boundaries.
    void splitBands(int threadCount) {
        const int count = std::min(pool(threadCount).size(), blocksY);
        bands.resize(std::size_t(count));
        std::vector<double> rowWeight(std::size_t(blocksY), 0.0);
        double total = 0.0;
        for (std::size_t i = 0; i < items.size(); ++i) {
            const Item& it = items[i];
            const double n = double(slots[i + 1] - slots[i]);
            const int row = it.testable && it.y0 <= it.y1 ? ((it.y0 + it.y1) / 2) >> kBlockLog2 : blocksY / 2;
            rowWeight[std::size_t(std::clamp(row, 0, blocksY - 1))] += n;
            total += n;
        }
        int row = 0;
        double sum = 0.0;
        for (int b = 0; b < count; ++b) {
            Band& band = bands[std::size_t(b)];
            band.y0 = row * kBlock;
            const double goal = total * double(b + 1) / double(count);
            // At least one block row each, and room left for the bands after this one.
            int end = row + 1;
            sum += rowWeight[std::size_t(row)];
            while (end < blocksY - (count - 1 - b) && sum < goal) sum += rowWeight[std::size_t(end++)];
            if (b == count - 1) end = blocksY;
            band.y1 = std::min(end * kBlock, height) - 1;
            row = end;
            band.seen.assign(slots.back() + 64, 0);  // 64 more: keptMask reads 64 flags at a time
        }
    }

    // Walks every item for `band`: a testable cluster whose rectangle misses the band, or is hidden
    // within it, is skipped (its flags stay 0); otherwise each triangle is tested (and occludes) on
    // the band's rows. Equal to one walk over the whole screen: a band sees a triangle exactly when
    // the whole screen does at some pixel of the band, and a triangle that a band does not see
    // writes nothing there (every pixel it covers already holds something nearer).
    void walk(const Walk& w, Band& band) {
        std::fill(depth.begin() + std::ptrdiff_t(band.y0) * width, depth.begin() + std::ptrdiff_t(band.y1 + 1) * width, kOpen);
        band.reserve(maxVertices, 0);
        for (std::size_t i = 0; i < items.size(); ++i) {
            const Item& it = items[i];
            if (it.testable && (it.x0 > it.x1 || it.y1 < band.y0 || it.y0 > band.y1 || hidden(it, band))) continue;
            const Instance& instance = w.scene.instances[w.kept[it.kept].instance];
            const Mesh& mesh = w.scene.meshes[std::size_t(instance.mesh)];
            const bool singleSided = mesh.material < 0 || !w.scene.materials[std::size_t(mesh.material)].doubleSided;
            // A masked or blended surface hides nothing (a discarded or blended fragment shows what
            // is behind it): tested, never written.
            const bool occluder =
                mesh.material < 0 || w.scene.materials[std::size_t(mesh.material)].alphaMode == AlphaMode::Opaque;
            const ClusterVertices& cv = w.maps[std::size_t(instance.mesh)].vertices;
            const glm::mat4 m = w.viewProjection * w.world[std::size_t(instance.node)];
            std::uint32_t slot = slots[i];
            for (std::uint32_t k = it.kept; k < it.kept + it.count; ++k)
                slot = walkCluster(w, band, cv, m, w.kept[k], singleSided, occluder, slot);
        }
    }

    // Kept cluster `kc` (of mesh vertices `cv`, under `m`) of an item that `band` does not find
    // hidden: each triangle tested (and occluding) on the band's rows, its flags from `slot` on.
    // Returns the slot after its triangles.
    std::uint32_t walkCluster(const Walk& w, Band& band, const ClusterVertices& cv, const glm::mat4& m,
                              const KeptCluster& kc, bool singleSided, bool occluder, std::uint32_t slot) {
        const std::uint32_t firstVertex = cv.firstVertex[kc.cluster];
        const std::uint32_t vertexCount = cv.firstVertex[kc.cluster + 1] - firstVertex;
        const occlusion::WindowArrays window = band.window();
        transform(m, &cv.x[firstVertex], &cv.y[firstVertex], &cv.z[firstVertex], vertexCount, window);
        for (std::uint32_t r = 0; r < kc.rangeCount; ++r) {
            const IndexRange& range = w.ranges[kc.firstRange + r];
            const std::uint32_t first = range.firstTriangle, count = range.triangleCount;
            // The quick verdict of every triangle; kTest ones are then tested in full. A triangle
            // with a corner the draw clips is drawn from rounded new vertices: kept, and hides
            // nothing. Without llvmpipe's rules every triangle is kept, and occludes.
            band.reserve(0, count + 64);  // keptMask reads 64 verdicts at a time
            std::uint8_t* verdict = band.verdict.data();
            if (simd && lookups && vertexCount <= occlusion::kLookupVertices)
                occlusion::verdictsAvx512(window, &cv.c0[first], &cv.c1[first], &cv.c2[first], count, singleSided,
                                          viewport, band.y0, band.y1, verdict, band.small());
            else if (simd)
                occlusion::verdictsAvx2(window, &cv.c0[first], &cv.c1[first], &cv.c2[first], count, singleSided,
                                        viewport, band.y0, band.y1, verdict, band.small());
            else
                for (std::uint32_t t = 0; t < count; ++t) {
                    const std::uint32_t a = cv.c0[first + t], b = cv.c1[first + t], c = cv.c2[first + t];
                    const bool unfixed = window.fx[a] == occlusion::kUnfixed || window.fx[b] == occlusion::kUnfixed ||
                                         window.fx[c] == occlusion::kUnfixed;
                    verdict[t] = unfixed ? occlusion::kKeep : occlusion::kTest;
                }
            // Dropped triangles (about half) are skipped 64 at a time, by the bits of the others:
            // a branch a triangle on whether it was dropped is one the CPU cannot predict.
            const occlusion::SmallTriangles small = band.small();
            if (!occluder) std::memset(small.occludes, 0, count);
            std::uint8_t* seenOut = &band.seen[slot];
            std::memset(seenOut, exactRules ? 0 : 1, count);
            for (std::uint32_t base = 0; base < count; base += 64) {
                std::uint64_t bits = keptMask(verdict + base);  // verdicts other than kDrop
                if (count - base < 64) bits &= (std::uint64_t(1) << (count - base)) - 1;
                for (; bits != 0; bits &= bits - 1) {
                    const std::uint32_t t = base + std::uint32_t(__builtin_ctzll(bits));
                    bool seen = verdict[t] == occlusion::kKeep;
                    if (verdict[t] == occlusion::kTest)
                        seen = triangleMaySeen(window, cv.c0[first + t], cv.c1[first + t], cv.c2[first + t],
                                               singleSided, occluder, band.y0, band.y1);
                    else if (verdict[t] == occlusion::kSmall)
                        seen = smallMaySeen(small, t);
                    else if (verdict[t] == occlusion::kMedium)
                        seen = mediumMaySeen(small, t);
                    seenOut[t] = std::uint8_t(seen || !exactRules);
                }
            }
            slot += count;
        }
        return slot;
    }

    // Bit k: some band may see (or must keep) the triangle in slot `slot` + k.
    std::uint64_t seenMask(std::size_t slot) const {
        std::uint64_t m = 0;
#if defined(__x86_64__)
        for (int q = 0; q < 4; ++q) {
            __m128i any = _mm_setzero_si128();
            for (const Band& band : bands)
                any = _mm_or_si128(any, _mm_loadu_si128(reinterpret_cast<const __m128i*>(&band.seen[slot + 16 * std::size_t(q)])));
            const int bits = _mm_movemask_epi8(_mm_cmpgt_epi8(any, _mm_setzero_si128()));
            m |= std::uint64_t(std::uint32_t(bits)) << (16 * q);
        }
#else
        for (const Band& band : bands) m |= keptMask(&band.seen[slot]);
#endif
        return m;
    }

    // Piece p of the items: the runs of their triangles that some band kept, into pieces[p], and
    // each one's entry of `result` (its firstRange counted from the piece's first range).
    void gather(const std::vector<KeptCluster>& kept, const std::vector<IndexRange>& ranges, std::size_t p,
                std::vector<KeptCluster>& result) {
        Piece& piece = pieces[p];
        piece.ranges.clear();
        piece.tested = piece.hidden = piece.triangles = 0;
        std::vector<IndexRange>& out = piece.ranges;
        for (std::size_t i = p * kPieceItems; i < std::min(items.size(), (p + 1) * kPieceItems); ++i) {
            const Item& it = items[i];
            std::uint32_t slot = slots[i];
            for (std::uint32_t k = it.kept; k < it.kept + it.count; ++k) {
                const KeptCluster& kc = kept[k];
                KeptCluster& kr = result[k];
                kr = kc;
                kr.firstRange = std::uint32_t(out.size());
                kr.rangeCount = 0;
                if (it.testable) ++piece.tested;
                std::uint32_t runStart = 0, runLength = 0;
                for (std::uint32_t r = 0; r < kc.rangeCount; ++r) {
                    const IndexRange& range = ranges[kc.firstRange + r];
                    // The runs of kept triangles, 64 flags at a time; a run that continues the last
                    // one (across words or ranges) extends it.
                    for (std::uint32_t base = 0; base < range.triangleCount; base += 64) {
                        std::uint64_t m = seenMask(slot + base);
                        if (range.triangleCount - base < 64) m &= (std::uint64_t(1) << (range.triangleCount - base)) - 1;
                        forEachRun(m, [&](std::uint32_t at, std::uint32_t length) {
                            const std::uint32_t t = range.firstTriangle + base + at;
                            if (runLength > 0 && runStart + runLength == t) {
                                runLength += length;
                                return;
                            }
                            if (runLength > 0) out.push_back({runStart, runLength}), ++kr.rangeCount;
                            runStart = t;
                            runLength = length;
                        });
                    }
                    slot += range.triangleCount;
                }
                if (runLength > 0) out.push_back({runStart, runLength}), ++kr.rangeCount;
                if (kr.rangeCount == 0) ++piece.hidden;
                for (std::uint32_t r = 0; r < kr.rangeCount; ++r) piece.triangles += out[kr.firstRange + r].triangleCount;
            }
        }
    }

    // The box [boxMin, boxMax] under `mvp` (the float product of the view-projection and the
    // instance's world matrix, in double) on the screen: `it`'s pixels it may reach and nearest
    // far-ness.
    void boxOnScreen(const glm::vec3& boxMin, const glm::vec3& boxMax, const glm::dmat4& mvp, Item& it) const {
        // Bound of the float vertex transform's error per clip coordinate: four rounded terms.
        const glm::dvec3 reach = glm::max(glm::abs(glm::dvec3(boxMin)), glm::abs(glm::dvec3(boxMax)));
        double err[4];
        for (int r = 0; r < 4; ++r)
            err[r] = 4.0 * kUnit *
                     (std::abs(mvp[0][r]) * reach.x + std::abs(mvp[1][r]) * reach.y + std::abs(mvp[2][r]) * reach.z +
                      std::abs(mvp[3][r]));
        double xMin = INFINITY, xMax = -INFINITY, yMin = INFINITY, yMax = -INFINITY, zMin = INFINITY, zMax = -INFINITY;
        double wMin = INFINITY;
        bool testable = true;
        for (int corner = 0; corner < 8 && testable; ++corner) {
            const glm::dvec3 p(corner & 1 ? boxMax.x : boxMin.x, corner & 2 ? boxMax.y : boxMin.y,
                               corner & 4 ? boxMax.z : boxMin.z);
            const glm::dvec4 q = mvp * glm::dvec4(p, 1.0);
            // In front of the near plane by more than the rounding of both sides.
            const double nearSide = halfZ ? q.z - err[2] : q.z + q.w - err[2] - err[3];
            if (!std::isfinite(q.x + q.y + q.z + q.w) || !(q.w - err[3] > 0.0) || !(nearSide > 0.0)) testable = false;
            xMin = std::min(xMin, q.x / q.w), xMax = std::max(xMax, q.x / q.w);
            yMin = std::min(yMin, q.y / q.w), yMax = std::max(yMax, q.y / q.w);
            zMin = std::min(zMin, q.z / q.w), zMax = std::max(zMax, q.z / q.w);
            wMin = std::min(wMin, q.w);
        }
        if (testable) {
            // x/w, y/w, z/w of a vertex inside the box lie between the corners' (a ratio of affine
            // functions over a box takes its extremes at corners); the float transform moves them by
            // at most (e + |ratio|·e_w)/w_float, w_float ≥ wMin − e_w > 0, and the division and the
            // viewport by a few units more.
            const double ratio = std::max({1.0, std::abs(xMin), std::abs(xMax), std::abs(yMin), std::abs(yMax),
                                           std::abs(zMin), std::abs(zMax)});
            const double wLow = wMin - err[3];
            const double ex = (err[0] + ratio * err[3]) / wLow + 4.0 * kUnit * ratio;
            const double ey = (err[1] + ratio * err[3]) / wLow + 4.0 * kUnit * ratio;
            const double ez = (err[2] + ratio * err[3]) / wLow + 4.0 * kUnit * ratio;
            // Window pixels whose centre the box may cover, grown by one pixel.
            const double wx0 = (xMin - ex) * viewport.sx + viewport.tx - 1.0, wx1 = (xMax + ex) * viewport.sx + viewport.tx + 1.0;
            const double wy0 = (yMin - ey) * viewport.sy + viewport.ty - 1.0, wy1 = (yMax + ey) * viewport.sy + viewport.ty + 1.0;
            it.x0 = std::int32_t(std::clamp(std::ceil(wx0 - 0.5), 0.0, double(width)));
            it.x1 = std::int32_t(std::clamp(std::floor(wx1 - 0.5), -1.0, double(width - 1)));
            it.y0 = std::int32_t(std::clamp(std::ceil(wy0 - 0.5), 0.0, double(height)));
            it.y1 = std::int32_t(std::clamp(std::floor(wy1 - 0.5), -1.0, double(height - 1)));
            // The nearest window depth a fragment may get, less its rounding and the 24-bit step.
            const double slack = 4.0 * kUnit;
            const double nearest = halfZ ? -(zMax + ez) - slack : 0.5 * (zMin - ez) + 0.5 - slack;
            it.nearest = float(nearest) - float(2.0 * kUnit);
            it.testable = std::isfinite(nearest);
        }
    }

    void reset(int w, int h, DepthFormat format) {
        width = w;
        height = h;
        halfZ = format == DepthFormat::D32F;
        viewport = raster::makeViewport(w, h, format);
        blocksX = (w + kBlock - 1) / kBlock;
        blocksY = (h + kBlock - 1) / kBlock;
        depth.resize(std::size_t(w) * std::size_t(h));  // each band opens its own rows (walk)
        blockMax.assign(std::size_t(blocksX) * std::size_t(blocksY), kOpen);
        blockDirty.assign(blockMax.size(), 0);
    }

    float farness(float windowZ) const { return halfZ ? -windowZ : windowZ; }

    float block(int bx, int by) {
        const std::size_t b = std::size_t(by) * std::size_t(blocksX) + std::size_t(bx);
        if (blockDirty[b]) {
            const int x0 = bx * kBlock, y0 = by * kBlock;
            const int x1 = std::min(x0 + kBlock, width), y1 = std::min(y0 + kBlock, height);
            float m = -kOpen;
#if defined(__x86_64__)
            if (x1 - x0 == kBlock) {  // a whole row of the block is two SSE registers (no NaN is stored)
                __m128 a = _mm_set1_ps(-kOpen), c = a;
                for (int y = y0; y < y1; ++y) {
                    const float* row = &depth[std::size_t(y) * std::size_t(width) + std::size_t(x0)];
                    a = _mm_max_ps(a, _mm_loadu_ps(row));
                    c = _mm_max_ps(c, _mm_loadu_ps(row + 4));
                }
                a = _mm_max_ps(a, c);
                a = _mm_max_ps(a, _mm_movehl_ps(a, a));
                a = _mm_max_ss(a, _mm_shuffle_ps(a, a, 1));
                m = _mm_cvtss_f32(a);
            } else
#endif
                for (int y = y0; y < y1; ++y) {
                    const float* row = &depth[std::size_t(y) * std::size_t(width)];
                    for (int x = x0; x < x1; ++x) m = std::max(m, row[x]);
                }
            blockMax[b] = m;
            blockDirty[b] = 0;
        }
        return blockMax[b];
    }

    // Every pixel of the item's rectangle within the band holds an occluder strictly nearer than
    // its nearest point.
    bool hidden(const Item& it, const Band& band) {
        const int bx0 = it.x0 >> kBlockLog2, bx1 = it.x1 >> kBlockLog2;
        const int by0 = std::max(it.y0, band.y0) >> kBlockLog2, by1 = std::min(it.y1, band.y1) >> kBlockLog2;
        for (int by = by0; by <= by1; ++by)
            for (int bx = bx0; bx <= bx1; ++bx) {
                if (block(bx, by) < it.nearest) continue;  // the whole block hides it
                // Some pixel of the block is not nearer: look at the pixels the box reaches.
                const int x0 = std::max(it.x0, bx * kBlock), x1 = std::min(it.x1, bx * kBlock + kBlock - 1);
                const int y0 = std::max({it.y0, band.y0, by * kBlock}), y1 = std::min({it.y1, band.y1, by * kBlock + kBlock - 1});
                for (int y = y0; y <= y1; ++y) {
                    const float* row = &depth[std::size_t(y) * std::size_t(width)];
                    for (int x = x0; x <= x1; ++x)
                        if (!(row[x] < it.nearest)) return false;
                }
            }
        return true;
    }

    // The window positions of `count` vertices under `m`, as the software backend's vertex stage
    // computes them (Kernels.inl transform; Rasterizer.h 1.), the viewport fused where it fuses.
    void transform(const glm::mat4& m, const float* px, const float* py, const float* pz, std::uint32_t count,
                   const occlusion::WindowArrays& out) const {
        if (simd)
            occlusion::transformAvx2(&m[0][0], px, py, pz, count, viewport, out);
        else if (fused)
            transformFused(m, px, py, pz, count, viewport, out);
        else
            transformBody<false>(m, px, py, pz, count, viewport, out);
    }

    // One triangle of a cluster that may be seen, as llvmpipe rasterizes it (Rasterizer.h 3. and 5.):
    // it owns no pixel centre, or every pixel it covers already holds an occluder strictly nearer
    // (false: drop it), or it may own a pixel (true: keep it; it then occludes, unless the draw
    // module may drop it, 2a.).
    // Whether a triangle set up as `t` (its edges and bounds) covers a pixel centre in rows
    // [rowLo, rowHi]: every k − dx·px + dy·py ≥ 0, i.e. their OR is not negative.
    static bool coversPixel(const raster::Triangle& t, int rowLo, int rowHi) {
        const std::int64_t x0 = t.x0, x1 = t.x1, y0 = std::max(t.y0, rowLo), y1 = std::min(t.y1, rowHi);
        if (y0 > y1) return false;
        std::int64_t e00[3], ex[3], ey[3];
        for (int i = 0; i < 3; ++i) {
            ex[i] = t.e[i].dx;
            ey[i] = t.e[i].dy;
            e00[i] = t.e[i].k - ex[i] * x0 + ey[i] * y0;
        }
        // Most triangles of a dense mesh span at most 2 × 2 pixel centres: decided without a
        // branch a pixel (whether one is covered is a coin toss the branch predictor loses).
        if (x1 - x0 <= 1 && y1 - y0 <= 1) {
            const std::int64_t m00 = e00[0] | e00[1] | e00[2];
            const std::int64_t m10 = (e00[0] - ex[0]) | (e00[1] - ex[1]) | (e00[2] - ex[2]);
            const std::int64_t m01 = (e00[0] + ey[0]) | (e00[1] + ey[1]) | (e00[2] + ey[2]);
            const std::int64_t m11 =
                (e00[0] - ex[0] + ey[0]) | (e00[1] - ex[1] + ey[1]) | (e00[2] - ex[2] + ey[2]);
            const bool right = x1 > x0, up = y1 > y0;
            return (m00 >= 0) | (right & (m10 >= 0)) | (up & (m01 >= 0)) | (right & up & (m11 >= 0));
        }
        for (std::int64_t py = y0; py <= y1; ++py) {
            std::int64_t e[3];
            for (int i = 0; i < 3; ++i) e[i] = e00[i] + ey[i] * (py - y0);
            for (std::int64_t px = x0; px <= x1; ++px) {
                if ((e[0] | e[1] | e[2]) >= 0) return true;
                for (int i = 0; i < 3; ++i) e[i] -= ex[i];
            }
        }
        return false;
    }

    // The edges of `t` at pixel (t.x0, y0) and their steps, for occlusion::narrowAvx2: false when a
    // value at a corner of columns t.x0 … t.x0 + 7 and rows y0 … y1 is not within ±2^30.
    static bool narrowEdges(const raster::Triangle& t, int y0, int y1, std::int32_t e00[3], std::int32_t ex[3],
                            std::int32_t ey[3]) {
        constexpr std::int64_t kLimit = std::int64_t(1) << 30;
        const auto fits = [](std::int64_t v) { return v > -kLimit && v < kLimit; };
        for (int i = 0; i < 3; ++i) {
            const std::int64_t dx = t.e[i].dx, dy = t.e[i].dy;
            const std::int64_t e = t.e[i].k - dx * t.x0 + dy * y0, right = e - 7 * dx, up = dy * (y1 - y0);
            if (!fits(e) || !fits(right) || !fits(e + up) || !fits(right + up)) return false;
            e00[i] = std::int32_t(e), ex[i] = std::int32_t(dx), ey[i] = std::int32_t(dy);
        }
        return true;
    }

    // The blocks of rows [y0, y1] and of the columns x0 + i of bit i of `columns` are dirty (a block
    // marked where nothing was lowered is only read again).
    void markColumns(int x0, int y0, int y1, std::uint32_t columns) {
        if (columns == 0) return;
        const int bx0 = (x0 + __builtin_ctz(columns)) >> kBlockLog2, bx1 = (x0 + 31 - __builtin_clz(columns)) >> kBlockLog2;
        std::uint8_t* dirty = blockDirty.data();  // (a byte store may alias the vector's own fields)
        const auto stride = std::size_t(blocksX);
        for (int by = y0 >> kBlockLog2; by <= y1 >> kBlockLog2; ++by)
            for (int bx = bx0; bx <= bx1; ++bx) dirty[std::size_t(by) * stride + std::size_t(bx)] = 1;
    }

    // Triangle t of a batch the quick test called kMedium: tested and written as triangleMaySeen
    // does (its narrow path), with the edges and plane the quick test computed as setup computes them.
    bool mediumMaySeen(const occlusion::SmallTriangles& small, std::uint32_t t) {
        const std::size_t stride = small.stride;
        std::int32_t e[3], ex[3], ey[3];
        for (std::size_t k = 0; k < 3; ++k) {
            e[k] = small.edge[k * stride + t];
            ex[k] = small.edge[(3 + k) * stride + t];
            ey[k] = small.edge[(6 + k) * stride + t];
        }
        const int x0 = small.x0[t], y0 = small.y0[t];
        const bool occludes = small.occludes[t] != 0;
        std::uint32_t columns = 0;
        const bool seen = occlusion::narrowAvx2(depth.data(), width, x0, small.x1[t], y0, small.y1[t], e, ex, ey,
                                                small.plane[t], small.plane[stride + t], small.plane[2 * stride + t],
                                                small.plane[3 * stride + t], float(2.0 * kUnit), halfZ, occludes, &columns);
        if (occludes) markColumns(x0, y0, small.y1[t], columns);
        return seen;
    }

    // Triangle t of a batch the quick test called kSmall: its covered pixels tested and written as
    // triangleMaySeen does, with the bounds the quick test computed as it computes them.
    bool smallMaySeen(const occlusion::SmallTriangles& small, std::uint32_t t) {
        const int x0 = small.x0[t], y0 = small.y0[t];
        const unsigned covered = small.covered[t];
        const bool occludes = small.occludes[t] != 0;
        bool seen = false;
        for (unsigned k = 0; k < 4; ++k) {
            if (!(covered & (1u << k))) continue;
            const int px = x0 + int(k & 1u), py = y0 + int(k >> 1);
            float& stored = depth[std::size_t(py) * std::size_t(width) + std::size_t(px)];
            seen = seen || !(stored < small.lo[k * small.stride + t]);
            if (occludes) {
                stored = std::min(stored, small.hi[k * small.stride + t]);
                blockDirty[std::size_t(py >> kBlockLog2) * std::size_t(blocksX) + std::size_t(px >> kBlockLog2)] = 1;
            }
        }
        return seen;
    }

    // The triangle with corners a, b, c of `w` (none kUnfixed).
    bool triangleMaySeen(const occlusion::WindowArrays& w, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                         bool singleSided, bool occluder, int rowLo, int rowHi) {
        // Setup's fixed-point part (Rasterizer.h 3.) on the positions kept with the vertices, then
        // the coverage test: most triangles of a dense mesh far away own no pixel centre. The depth
        // plane only for those that cover one.
        // First setup's bounds test alone (no pixel centre within the fixed-point bounds): it drops
        // a fifth of a dense mesh's triangles for a few instructions.
        const std::int32_t minX = std::min({w.fx[a], w.fx[b], w.fx[c]}), maxX = std::max({w.fx[a], w.fx[b], w.fx[c]});
        const std::int32_t minY = std::min({w.fy[a], w.fy[b], w.fy[c]}), maxY = std::max({w.fy[a], w.fy[b], w.fy[c]});
        if (-((-minX) >> 8) > (maxX >> 8) || std::max(-((-minY) >> 8), rowLo) > std::min(maxY >> 8, rowHi)) return false;
        std::int64_t X[3] = {w.fx[a], w.fx[b], w.fx[c]}, Y[3] = {w.fy[a], w.fy[b], w.fy[c]};
        raster::Triangle t;
        const raster::SetupOrder order = raster::setupEdges(X, Y, singleSided, viewport, &t);
        if (order == raster::SetupOrder::Dropped) return false;
        // A triangle at most 8 pixels wide whose edges fit in 32 bits is rasterized 8 pixels a row
        // at once (occlusion::narrowAvx2), which finds no pixel as cheaply as coversPixel does.
        const int ya = std::max(t.y0, rowLo), yb = std::min(t.y1, rowHi);
        std::int32_t e00[3], ex[3], ey[3];
        const bool narrow = simd && t.x1 - t.x0 < 8 && ya <= yb && narrowEdges(t, ya, yb, e00, ex, ey);
        if (!narrow && !coversPixel(t, rowLo, rowHi)) return false;  // no pixel
        // Only the positions are read (drawModuleKeepsFront, setupDepthPlane): the attributes are
        // left unset (zeroing three vertices was a twentieth of the pass).
        raster::SetupVertex s[3];
        const std::uint32_t corner[3] = {a, b, c};
        for (int i = 0; i < 3; ++i) {
            s[i].x = w.x[corner[i]];
            s[i].y = w.y[corner[i]];
            s[i].z = w.z[corner[i]];
            s[i].oow = 1.0f;
        }
        // The draw module's own cull stage may drop a front-facing sliver that setup keeps: such a
        // triangle is kept but hides nothing.
        const bool occludes = occluder && (!singleSided || raster::drawModuleKeepsFront(&s[0], &s[1], &s[2]));
        const raster::SetupVertex* v[3] = {&s[0], &s[1], &s[2]};
        if (order == raster::SetupOrder::Swapped) std::swap(v[0], v[1]);
        raster::setupDepthPlane(v[0], v[1], v[2], &t);
        // llvmpipe's z at pixel (px, py) is fma(dzdy, py, fma(dzdx, px, z0)) in float, clamped to
        // [0, 1] (Rasterizer.h 5.). Here it is (z0 + dzdy·py) + dzdx·px, rounded as it goes;
        // `s0` bounds the distance between the two (occlusion::depthSlack).
        const float s0 = occlusion::depthSlack(t.z0, t.dzdx, t.dzdy, float(width), float(height));
        if (!(s0 < 1.0f)) return narrow ? coversPixel(t, rowLo, rowHi) : true;  // a plane that says nothing
        const float up = float(2.0 * kUnit);
        if (narrow) {
            std::uint32_t columns = 0;
            const bool seen = occlusion::narrowAvx2(depth.data(), width, t.x0, t.x1, ya, yb, e00, ex, ey, t.z0, t.dzdx,
                                                    t.dzdy, s0, up, halfZ, occludes, &columns);
            if (occludes) markColumns(t.x0, ya, yb, columns);
            return seen;
        }
        const float dzdx = t.dzdx;
        bool seen = false;
        // A wide triangle's rows, each edge solved for px (stepped from row to row).
        occlusion::EdgeRows edges[3] = {{t.e[0], ya}, {t.e[1], ya}, {t.e[2], ya}};
        for (int py = ya; py <= yb; ++py) {
            // The row's covered pixels, edge by edge: k − dx·px + dy·py ≥ 0. A narrow triangle
            // tests its few pixels; a wide one takes the bounds of its edges.
            std::int64_t xa = t.x0, xb = t.x1;
            if (t.x1 - t.x0 < 8) {
                const auto inside = [&t, py](std::int64_t px) {
                    std::int64_t m = 0;
                    for (const raster::Edge& e : t.e) m |= e.k - std::int64_t(e.dx) * px + std::int64_t(e.dy) * py;
                    return m >= 0;
                };
                while (xa <= xb && !inside(xa)) ++xa;
                while (xb >= xa && !inside(xb)) --xb;
            } else {
                for (occlusion::EdgeRows& e : edges) {
                    e.bound(xa, xb);
                    e.nextRow();
                }
            }
            if (xa > xb) continue;
            float* row = &depth[std::size_t(py) * std::size_t(width)];
            const float zRow = t.z0 + t.dzdy * float(py);
            // Far-ness bounds of the stored value at each pixel: lo ≤ it ≤ hi (D24 stores the
            // clamped z, D32F is read as its negation).
            bool rowSeen = false;
            if (simd) {  // eight pixels at a time, the same arithmetic
                rowSeen = occlusion::spanAvx2(row, int(xa), int(xb), zRow, dzdx, s0, up, halfZ, occludes);
            } else if (!halfZ) {
                for (std::int64_t px = xa; px <= xb; ++px) {
                    const float z = zRow + dzdx * float(px);
                    const float lo = std::clamp(z - s0, 0.0f, 1.0f), hi = std::min(z + s0, 1.0f) + up;
                    rowSeen = rowSeen || !(row[px] < lo);
                    if (occludes) row[px] = std::min(row[px], hi);
                }
            } else {
                for (std::int64_t px = xa; px <= xb; ++px) {
                    const float z = zRow + dzdx * float(px);
                    const float lo = -std::clamp(z + s0, 0.0f, 1.0f), hi = -std::clamp(z - s0, 0.0f, 1.0f) + up;
                    rowSeen = rowSeen || !(row[px] < lo);
                    if (occludes) row[px] = std::min(row[px], hi);
                }
            }
            seen = seen || rowSeen;
            if (occludes) {
                std::uint8_t* dirty = &blockDirty[std::size_t(py >> kBlockLog2) * std::size_t(blocksX)];
                for (std::int64_t bx = xa >> kBlockLog2; bx <= xb >> kBlockLog2; ++bx) dirty[bx] = 1;
            }
        }
        return seen;
    }
};

OcclusionTarget occlusionTarget(const Backend& backend, const Settings& settings) {
    OcclusionTarget target;
    target.width = settings.width;
    target.height = settings.height;
    target.threads = settings.threads;
    target.exactRules = backend.followsLlvmpipeRules();
    // What a submitted triangle costs the draw, measured on a dense mesh, and a draw on instances of
    // a small one (docs/occlusion.md).
    target.drawNsPerTriangle = backend.name() == "software" ? kSoftwareNsPerTriangle
                               : target.exactRules         ? kLlvmpipeNsPerTriangle
                                                           : kGpuNsPerTriangle;
    target.drawNsPerDraw = backend.name() != "software" && target.exactRules ? kLlvmpipeNsPerDraw : 0.0;
    target.gathering = backend.rangeGathering();
    return target;
}

OcclusionCuller::OcclusionCuller() : state_(std::make_unique<State>()) {}
OcclusionCuller::~OcclusionCuller() = default;
OcclusionCuller::OcclusionCuller(OcclusionCuller&&) noexcept = default;
OcclusionCuller& OcclusionCuller::operator=(OcclusionCuller&&) noexcept = default;

const OcclusionStats& OcclusionCuller::stats() const { return state_->stats; }

void OcclusionCuller::parallel(const OcclusionTarget& target, std::size_t count,
                               const std::function<void(std::size_t, int)>& fn) {
    if (state_->warm)
        state_->pool(target.threads).run(count, fn);
    else
        for (std::size_t i = 0; i < count; ++i) fn(i, 0);
}

int OcclusionCuller::threads(const OcclusionTarget& target) { return state_->pool(target.threads).size(); }

bool OcclusionCuller::prepare(const OcclusionTarget& target) {
    State& st = *state_;
    // Likely skipped: backing off, or the last plan was too small to pay.
    st.warm = !(target.adaptive && (st.skipLeft > 0 || st.lastPlanned < kMinTriangles));
    if (st.warm) st.pool(target.threads).warm(kWarmFor);
    return st.warm;
}

std::uint64_t OcclusionCuller::bytes() const {
    const State& st = *state_;
    std::uint64_t total = st.depth.capacity() * sizeof(float) + st.blockMax.capacity() * sizeof(float) +
                          st.blockDirty.capacity() + st.items.capacity() * sizeof(Item) +
                          st.slots.capacity() * sizeof(std::uint32_t);
    for (const Band& band : st.bands)
        total += band.seen.capacity() + band.verdict.capacity() + band.covered.capacity() + band.occludes.capacity() +
                 (band.x.capacity() + band.y.capacity() + band.z.capacity() + band.lo.capacity() + band.hi.capacity()) *
                     sizeof(float) +
                 (band.fx.capacity() + band.fy.capacity() + band.smallX0.capacity() + band.smallY0.capacity() +
                  band.smallX1.capacity() + band.smallY1.capacity() + band.edge.capacity()) *
                     sizeof(std::int32_t) +
                 band.plane.capacity() * sizeof(float);
    return total;
}

void OcclusionCuller::run(const Scene& scene, const std::vector<MeshMap>& maps, const std::vector<glm::mat4>& world,
                          const View& view, const OcclusionTarget& target, const std::vector<KeptCluster>& kept,
                          const std::vector<IndexRange>& ranges, std::vector<KeptCluster>& result,
                          std::vector<IndexRange>& out) {
    const int width = target.width, height = target.height;
    const bool exactRules = target.exactRules;
    const auto t0 = Clock::now();
    State& st = *state_;
    st.stats = {};
    std::size_t planned = 0;
    for (const IndexRange& r : ranges) planned += r.triangleCount;
    st.lastPlanned = planned;
    // Backing off after a pass that did not pay holds for plans of about that size or smaller: a
    // plan much larger (a view of more, smaller triangles) is tried again.
    const bool backingOff = st.skipLeft > 0 && double(planned) <= kBackOffGrowth * double(st.failedPlanned);
    const bool skip = width <= 0 || height <= 0 || (target.adaptive && (planned < kMinTriangles || backingOff));
    if (skip) {
        st.rest();
        if (target.adaptive && backingOff) --st.skipLeft;
        st.width = st.height = 0;
        result = kept;
        out = ranges;
        st.stats.ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        return;
    }
    st.exactRules = exactRules;
    st.simd = target.simd && st.avx2;
    st.lookups = target.avx512 && st.avx512;
    st.stats.ran = true;
    st.reset(width, height, view.depthFormat);

    const glm::mat4 viewProjection = view.projection * view.view;  // as the backends compute it
    // The bands' room for a cluster's vertices: the largest cluster of a mesh walked, rounded up to 8
    // and 8 more (the AVX2 loops read 8 at a time), and at least 64 (the AVX-512 quick test reads 64
    // of each array).
    st.maxVertices = occlusion::kLookupVertices;
    std::uint32_t lastInstance = std::numeric_limits<std::uint32_t>::max();
    for (const KeptCluster& kc : kept)
        if (kc.instance != lastInstance) {
            lastInstance = kc.instance;
            const ClusterVertices& cv = maps[std::size_t(scene.instances[kc.instance].mesh)].vertices;
            st.maxVertices = std::max(st.maxVertices, (std::size_t(cv.maxVertices) + 7) / 8 * 8 + 8);
        }
    // The items: a cluster each, or an instance of a small mesh whole; then each one's box on the
    // screen (the pixels it may reach and its nearest far-ness), in pieces side by side.
    st.items.clear();
    for (std::uint32_t k = 0; k < kept.size();) {
        Item it{};
        it.kept = k;
        const std::uint32_t instance = kept[k].instance;
        const bool whole = scene.meshes[std::size_t(scene.instances[instance].mesh)].triangleCount() <= kGroupTriangles;
        for (++k; whole && k < kept.size() && kept[k].instance == instance; ++k) ++it.count;
        st.items.push_back(it);
    }
    st.pool(target.threads).run((st.items.size() + kPieceItems - 1) / kPieceItems, [&](std::size_t p, int) {
        std::uint32_t instanceOf = std::numeric_limits<std::uint32_t>::max();
        glm::dmat4 mvp(1.0);
        for (std::size_t i = p * kPieceItems; i < std::min(st.items.size(), (p + 1) * kPieceItems); ++i) {
            Item& it = st.items[i];
            const std::uint32_t instance = kept[it.kept].instance;
            if (instance != instanceOf) {
                const Instance& in = scene.instances[instance];
                mvp = glm::dmat4(viewProjection * world[std::size_t(in.node)]);  // the float product, exactly
                instanceOf = instance;
            }
            const std::vector<Cluster>& clusters = maps[std::size_t(scene.instances[instance].mesh)].clusters;
            glm::vec3 boxMin = clusters[kept[it.kept].cluster].boxMin, boxMax = clusters[kept[it.kept].cluster].boxMax;
            for (std::uint32_t k = it.kept + 1; k < it.kept + it.count; ++k) {
                boxMin = glm::min(boxMin, clusters[kept[k].cluster].boxMin);
                boxMax = glm::max(boxMax, clusters[kept[k].cluster].boxMax);
            }
            st.boxOnScreen(boxMin, boxMax, mvp, it);
        }
    });

    // Nearest first; boxes that cannot be tested first of all (they are drawn, and hide things).
    std::sort(st.items.begin(), st.items.end(), [](const Item& a, const Item& b) {
        if (a.testable != b.testable) return !a.testable;
        return a.nearest < b.nearest;
    });

    // Triangle slots: item i's triangles are [slot[i], slot[i + 1]) of every band's flags.
    st.slots.assign(st.items.size() + 1, 0);
    for (std::size_t i = 0; i < st.items.size(); ++i) {
        std::uint32_t n = 0;
        for (std::uint32_t k = st.items[i].kept; k < st.items[i].kept + st.items[i].count; ++k)
            for (std::uint32_t r = 0; r < kept[k].rangeCount; ++r) n += ranges[kept[k].firstRange + r].triangleCount;
        st.slots[i + 1] = st.slots[i] + n;
    }
    st.splitBands(target.threads);

    // Each band of rows walks every cluster in the order above, with the part of the buffer it owns:
    // what it finds is what one walk over the whole screen finds (State::walk).
    const Walk walk{scene, maps, world, viewProjection, kept, ranges};
    st.pool(target.threads).run(st.bands.size(), [&](std::size_t band, int) { st.walk(walk, st.bands[band]); });

    // A triangle is kept when some band may see it (or must keep it); a cluster with nothing left
    // is hidden. The plan's ranges are gathered in chunks of items side by side, then joined in
    // item order.
    const std::size_t pieceCount = (st.items.size() + kPieceItems - 1) / kPieceItems;
    st.pieces.resize(pieceCount);
    result.assign(kept.size(), KeptCluster{});
    st.pool(target.threads).run(pieceCount, [&](std::size_t p, int) { st.gather(kept, ranges, p, result); });
    out.clear();
    std::size_t left = 0;
    for (std::size_t p = 0; p < pieceCount; ++p) {
        const Piece& piece = st.pieces[p];
        const auto offset = std::uint32_t(out.size());
        for (std::size_t i = p * kPieceItems; i < std::min(st.items.size(), (p + 1) * kPieceItems); ++i)
            for (std::uint32_t k = st.items[i].kept; k < st.items[i].kept + st.items[i].count; ++k)
                result[k].firstRange += offset;
        out.insert(out.end(), piece.ranges.begin(), piece.ranges.end());
        st.stats.clustersTested += piece.tested;
        st.stats.clustersHidden += piece.hidden;
        left += piece.triangles;
    }
    st.rest();
    st.stats.trianglesHidden = planned - left;
    st.stats.ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    // Did it pay? The draw it saved (the triangles and the draws that went, by the target's costs of
    // each) against its own time.
    st.stats.drawsSaved = planDraws(target, kept, ranges) - planDraws(target, result, out);
    st.stats.savedMs =
        (double(st.stats.trianglesHidden) * target.drawNsPerTriangle + double(st.stats.drawsSaved) * target.drawNsPerDraw) * 1e-6;
    if (!target.adaptive) return;
    if (st.stats.savedMs < st.stats.ms) {
        st.backOff = std::min(std::max(1, 2 * st.backOff), kMaxBackOff);
        st.skipLeft = st.backOff;
        st.failedPlanned = planned;
    } else {
        st.backOff = 0;
        st.skipLeft = 0;
    }
}

std::vector<std::uint8_t> OcclusionCuller::image(int& width, int& height) const {
    const State& st = *state_;
    width = st.width;
    height = st.height;
    std::vector<std::uint8_t> rgba(std::size_t(width) * std::size_t(height) * 4);
    // Grey by depth between the nearest and farthest covered pixels: white nearest.
    float lo = kOpen, hi = -kOpen;
    for (float f : st.depth)
        if (f != kOpen) lo = std::min(lo, f), hi = std::max(hi, f);
    const float span = hi > lo ? hi - lo : 1.0f;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float f = st.depth[std::size_t(height - 1 - y) * std::size_t(width) + std::size_t(x)];
            std::uint8_t* px = &rgba[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4];
            if (f == kOpen) {
                px[0] = 40, px[1] = 60, px[2] = 140, px[3] = 255;
            } else {
                const auto g = std::uint8_t(std::lround(235.0f - 200.0f * (f - lo) / span));
                px[0] = px[1] = px[2] = g, px[3] = 255;
            }
        }
    return rgba;
}

}  // namespace frugal
