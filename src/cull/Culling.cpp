#include "cull/Culling.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "pipeline/IndexRanges.h"
#include "scene/MeshBuild.h"

namespace frugal {

namespace {

constexpr int kSampleSide = 3;  // a bin's cell is sampled on a 3 × 3 grid of directions
constexpr int kBinSamples = kSampleSide * kSampleSide;

// Relative margins: a test drops something only when it is outside by more than float rounding.
constexpr double kPlaneMargin = 1e-5;
constexpr float kConeMargin = 1e-4f;
// How far GL may move a vertex's window position, per axis, in pixels: llvmpipe snaps it to the
// nearest 1/256 pixel (half a step), with 1/4096 pixel to spare; InstanceView::facingK adds the
// float transform's rounding (small near the origin, not a million units away). Facing is decided
// by the sign of the snapped triangle's area, so a triangle seen nearly edge-on may come out
// front-facing though it faces away (InstanceView).
constexpr double kSnap = 1.0 / 512.0 + 1.0 / 4096.0;
// A unit of float roundoff.
constexpr double kFloatUnit = 1.0 / 16777216.0;

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

// The largest singular value of `m` (its largest stretch of a vector), from above: the largest
// eigenvalue of mᵀm in closed form (Smith's trigonometric solution of the symmetric 3×3 case), with
// a relative margin for its rounding, and never more than the Frobenius norm, which also bounds it.
double largestStretch(const glm::dmat3& m) {
    const glm::dmat3 a = glm::transpose(m) * m;
    const double frobenius = std::sqrt(a[0][0] + a[1][1] + a[2][2]);
    const double p1 = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const double q = (a[0][0] + a[1][1] + a[2][2]) / 3.0;
    const double p2 = (a[0][0] - q) * (a[0][0] - q) + (a[1][1] - q) * (a[1][1] - q) + (a[2][2] - q) * (a[2][2] - q) + 2.0 * p1;
    double largest = q;
    if (p2 > 0.0) {
        const double p = std::sqrt(p2 / 6.0);
        const glm::dmat3 b = (a - q * glm::dmat3(1.0)) / p;
        const double phi = std::acos(std::clamp(glm::determinant(b) / 2.0, -1.0, 1.0)) / 3.0;
        largest = q + 2.0 * p * std::cos(phi);
    }
    const double stretch = std::sqrt(std::max(largest, 0.0)) * (1.0 + 1e-6) + 1e-12 * frobenius;
    return std::isfinite(stretch) ? std::min(stretch, frobenius * (1.0 + 1e-12)) : frobenius;
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
    // GL decides facing from the snapped window positions (kSnap), and that can turn a triangle
    // seen nearly edge-on: the margin above covers the float test, not this. Twice the area is
    // e1 × e2 for the two shorter edges; with every vertex moved by at most s per axis (the snap,
    // and the float transform's rounding for the cluster's sphere), it changes by at most
    // 2s·(|Δx| + |Δy| of e1 and of e2) + 8s².
    // In exact terms twice the area is fx·fy·|det L|·2A·|f| ÷ (Z0·Z1·Z2) (perspective; fx, fy pixels
    // per unit at depth 1, L the linear part of view·model, A the triangle's area and f the facing
    // value above, both in object units, Z the vertices' depths), and fx·fy·|det L|·2A·|f|·|u| for
    // orthographic views (u = L⁻¹·ẑ). An edge of an unclipped triangle spans at most
    // fmax·g·‖L‖·length ÷ Zmin pixels in |Δx| + |Δy| (a vertex inside the frustum has |x/z| ≤
    // 1/|P00| and |y/z| ≤ 1/|P11|, so |Δx| + |Δy| ≤ fmax·(|ΔX| + |ΔY| + (1/|P00| + 1/|P11|)·|ΔZ|) ÷
    // Zmin, and g = √(2 + (1/|P00| + 1/|P11|)²) by Cauchy–Schwarz; orthographic: g = √2 and no Z;
    // ‖L‖ its largest stretch). So a triangle faces away after snapping too when
    // f < −(K1·(|e1| + |e2|)/(2A) + K2/(2A)), with, for a depth range [Zmin, Zmax],
    //   K1 = 2s·fmax·g·‖L‖·Zmax³ ÷ (Zmin·fx·fy·|det L|),   K2 = 8s²·Zmax³ ÷ (fx·fy·|det L|)
    // (orthographic: Zmax³/Zmin and Zmax³ become 1/|u|). Per triangle, (|e1| + |e2|)/(2A) and 1/(2A)
    // are MeshMap::facingSlack; facingK gives K1, K2 for a cluster's sphere. A triangle that GL clips
    // is fanned into new triangles that may be thinner than it: those are never dropped for facing.
    glm::dmat4 viewModel{1.0};
    double fx = 0.0, fy = 0.0, fmax = 0.0, g = 0.0, detL = 0.0, normL = 0.0, zRow = 0.0, uLength = 0.0;
    double projX = 1.0, projY = 1.0;  // P00, P11: fx / |P00| is half the width in pixels
    int width = 0, height = 0;
    bool perspective = true, sizeKnown = false;

    // K1, K2 for the triangles of a sphere (object space); +inf when nothing can be said (the sphere
    // reaches the eye's plane, the size of the target is not known, a degenerate transform).
    glm::vec2 facingK(const glm::dvec3& center, double radius) const {
        constexpr float kNone = INFINITY;
        const double area = fx * fy * detL;
        if (!sizeKnown || !(area > 0.0) || !std::isfinite(area)) return glm::vec2(kNone);
        double depthFactor = 1.0, perimeterFactor = 1.0;  // Zmax³ and Zmax³/Zmin; 1/|u| twice, orthographic
        double wmin = 1.0;                                 // clip w: the depth Z, or 1 (orthographic)
        if (perspective) {
            const double zc = -(viewModel * glm::dvec4(center, 1.0)).z;
            const double reach = radius * zRow * (1.0 + 1e-6);
            const double zmin = zc - reach, zmax = zc + reach;
            if (!(zmin > 0.0) || !std::isfinite(zmax)) return glm::vec2(kNone);
            depthFactor = zmax * zmax * zmax;
            perimeterFactor = depthFactor / zmin;
            wmin = zmin;
        } else {
            if (!(uLength > 0.0)) return glm::vec2(kNone);
            depthFactor = perimeterFactor = 1.0 / uLength;
        }
        // The float transform: each clip coordinate within eight units of roundoff of the sizes of
        // its terms (the matrix is itself a float product), so x/w moves by at most (ex + ew)/w
        // inside the frustum (|x/w| ≤ 1); the viewport and the snap's own float steps add 4u·size.
        const auto termSizes = [&](int row) {
            double size = std::abs(mvp[3][row]);
            for (int j = 0; j < 3; ++j) size += std::abs(mvp[j][row]) * (std::abs(center[j]) + radius);
            return size;
        };
        const double ew = 8.0 * kFloatUnit * termSizes(3);
        const double moved = std::max(fx / std::abs(projX) * (8.0 * kFloatUnit * termSizes(0) + ew),
                                      fy / std::abs(projY) * (8.0 * kFloatUnit * termSizes(1) + ew)) / wmin +
                             4.0 * kFloatUnit * double(std::max(width, height));
        const double snap = kSnap + moved;
        if (!std::isfinite(snap)) return glm::vec2(kNone);
        const double k1 = 2.0 * snap * fmax * g * normL * perimeterFactor / area;
        const double k2 = 8.0 * snap * snap * depthFactor / area;
        const auto up = [](double x) {
            if (!(x >= 0.0)) return INFINITY;  // not a number: no bound
            const float f = float(x);
            return double(f) >= x ? f : std::nextafter(f, INFINITY);
        };
        return {up(k1), up(k2)};
    }

    InstanceView(const glm::mat4& model, const View& view) {
        // The frustum of the given planes (pipeline/Camera.h): the fit moves them only where no
        // triangle is, so every triangle is inside both or neither; paper 002's sphere tests, which
        // look at the bounding sphere and not the triangles, keep their classes and bins this way.
        const glm::dmat4 m(model), v(view.view), p(view.givenProjection);
        mvp = p * v * m;
        planes = clipPlanes(mvp, view.depthFormat);
        const glm::dmat4 toObject = glm::inverse(v * m);
        eye = toObject * (view.perspective ? glm::dvec4(0, 0, 0, 1) : glm::dvec4(0, 0, 1, 0));
        if (!view.perspective) {
            uLength = glm::length(glm::dvec3(eye));
            eye = glm::dvec4(glm::normalize(glm::dvec3(eye)), 0.0);
        }
        viewModel = v * m;
        const glm::dmat3 linear(viewModel);
        perspective = view.perspective;
        sizeKnown = view.width > 0 && view.height > 0;
        const glm::dmat4 drawn(view.projection);
        fx = std::abs(drawn[0][0]) * 0.5 * double(view.width);
        fy = std::abs(drawn[1][1]) * 0.5 * double(view.height);
        projX = drawn[0][0];
        projY = drawn[1][1];
        width = view.width;
        height = view.height;
        fmax = std::max(fx, fy);
        const double spread = perspective ? 1.0 / std::abs(drawn[0][0]) + 1.0 / std::abs(drawn[1][1]) : 0.0;
        g = std::sqrt(2.0 + spread * spread);
        detL = std::abs(glm::determinant(linear));
        normL = largestStretch(linear);
        zRow = glm::length(glm::dvec3(linear[0][2], linear[1][2], linear[2][2]));
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
        if (!coneTest(c, axis, cutoff)) return false;
        if (towardEye) return true;
        // Faces away after snapping too: every triangle at least the facing margin away from
        // edge-on (facingK), i.e. the cone widened by α, sin α = the cluster's largest margin ÷ its
        // nearest distance (the same value f, in cosines for orthographic views). Any normal within
        // α of one of the cone's still faces away, so each triangle's f ≤ −distance·sin α. The
        // widened cutoff is sin(h + α) for cutoff = sin h, while h + α < 90°, i.e. sin α < cos h.
        const glm::vec2 k = facingK(glm::dvec3(c.center), double(c.radius));
        const double slack = double(k.x) * double(c.slack.x) + double(k.y) * double(c.slack.y);
        const double distance =
            eye.w != 0.0 ? glm::length(glm::dvec3(c.center) - glm::dvec3(eye)) - double(c.radius) : 1.0;
        if (!(distance > 0.0) || !(slack < distance)) return false;
        const double sinA = slack / distance, sinH = std::clamp(cutoff, -1.0, 1.0);
        const double cosH = std::sqrt(1.0 - sinH * sinH);
        if (!(sinA < cosH)) return false;
        // Rounded up a little: the widened cone may only be wider.
        const double widened = std::min(sinH * std::sqrt(1.0 - sinA * sinA) + cosH * sinA + 1e-12, 1.0);
        return widened < 1.0 && coneTest(c, axis, widened);
    }

    // meshoptimizer's test of a cone (axis, cutoff) against the eye, with the margins of its rounding.
    bool coneTest(const Cluster& c, const glm::dvec3& axis, double cutoff) const {
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

// Per vertex of a cluster of one instance, which clip planes it is outside of (bit k: plane k of
// -w ≤ x, y, z ≤ w), by more than rounding, and kMayClip when it is not inside all of them by more
// than rounding. A triangle whose three vertices share a bit of the six lies wholly outside that
// plane and cannot own a pixel; one without kMayClip on any vertex is drawn unclipped.
constexpr std::uint8_t kMayClip = 1u << 6;
constexpr std::uint8_t kOutside = 0x3f;

class Outcodes {
public:
    Outcodes(const ClusterVertices& vertices, const glm::dmat4& mvp) : vertices_(vertices), mvp_(mvp) {}

    // The codes of cluster `c`'s vertices (ClusterVertices: its triangles' corners c0, c1, c2 index
    // them), computed for the whole cluster at once: its vertices are side by side, where the
    // mesh's would be scattered over memory the draw has just used.
    const std::uint8_t* cluster(std::uint32_t c) {
        if (c != cluster_) {
            const std::uint32_t first = vertices_.firstVertex[c], count = vertices_.firstVertex[c + 1] - first;
            for (std::uint32_t v = 0; v < count; ++v)
                codes_[v] = compute(vertices_.x[first + v], vertices_.y[first + v], vertices_.z[first + v]);
            cluster_ = c;
        }
        return codes_;
    }

private:
    std::uint8_t compute(float px, float py, float pz) const {
        const glm::dvec4 c = mvp_ * glm::dvec4(double(px), double(py), double(pz), 1.0);
        if (!std::isfinite(c.x + c.y + c.z + c.w)) return 0;  // not a number: outside of nothing, kept
        auto out = [](double x, double w) { return x + w < -kPlaneMargin * (std::abs(x) + std::abs(w)); };
        auto near = [](double x, double w) { return x + w <= kPlaneMargin * (std::abs(x) + std::abs(w)); };
        std::uint8_t code = 0;
        for (int axis = 0; axis < 3; ++axis) {
            if (out(c[axis], c.w)) code |= std::uint8_t(1u << (2 * axis));
            if (out(-c[axis], c.w)) code |= std::uint8_t(2u << (2 * axis));
            if (near(c[axis], c.w) || near(-c[axis], c.w)) code |= kMayClip;
        }
        return code;
    }

    const ClusterVertices& vertices_;
    glm::dmat4 mvp_;
    std::uint32_t cluster_ = UINT32_MAX;  // whose codes codes_ holds
    std::uint8_t codes_[kClusterVertices];
};

bool isSingleSided(const Scene& scene, const Mesh& mesh) {
    return mesh.material < 0 || !scene.materials[std::size_t(mesh.material)].doubleSided;
}

// The exact per-triangle tests over cluster `ci` of `map`: frustum (unless `inside`) and facing
// (when `singleSided`).
void testTriangles(const MeshMap& map, std::uint32_t ci, const InstanceView& iv, Outcodes& vertices, bool inside,
                   bool singleSided, glm::vec2 k, RangeList& out) {
    const std::uint32_t first = map.clusters[ci].first, count = map.clusters[ci].count;
    const ClusterVertices& cv = map.vertices;
    const std::uint8_t* codes = nullptr;  // the cluster's vertices' outcodes, on first use
    // Facing first, a batch of triangles at a time in one loop that vectorizes (InstanceView's test,
    // with the snapping margin K1·slack.x + K2·slack.y: `k` is facingK of what is tested).
    constexpr std::uint32_t kBatch = 128;
    std::uint8_t facing[kBatch];
    const glm::vec4 e = iv.eyeFloat;
    const float sign = iv.facingSign, m0 = iv.marginBase, m1 = iv.marginPerD;
    std::uint32_t runStart = first, runLength = 0;
    for (std::uint32_t batch = first; batch < first + count; batch += kBatch) {
        const std::uint32_t n = std::min(kBatch, first + count - batch);
        const glm::vec4* planes = map.planes.data() + batch;
        const glm::vec2* slack = map.facingSlack.data() + batch;
        for (std::uint32_t i = 0; i < n; ++i) {
            const glm::vec4& p = planes[i];
            const float f = p.x * e.x + p.y * e.y + p.z * e.z - p.w * e.w;
            // Written so that a margin that is not a number keeps the triangle.
            facing[i] = !singleSided || !(sign * f <= -(m0 + m1 * std::abs(p.w) + k.x * slack[i].x + k.y * slack[i].y));
        }
        if (inside) {
            // Inside the frustum the facing test alone decides: its runs, 64 flags at a time (a
            // branch a triangle on whether it faces the eye is one the CPU cannot predict). Runs that
            // touch are merged by `out`.
            for (std::uint32_t base = 0; base < n; base += 64) {
                const std::uint32_t len = std::min<std::uint32_t>(64, n - base);
                std::uint64_t m = 0;
                for (std::uint32_t i = 0; i < len; ++i) m |= std::uint64_t(facing[base + i] != 0) << i;
                forEachRun(m, [&](std::uint32_t at, std::uint32_t length) { out.add(batch + base + at, length); });
            }
            continue;
        }
        // Across the frustum, triangle by triangle: there the kept runs are long and the branch is
        // predicted (the 64-flag runs above measured slower here).
        for (std::uint32_t t = batch; t < batch + n; ++t) {
            bool keep = facing[t - batch] != 0;
            if (keep || singleSided) {
                if (codes == nullptr) codes = vertices.cluster(ci);
                const std::uint8_t a = codes[cv.c0[t]], b = codes[cv.c1[t]], c = codes[cv.c2[t]];
                // Outside a plane: dropped. Clipped by GL: its new triangles may turn, so facing
                // does not drop it.
                if ((a & b & c & kOutside) != 0)
                    keep = false;
                else if (((a | b | c) & kMayClip) != 0)
                    keep = true;
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
void conservativeCluster(const MeshMap& map, std::uint32_t ci, const InstanceView& iv, Outcodes& vertices,
                         bool singleSided, Side whole, RangeList& out) {
    const Cluster& c = map.clusters[ci];
    const Side side = whole == Side::Straddles ? boxSide(iv.planes, c.boxMin, c.boxMax) : whole;
    if (side == Side::Outside) return;
    // A cone drops only a cluster that GL draws unclipped (its triangles' margins hold; a clipped one
    // goes to the triangle tests).
    if (singleSided && side == Side::Inside && !c.hasDegenerate && iv.coneAway(c, false)) return;
    const bool allFacing = !singleSided || iv.coneAway(c, true);
    if (side == Side::Inside && allFacing)
        out.add(c.first, c.count);
    else
        testTriangles(map, ci, iv, vertices, side == Side::Inside, singleSided && !allFacing,
                      singleSided && !allFacing ? iv.facingK(glm::dvec3(c.center), double(c.radius)) : glm::vec2(0.0f), out);
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

namespace {

// Instances that culling draws whole: a deforming one (its map, clusters and hull are of its rest
// pose) and one of points or segments (the maps, cones and hulls are of triangles; a point or a
// segment is never culled, so never wrongly).
bool drawnWhole(const Scene& scene, const Instance& instance) {
    return scene.deforms(instance) || !scene.meshes[std::size_t(instance.mesh)].triangles();
}

// `list` with every instance drawn whole (drawnWhole) added, in instance order (the scene order
// plans keep).
DrawList withDeformingWhole(const Scene& scene, DrawList list) {
    bool any = false;
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const Mesh& mesh = scene.meshes[std::size_t(scene.instances[i].mesh)];
        if (!drawnWhole(scene, scene.instances[i]) || mesh.primitiveCount() == 0) continue;
        RangeList whole;
        whole.add(0, std::uint32_t(mesh.primitiveCount()));
        list.push_back(DrawCommand{int(i), std::move(whole.ranges)});
        any = true;
    }
    if (any)
        std::sort(list.begin(), list.end(),
                  [](const DrawCommand& a, const DrawCommand& b) { return a.instance < b.instance; });
    return list;
}

}  // namespace

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
        // A deforming instance, or one of points or segments, is drawn whole and is no occluder.
        const bool empty = scene.meshes[std::size_t(instance.mesh)].triangleCount() == 0 || drawnWhole(scene, instance);
        clusterStart_[i + 1] = clusterStart_[i] + (empty ? 0 : maps_[std::size_t(instance.mesh)].clusters.size());
    }
    const std::size_t pieceClusters = sideBySide ? kPieceClusters : std::max<std::size_t>(clusterStart_.back(), 1);
    const std::size_t pieceCount = (clusterStart_.back() + pieceClusters - 1) / pieceClusters;
    if (pieces_.size() < pieceCount) pieces_.resize(pieceCount);
    occlusion_.parallel(target, pieceCount, [&](std::size_t p, int) {
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
            Outcodes vertices(map.vertices, iv.mvp);
            const bool singleSided = isSingleSided(scene, mesh);
            for (; at < std::min(last, clusterStart_[i + 1]); ++at) {
                const std::size_t c = at - clusterStart_[i];
                out.ranges.clear();
                conservativeCluster(map, std::uint32_t(c), iv, vertices, singleSided, whole, out);
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
    return withDeformingWhole(scene, std::move(list));
}

DrawList SceneCuller::cull(Cull method, const Scene& scene, const std::vector<glm::mat4>& world,
                           const View& view, const OcclusionTarget& target) const {
    DrawList list;
    const CullTraits& traits = traitsOf(method);
    if (!traits.prepares || traits.idPass) return fullDrawList(scene);  // none; the oracle draws its own
    if (traits.occlusion) return cullOcclusion(scene, world, view, target);
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        const Mesh& mesh = scene.meshes[std::size_t(instance.mesh)];
        const MeshMap& map = maps_[std::size_t(instance.mesh)];
        const std::uint32_t triangles = std::uint32_t(mesh.primitiveCount());
        if (triangles == 0) continue;
        const glm::mat4& model = world[std::size_t(instance.node)];
        const bool singleSided = isSingleSided(scene, mesh);
        RangeList out;
        if (drawnWhole(scene, instance)) {
            // Its triangles move with its pose (the mesh's map describes its rest pose only), or it
            // has none.
            out.add(0, triangles);
            list.push_back(DrawCommand{int(i), std::move(out.ranges)});
            continue;
        }

        switch (method) {
            case Cull::Sphere:
                if (classifySphere(map.sphere, model, view) != SphereClass::Outside) out.add(0, triangles);
                break;

            case Cull::Backface: {
                const InstanceView iv(model, view);
                // Every triangle tested, cluster by cluster: the facing margin of a cluster's depth
                // range (the whole mesh's would be wider), and no clip test for a cluster whose box
                // is inside (GL clips none of it).
                Outcodes vertices(map.vertices, iv.mvp);
                for (std::uint32_t ci = 0; ci < map.clusters.size(); ++ci) {
                    const Cluster& c = map.clusters[ci];
                    const Side side = boxSide(iv.planes, c.boxMin, c.boxMax);
                    testTriangles(map, ci, iv, vertices, side == Side::Inside, singleSided,
                                  singleSided ? iv.facingK(glm::dvec3(c.center), double(c.radius)) : glm::vec2(0.0f),
                                  out);
                }
                break;
            }

            case Cull::Cones: {
                const InstanceView iv(model, view);
                for (const Cluster& c : map.clusters) {
                    const Side side = boxSide(iv.planes, c.boxMin, c.boxMax);
                    if (side == Side::Outside) continue;
                    if (singleSided && side == Side::Inside && iv.coneAway(c, false)) continue;
                    out.add(c.first, c.count);
                }
                break;
            }

            case Cull::Conservative: {
                const InstanceView iv(model, view);
                const Side whole = boxSide(iv.planes, meshBoxes_[std::size_t(instance.mesh)].first,
                                           meshBoxes_[std::size_t(instance.mesh)].second);
                if (whole == Side::Outside) break;
                Outcodes vertices(map.vertices, iv.mvp);
                for (std::uint32_t ci = 0; ci < map.clusters.size(); ++ci)
                    conservativeCluster(map, ci, iv, vertices, singleSided, whole, out);
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
            case Cull::OcclusionAhead:
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
        total += normalizeRanges(command.ranges, std::uint32_t(mesh.primitiveCount()), runs);
    }
    return std::size_t(total);
}

}  // namespace frugal
