#include "cull/Culling.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "render/IndexRanges.h"
#include "scene/MeshBuild.h"

namespace frugal {

namespace {

constexpr int kSampleSide = 3;  // a bin's cell is sampled on a 3 × 3 grid of directions
constexpr int kBinSamples = kSampleSide * kSampleSide;

// Relative margins: a test drops something only when it is outside by more than float rounding.
constexpr double kPlaneMargin = 1e-5;
constexpr float kConeMargin = 1e-4f;

struct Plane {
    glm::dvec4 p{0.0};  // a·x + b·y + c·z + d ≥ 0 inside
    double eval(const glm::dvec3& x) const { return p.x * x.x + p.y * x.y + p.z * x.z + p.w; }
};

// At most six planes, in place (an instance's view is made per instance and frame: no allocation).
struct Planes {
    std::array<Plane, 6> at;
    std::size_t count = 0;
    const Plane* begin() const { return at.data(); }
    const Plane* end() const { return at.data() + count; }
};

// The six clip planes (-w ≤ x, y ≤ w; -w ≤ z ≤ w for D24, 0 ≤ z ≤ w for D32F's zero-to-one clip
// space) of `m` (clip = m · point) in the point's space (Gribb & Hartmann). A plane with no normal
// (the far plane of an infinite projection) is dropped when it holds everywhere.
Planes clipPlanes(const glm::dmat4& m, DepthFormat format) {
    auto row = [&m](int i) { return glm::dvec4(m[0][i], m[1][i], m[2][i], m[3][i]); };
    const glm::dvec4 r0 = row(0), r1 = row(1), r2 = row(2), r3 = row(3);
    const glm::dvec4 zLow = format == DepthFormat::D32F ? r2 : r3 + r2;
    Planes planes;
    for (const glm::dvec4& p : {r3 + r0, r3 - r0, r3 + r1, r3 - r1, zLow, r3 - r2}) {
        const double n = glm::length(glm::dvec3(p));
        if (n == 0.0 && p.w >= 0.0) continue;
        planes.at[planes.count++] = Plane{p};
    }
    return planes;
}

// The part of a box outside one plane, all of it or some of it.
enum class Side { Outside, Straddles, Inside };

Side boxSide(const Planes& planes, const glm::vec3& lo, const glm::vec3& hi) {
    const glm::dvec3 dlo(lo), dhi(hi);
    if (!std::isfinite(dlo.x + dlo.y + dlo.z + dhi.x + dhi.y + dhi.z)) return Side::Straddles;
    bool inside = true;
    // Size of the numbers a plane test adds up, for its margin: |n|₁·|corner|∞ + |d| bounds every term.
    const double extent = std::max({std::abs(dlo.x), std::abs(dlo.y), std::abs(dlo.z), std::abs(dhi.x), std::abs(dhi.y),
                                    std::abs(dhi.z)});
    for (const Plane& plane : planes) {
        const glm::dvec3 n(plane.p);
        // The corner farthest along the normal, and the nearest.
        const glm::dvec3 far(n.x >= 0 ? dhi.x : dlo.x, n.y >= 0 ? dhi.y : dlo.y, n.z >= 0 ? dhi.z : dlo.z);
        const glm::dvec3 near(n.x >= 0 ? dlo.x : dhi.x, n.y >= 0 ? dlo.y : dhi.y, n.z >= 0 ? dlo.z : dhi.z);
        const double scale = (std::abs(n.x) + std::abs(n.y) + std::abs(n.z)) * extent + std::abs(plane.p.w);
        if (plane.eval(far) < -kPlaneMargin * scale) return Side::Outside;
        if (plane.eval(near) < kPlaneMargin * scale) inside = false;
    }
    return inside ? Side::Inside : Side::Straddles;
}

// What a frame looks like from one instance's object space.
struct InstanceView {
    glm::dmat4 mvp{1.0};
    Planes planes;              // clip planes in object space
    glm::dvec4 eye{0.0};        // homogeneous: (eye, 1) for perspective, (towards the viewer, 0) for ortho
    bool mirrored = false;      // window-space winding is the opposite of object space
    double eyeScale = 0.0;      // |eye.xyz|: the size of the numbers in the cone tests (their margin)
    // The facing test of a triangle's plane (unit normal n, n·a = d), in float: f = n·eye.xyz − d·eye.w
    // is > 0 when it faces the eye. It may be drawn when sign·f > −(marginBase + marginPerD·|d|): the
    // margin (1e-5 of the numbers' size) is far above float rounding (≈1e-7), and never 0, so that a
    // degenerate plane (n = 0, d = 0) stays undecided, hence kept.
    glm::vec4 eyeFloat{0.0f};
    float facingSign = 1.0f;    // −1 when mirrored
    float marginBase = 0.0f, marginPerD = 0.0f;

    InstanceView(const glm::mat4& model, const View& view) {
        // The frustum of the given planes (render/Camera.h): the fit moves them only where no
        // triangle is, so every triangle is inside both or neither; paper 002's sphere tests, which
        // look at the bounding sphere and not the triangles, keep their classes and bins this way.
        const glm::dmat4 m(model), v(view.view), p(view.givenProjection);
        mvp = p * v * m;
        planes = clipPlanes(mvp, view.depthFormat);
        const glm::dmat4 toObject = glm::inverse(v * m);
        eye = toObject * (view.perspective ? glm::dvec4(0, 0, 0, 1) : glm::dvec4(0, 0, 1, 0));
        if (!view.perspective) eye = glm::dvec4(glm::normalize(glm::dvec3(eye)), 0.0);
        const double det = glm::determinant(glm::dmat3(v * m));
        mirrored = (det < 0.0) != (p[0][0] * p[1][1] < 0.0);
        eyeScale = glm::length(glm::dvec3(eye));
        eyeFloat = glm::vec4(eye);
        facingSign = mirrored ? -1.0f : 1.0f;
        marginBase = float(kPlaneMargin * (eye.w != 0.0 ? eyeScale : 1.0)) + 1e-30f;
        marginPerD = eye.w != 0.0 ? float(kPlaneMargin) : 0.0f;
    }

    // Cone tests for a whole cluster: every triangle faces away (cullable), or every one faces the
    // eye (no per-triangle test needed).
    bool coneAway(const Cluster& c, bool towardEye) const {
        // No cone, no bound, or no axis (meshoptimizer gives a zero axis when every normal underflows).
        if (!(c.coneCutoff < 1.0f) || !std::isfinite(c.radius) || !(glm::dot(c.coneAxis, c.coneAxis) > 0.5f))
            return false;
        // Faces away (not mirrored): dot(center − e, axis) ≥ cutoff·|center − e| + radius; the
        // opposite side uses −axis. Mirroring swaps which side GL draws.
        const bool flip = towardEye != mirrored;
        const glm::dvec3 axis = glm::dvec3(c.coneAxis) * (flip ? -1.0 : 1.0);
        const double cutoff = std::min(double(c.coneCutoff) + kConeMargin, 1.0);
        if (eye.w != 0.0) {
            const glm::dvec3 toCenter = glm::dvec3(c.center) - glm::dvec3(eye);
            const double distance = glm::length(toCenter);
            return glm::dot(toCenter, axis) >= cutoff * distance + double(c.radius) * (1.0 + kConeMargin) +
                                                    kPlaneMargin * (distance + eyeScale);
        }
        // Orthographic: the view direction is −eye.
        return glm::dot(-glm::dvec3(eye), axis) >= cutoff;
    }
};

// Builds one instance's ranges, merging runs that touch.
struct RangeList {
    std::vector<IndexRange> ranges;
    void add(std::uint32_t first, std::uint32_t count) {
        if (count == 0) return;
        if (!ranges.empty() && ranges.back().firstTriangle + ranges.back().triangleCount == first)
            ranges.back().triangleCount += count;
        else
            ranges.push_back({first, count});
    }
};

// Per vertex of one instance, which clip planes it is outside of (bit k: plane k of -w ≤ x, y, z ≤ w),
// by more than rounding; computed on first use. A triangle whose three vertices share a bit lies
// wholly outside that plane and cannot own a pixel.
class Outcodes {
public:
    Outcodes(const Mesh& mesh, const glm::dmat4& mvp) : Outcodes(mesh, mvp, own_) {}
    // Kept in `cache` (reused from instance to instance without clearing).
    Outcodes(const Mesh& mesh, const glm::dmat4& mvp, SceneCuller::OutcodeCache& cache)
        : mesh_(mesh), mvp_(mvp), cache_(cache) {
        const std::size_t n = mesh.positions.size();
        if (cache_.codes.size() < n) cache_.codes.resize(n), cache_.epochOf.resize(n, 0);
        if (++cache_.epoch == 0) {  // wrapped: every stamp is stale again
            std::fill(cache_.epochOf.begin(), cache_.epochOf.end(), 0u);
            cache_.epoch = 1;
        }
    }

    std::uint8_t operator[](std::uint32_t v) {
        if (cache_.epochOf[v] != cache_.epoch) {
            cache_.epochOf[v] = cache_.epoch;
            cache_.codes[v] = compute(mesh_.positions[v]);
        }
        return cache_.codes[v];
    }

private:
    std::uint8_t compute(const glm::vec3& p) const {
        const glm::dvec4 c = mvp_ * glm::dvec4(glm::dvec3(p), 1.0);
        if (!std::isfinite(c.x + c.y + c.z + c.w)) return 0;  // not a number: outside of nothing, kept
        auto out = [](double x, double w) { return x + w < -kPlaneMargin * (std::abs(x) + std::abs(w)); };
        std::uint8_t code = 0;
        for (int axis = 0; axis < 3; ++axis) {
            if (out(c[axis], c.w)) code |= std::uint8_t(1u << (2 * axis));
            if (out(-c[axis], c.w)) code |= std::uint8_t(2u << (2 * axis));
        }
        return code;
    }

    const Mesh& mesh_;
    glm::dmat4 mvp_;
    SceneCuller::OutcodeCache own_;
    SceneCuller::OutcodeCache& cache_;
};

bool isSingleSided(const Scene& scene, const Mesh& mesh) {
    return mesh.material < 0 || !scene.materials[std::size_t(mesh.material)].doubleSided;
}

// The exact per-triangle tests over [first, first + count): frustum (unless `inside`) and facing
// (when `singleSided`).
void testTriangles(const Mesh& mesh, const MeshMap& map, const InstanceView& iv, Outcodes& vertices,
                   std::uint32_t first, std::uint32_t count, bool inside, bool singleSided, RangeList& out) {
    // Facing first, a batch of triangles at a time in one loop that vectorizes (InstanceView's test).
    constexpr std::uint32_t kBatch = 128;
    std::uint8_t facing[kBatch];
    const glm::vec4 e = iv.eyeFloat;
    const float sign = iv.facingSign, m0 = iv.marginBase, m1 = iv.marginPerD;
    std::uint32_t runStart = first, runLength = 0;
    for (std::uint32_t batch = first; batch < first + count; batch += kBatch) {
        const std::uint32_t n = std::min(kBatch, first + count - batch);
        const glm::vec4* planes = map.planes.data() + batch;
        for (std::uint32_t i = 0; i < n; ++i) {
            const glm::vec4& p = planes[i];
            const float f = p.x * e.x + p.y * e.y + p.z * e.z - p.w * e.w;
            facing[i] = !singleSided || sign * f > -(m0 + m1 * std::abs(p.w));
        }
        for (std::uint32_t t = batch; t < batch + n; ++t) {
            bool keep = facing[t - batch] != 0;
            if (keep && !inside) {
                const std::uint32_t* tri = &mesh.indices[3 * std::size_t(t)];
                keep = (vertices[tri[0]] & vertices[tri[1]] & vertices[tri[2]]) == 0;
            }
            if (keep) {
                if (runLength == 0) runStart = t;
                ++runLength;
            } else if (runLength > 0) {
                out.add(runStart, runLength);
                runLength = 0;
            }
        }
    }
    out.add(runStart, runLength);
}

// Conservative culling of one cluster: dropped whole when its box is outside the frustum or its
// cone faces away, kept whole when inside and facing, tested triangle by triangle otherwise.
// `whole` is the side of the box of all the mesh's clusters (meshBox): a box inside it is inside
// the frustum too when that box is (and outside when it is), margins included; only a box that
// straddles a plane needs its clusters tested one by one.
void conservativeCluster(const Mesh& mesh, const MeshMap& map, const Cluster& c, const InstanceView& iv,
                         Outcodes& vertices, bool singleSided, Side whole, RangeList& out) {
    const Side side = whole == Side::Straddles ? boxSide(iv.planes, c.boxMin, c.boxMax) : whole;
    if (side == Side::Outside) return;
    if (singleSided && !c.hasDegenerate && iv.coneAway(c, false)) return;
    const bool allFacing = !singleSided || iv.coneAway(c, true);
    if (side == Side::Inside && allFacing)
        out.add(c.first, c.count);
    else
        testTriangles(mesh, map, iv, vertices, c.first, c.count, side == Side::Inside, singleSided && !allFacing, out);
}

// Adds every non-empty bin of `map` one of whose sample directions (`samples`, kBinSamples a bin)
// satisfies `take`.
template <class Take>
void addBinsWhere(const MeshMap& map, const std::vector<glm::vec3>& samples, RangeList& out, Take take) {
    for (std::size_t b = 0; b < map.bins.size(); ++b) {
        const Bin& bin = map.bins[b];
        if (bin.count == 0) continue;
        for (int s = 0; s < kBinSamples; ++s)
            if (take(glm::dvec3(samples[b * kBinSamples + std::size_t(s)]))) {
                out.add(bin.first, bin.count);
                break;
            }
    }
}

// World-space sphere of an instance against the frustum (paper equation 2).
SphereClass classifySphere(const Sphere& sphere, const glm::mat4& model, const View& view) {
    const glm::dmat4 m(model);
    const glm::dvec3 center = glm::dvec3(m * glm::dvec4(sphere.center, 1.0));
    const double scale = std::max({glm::length(glm::dvec3(m[0])), glm::length(glm::dvec3(m[1])),
                                   glm::length(glm::dvec3(m[2]))});
    const double radius = sphere.radius * scale;
    const Planes planes =
        clipPlanes(glm::dmat4(view.givenProjection) * glm::dmat4(view.view), view.depthFormat);
    bool whole = true;
    for (const Plane& plane : planes) {
        const double n = glm::length(glm::dvec3(plane.p));
        if (n == 0.0) return SphereClass::Outside;  // nothing is inside a plane with no normal and d < 0
        const double distance = plane.eval(center) / n;
        const double margin = kPlaneMargin * (glm::length(center) + radius + std::abs(plane.p.w) / n);
        if (!(distance >= -radius - margin)) return SphereClass::Outside;  // NaN keeps nothing either
        if (distance < radius + margin) whole = false;
    }
    return whole ? SphereClass::Whole : SphereClass::Partial;
}

}  // namespace

SceneCuller SceneCuller::prepare(Scene& scene, const MapParams& params) {
    SceneCuller culler;
    culler.maps_.reserve(scene.meshes.size());
    for (Mesh& mesh : scene.meshes) {
        std::vector<std::uint32_t> order;
        culler.maps_.push_back(buildMeshMap(mesh, params, order));
        reorderTriangles(mesh, order);
        // A cluster box that is not finite makes the mesh's not finite: it straddles every plane, and
        // each cluster is tested on its own (no cluster at all: the same).
        glm::vec3 lo(NAN), hi(NAN);
        bool finite = !culler.maps_.back().clusters.empty();
        for (const Cluster& c : culler.maps_.back().clusters) {
            finite = finite && std::isfinite(c.boxMin.x + c.boxMin.y + c.boxMin.z + c.boxMax.x + c.boxMax.y + c.boxMax.z);
            lo = glm::min(c.boxMin, lo), hi = glm::max(c.boxMax, hi);
        }
        culler.meshBoxes_.emplace_back(finite ? lo : glm::vec3(NAN), finite ? hi : glm::vec3(NAN));
    }
    // The bins' sample directions depend on the bin counts only: one set for every mesh.
    const double pi = std::numbers::pi;
    culler.binSamples_.reserve(std::size_t(params.thetaBins * params.phiBins * kBinSamples));
    for (int i = 0; i < params.thetaBins; ++i)
        for (int j = 0; j < params.phiBins; ++j)
            for (int si = 0; si < kSampleSide; ++si)
                for (int sj = 0; sj < kSampleSide; ++sj) {
                    // Corners and middles of the cell: edges included, so neighbouring cells agree.
                    const double theta = pi * (i + si / double(kSampleSide - 1)) / params.thetaBins;
                    const double phi = 2.0 * pi * (j + sj / double(kSampleSide - 1)) / params.phiBins;
                    culler.binSamples_.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                                    std::cos(theta));
                }
    return culler;
}

PrepStats SceneCuller::totals() const {
    PrepStats total;
    for (const MeshMap& map : maps_) {
        total.sphereMs += map.stats.sphereMs;
        total.mapMs += map.stats.mapMs;
        total.clusterMs += map.stats.clusterMs;
        total.hullMs += map.stats.hullMs;
        total.mapBytes += map.stats.mapBytes;
        total.accessBytes += map.stats.accessBytes;
        total.hullBytes += map.stats.hullBytes;
    }
    return total;
}

SphereClass SceneCuller::classify(const Scene& scene, int instance, const std::vector<glm::mat4>& world,
                                  const View& view) const {
    const Instance& in = scene.instances[std::size_t(instance)];
    return classifySphere(maps_[std::size_t(in.mesh)].sphere, world[std::size_t(in.node)], view);
}

DrawList SceneCuller::cullOcclusion(const Scene& scene, const std::vector<glm::mat4>& world, const View& view,
                                    const OcclusionTarget& target) const {
    // The conservative plan, cluster by cluster, then what the occlusion pass leaves of it.
    // The conservative plan is made in pieces of kPieceClusters clusters (counting
    // over every instance's clusters in order) side by side, joined in order: when the occlusion
    // pass is likely to run and its threads are awake. Otherwise in one piece, on this thread (a
    // piece costs the set-up of each instance it starts in).
    constexpr std::size_t kPieceClusters = 128;
    const bool sideBySide = occlusion_.prepare(target);
    clusterStart_.assign(scene.instances.size() + 1, 0);
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        const bool empty = scene.meshes[std::size_t(instance.mesh)].triangleCount() == 0;
        clusterStart_[i + 1] = clusterStart_[i] + (empty ? 0 : maps_[std::size_t(instance.mesh)].clusters.size());
    }
    const std::size_t pieceClusters = sideBySide ? kPieceClusters : std::max<std::size_t>(clusterStart_.back(), 1);
    const std::size_t pieceCount = (clusterStart_.back() + pieceClusters - 1) / pieceClusters;
    if (pieces_.size() < pieceCount) pieces_.resize(pieceCount);
    outcodes_.resize(std::size_t(occlusion_.threads(target)));
    occlusion_.parallel(target, pieceCount, [&](std::size_t p, int worker) {
        ConservativePiece& piece = pieces_[p];
        piece.kept.clear();
        piece.ranges.clear();
        const std::size_t first = p * pieceClusters, last = std::min(first + pieceClusters, clusterStart_.back());
        // The instance of cluster `first`: the last one starting at or before it (empty ones start
        // where the next one does).
        std::size_t i = std::size_t(std::upper_bound(clusterStart_.begin(), clusterStart_.end(), first) - clusterStart_.begin()) - 1;
        RangeList out;
        for (std::size_t at = first; at < last; ++i) {
            if (clusterStart_[i + 1] <= at) continue;
            const Instance& instance = scene.instances[i];
            const Mesh& mesh = scene.meshes[std::size_t(instance.mesh)];
            const MeshMap& map = maps_[std::size_t(instance.mesh)];
            const InstanceView iv(world[std::size_t(instance.node)], view);
            const Side whole = boxSide(iv.planes, meshBoxes_[std::size_t(instance.mesh)].first,
                                       meshBoxes_[std::size_t(instance.mesh)].second);
            if (whole == Side::Outside) {
                at = std::min(last, clusterStart_[i + 1]);
                continue;
            }
            Outcodes vertices(mesh, iv.mvp, outcodes_[std::size_t(worker)]);
            const bool singleSided = isSingleSided(scene, mesh);
            for (; at < std::min(last, clusterStart_[i + 1]); ++at) {
                const std::size_t c = at - clusterStart_[i];
                out.ranges.clear();
                conservativeCluster(mesh, map, map.clusters[c], iv, vertices, singleSided, whole, out);
                if (out.ranges.empty()) continue;
                piece.kept.push_back({std::uint32_t(i), std::uint32_t(c), std::uint32_t(piece.ranges.size()),
                                      std::uint32_t(out.ranges.size())});
                piece.ranges.insert(piece.ranges.end(), out.ranges.begin(), out.ranges.end());
            }
        }
    });
    std::vector<KeptCluster> kept;
    std::vector<IndexRange> ranges;
    for (std::size_t p = 0; p < pieceCount; ++p) {
        const ConservativePiece& piece = pieces_[p];
        const auto offset = std::uint32_t(ranges.size());
        for (KeptCluster k : piece.kept) {
            k.firstRange += offset;
            kept.push_back(k);
        }
        ranges.insert(ranges.end(), piece.ranges.begin(), piece.ranges.end());
    }
    std::vector<KeptCluster> left;
    std::vector<IndexRange> leftRanges;
    occlusion_.run(scene, maps_, world, view, target, kept, ranges, left, leftRanges);
    DrawList list;
    for (std::size_t k = 0; k < left.size();) {
        const std::uint32_t instance = left[k].instance;
        RangeList out;
        for (; k < left.size() && left[k].instance == instance; ++k)
            for (std::uint32_t r = 0; r < left[k].rangeCount; ++r) {
                const IndexRange& range = leftRanges[left[k].firstRange + r];
                out.add(range.firstTriangle, range.triangleCount);
            }
        if (!out.ranges.empty()) list.push_back(DrawCommand{int(instance), std::move(out.ranges)});
    }
    return list;
}

DrawList SceneCuller::cull(Cull method, const Scene& scene, const std::vector<glm::mat4>& world,
                           const View& view, const OcclusionTarget& target) const {
    DrawList list;
    if (method == Cull::None || method == Cull::Oracle) return fullDrawList(scene);
    if (method == Cull::Occlusion) return cullOcclusion(scene, world, view, target);
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        const Mesh& mesh = scene.meshes[std::size_t(instance.mesh)];
        const MeshMap& map = maps_[std::size_t(instance.mesh)];
        const std::uint32_t triangles = std::uint32_t(mesh.triangleCount());
        if (triangles == 0) continue;
        const glm::mat4& model = world[std::size_t(instance.node)];
        const bool singleSided = isSingleSided(scene, mesh);
        RangeList out;

        switch (method) {
            case Cull::Sphere:
                if (classifySphere(map.sphere, model, view) != SphereClass::Outside) out.add(0, triangles);
                break;

            case Cull::Backface: {
                const InstanceView iv(model, view);
                Outcodes vertices(mesh, iv.mvp);
                testTriangles(mesh, map, iv, vertices, 0, triangles, false, singleSided, out);
                break;
            }

            case Cull::Cones: {
                const InstanceView iv(model, view);
                for (const Cluster& c : map.clusters) {
                    if (boxSide(iv.planes, c.boxMin, c.boxMax) == Side::Outside) continue;
                    if (singleSided && iv.coneAway(c, false)) continue;
                    out.add(c.first, c.count);
                }
                break;
            }

            case Cull::Conservative: {
                const InstanceView iv(model, view);
                const Side whole = boxSide(iv.planes, meshBoxes_[std::size_t(instance.mesh)].first,
                                           meshBoxes_[std::size_t(instance.mesh)].second);
                if (whole == Side::Outside) break;
                Outcodes vertices(mesh, iv.mvp);
                for (const Cluster& c : map.clusters) conservativeCluster(mesh, map, c, iv, vertices, singleSided, whole, out);
                break;
            }

            case Cull::Paper: {
                const SphereClass sphereClass = classifySphere(map.sphere, model, view);
                if (sphereClass == SphereClass::Outside) break;
                const InstanceView iv(model, view);
                const std::vector<glm::vec3>& samples = binSamples_;
                const glm::dvec3 c = map.sphere.center;
                const double r = map.sphere.radius;
                // Towards the viewer from the centre, in object space.
                const glm::dvec3 toward = iv.eye.w != 0.0 ? glm::dvec3(iv.eye) / iv.eye.w - c : glm::dvec3(iv.eye);
                if (sphereClass == SphereClass::Partial) {
                    // The bins whose patch of the bounding sphere is inside the frustum, on the camera's side.
                    addBinsWhere(map, samples, out, [&](const glm::dvec3& dir) {
                        const glm::dvec3 p = c + r * dir;
                        return glm::dot(dir, toward) >= 0.0 &&
                               std::all_of(iv.planes.begin(), iv.planes.end(),
                                           [&p](const Plane& plane) { return plane.eval(p) >= 0.0; });
                    });
                    break;
                }
                // Whole object in view: azimuths about the camera's up axis, 0 towards the viewer.
                const glm::dmat3 toObject = glm::inverse(glm::dmat3(glm::dmat4(model)));
                const glm::dvec3 upWorld = glm::dvec3(glm::inverse(glm::dmat4(view.view))[1]);
                const glm::dvec3 up = glm::normalize(toObject * upWorld);
                glm::dvec3 front = toward - glm::dot(toward, up) * up;
                const double frontLength = glm::length(front);
                if (map.hull.vertices.size() < 2 || !(frontLength > 0.0) || !std::isfinite(frontLength)) {
                    out.add(0, triangles);  // no hull to speak of, or looking along the up axis: keep all
                    break;
                }
                front /= frontLength;
                const glm::dvec3 right = glm::cross(front, up);
                // The hull's vertices of largest side factor (R·sin θ·sin φ in this frame) left and right.
                double leftSide = INFINITY, rightSide = -INFINITY, leftAzimuth = 0.0, rightAzimuth = 0.0;
                for (const glm::vec3& h : map.hull.vertices) {
                    const glm::dvec3 d = glm::dvec3(h) - c;
                    const double side = glm::dot(d, right);
                    const double azimuth = std::atan2(side, glm::dot(d, front));
                    if (side > rightSide) rightSide = side, rightAzimuth = azimuth;
                    if (side < leftSide) leftSide = side, leftAzimuth = azimuth;
                }
                // What lies behind them by azimuth is taken as hidden.
                addBinsWhere(map, samples, out, [&](const glm::dvec3& dir) {
                    const double azimuth = std::atan2(glm::dot(dir, right), glm::dot(dir, front));
                    return azimuth >= leftAzimuth && azimuth <= rightAzimuth;
                });
                break;
            }

            case Cull::None:
            case Cull::Occlusion:
            case Cull::Oracle:
                break;
        }
        if (!out.ranges.empty()) list.push_back(DrawCommand{int(i), std::move(out.ranges)});
    }
    return list;
}

std::size_t submittedTriangles(const Scene& scene, const DrawList& list) {
    std::uint64_t total = 0;
    std::vector<IndexRange> runs;
    for (const DrawCommand& command : list) {
        if (command.instance < 0 || std::size_t(command.instance) >= scene.instances.size()) continue;
        const Mesh& mesh = scene.meshes[std::size_t(scene.instances[std::size_t(command.instance)].mesh)];
        total += normalizeRanges(command.ranges, std::uint32_t(mesh.triangleCount()), runs);
    }
    return std::size_t(total);
}

}  // namespace frugal
