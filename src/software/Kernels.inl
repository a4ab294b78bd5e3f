// Kernel bodies, included by KernelsAvx2.cpp and KernelsGeneric.cpp inside a flavour namespace after
// Simd.h (no includes here). The arithmetic is the one Rasterizer.h and Shading.h document; where an
// FMA is used it is written as fma/fmas, every other a·b + c is rounded twice (fp-contract=off).

using simd::F8;
using simd::I8;

namespace {

// ---------------------------------------------------------------------------------------------
// Vertex stage (Rasterizer.h, 1.)

void transform(const VertexJob& job, std::size_t begin, std::size_t end) {
    const glm::mat4& m = job.mvp;
    const glm::mat3& nm = job.normalMatrix;
    const Viewport& vp = job.viewport;
    for (std::size_t i = begin; i < end; ++i) {
        const glm::vec3 p = job.positions[i];
        glm::vec4 c;
        for (int r = 0; r < 4; ++r) c[r] = ((m[0][r] * p.x + m[1][r] * p.y) + m[2][r] * p.z) + m[3][r];
        job.clip[i] = c;
        job.mask[i] = std::uint8_t(clipMask(c, vp.halfZ));

        SetupVertex& v = job.out[i];
        const float oow = 1.0f / c.w;
        v.x = simd::fmas(c.x * oow, vp.sx, vp.tx);
        v.y = simd::fmas(c.y * oow, vp.sy, vp.ty);
        v.z = simd::fmas(c.z * oow, vp.sz, vp.tz);
        v.oow = oow;

        const glm::vec3 n = job.normals ? job.normals[i] : glm::vec3(0.0f, 0.0f, 1.0f);
        for (int r = 0; r < 3; ++r) v.a[r] = (nm[0][r] * n.x + nm[1][r] * n.y) + nm[2][r] * n.z;
        const glm::vec4 color = job.colors ? job.colors[i] : glm::vec4(1.0f);
        v.a[3] = color.r;
        v.a[4] = color.g;
        v.a[5] = color.b;
        v.a[6] = color.a;
        const glm::vec2 uv = job.uvs ? job.uvs[i] : glm::vec2(0.0f);
        const glm::mat3& t = job.uvTransform;  // mat3 · vec3(uv, 1), as mesh.vert
        v.a[7] = (t[0][0] * uv.x + t[1][0] * uv.y) + t[2][0];
        v.a[8] = (t[0][1] * uv.x + t[1][1] * uv.y) + t[2][1];
        const glm::mat4& w = job.model;  // ((c0·x + c1·y) + c2·z) + c3, as mesh.vert
        for (int r = 0; r < 3; ++r) v.a[9 + r] = ((w[0][r] * p.x + w[1][r] * p.y) + w[2][r] * p.z) + w[3][r];
        if (job.tangents) {  // the tangent by the model matrix, bitangent cross(normal, tangent) · w
            const glm::vec4 tg = job.tangents[i];
            float* tw = v.a + 12;
            for (int r = 0; r < 3; ++r) tw[r] = (w[0][r] * tg.x + w[1][r] * tg.y) + w[2][r] * tg.z;
            const float* nw = v.a;
            v.a[15] = (nw[1] * tw[2] - nw[2] * tw[1]) * tg.w;
            v.a[16] = (nw[2] * tw[0] - nw[0] * tw[2]) * tg.w;
            v.a[17] = (nw[0] * tw[1] - nw[1] * tw[0]) * tg.w;
        } else {
            for (int k = 12; k < 18; ++k) v.a[k] = 0.0f;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Coverage and depth (Rasterizer.h, 3. and 5.)

inline std::int64_t max0(std::int64_t a) { return a > 0 ? a : 0; }
inline std::int64_t min0(std::int64_t a) { return a < 0 ? a : 0; }

// Samples: the target's (1 or kMaxSamples), a constant so that one sample compiles to the pixel's
// centre alone.
template <int Samples>
void rasterSamples(const Triangle& t, TileState& tile) {
    const int x0 = t.x0 > tile.x0 ? t.x0 : tile.x0;
    const int x1 = t.x1 < tile.x1 - 1 ? t.x1 : tile.x1 - 1;
    const int y0 = t.y0 > tile.y0 ? t.y0 : tile.y0;
    const int y1 = t.y1 < tile.y1 - 1 ? t.y1 : tile.y1 - 1;
    if (x0 > x1 || y0 > y1) return;

    const F8 dzdx = simd::splat(t.dzdx), dzdy = simd::splat(t.dzdy), z0 = simd::splat(t.z0);
    const I8 id = simd::splati(std::int32_t(t.id));
    const F8 zero = simd::splat(0.0f), one = simd::splat(1.0f), zscale = simd::splat(16777215.0f);
    const I8 lane = simd::ramp(0);
    const std::uint32_t stride = std::uint32_t(tile.target.stride);
    const bool reversed = tile.target.depthFormat == DepthFormat::D32F;
    std::uint32_t myIndex = kNoWinner;

    for (int sample = 0; sample < Samples; ++sample) {
        // The sample's edges and position (Rasterizer.h, 6.); a single sample is the pixel's centre.
        const Edge* edges = t.e;
        Edge sampleEdges[3];
        float sx = 0.0f, sy = 0.0f;
        if constexpr (Samples > 1) {
            const std::int64_t fx = kSampleFixed[sample][0], fy = kSampleFixed[sample][1];
            for (int e = 0; e < 3; ++e) {
                sampleEdges[e] = t.e[e];
                sampleEdges[e].k = (t.e[e].k + fy * t.e[e].dy - fx * t.e[e].dx) >> 8;
            }
            edges = sampleEdges;
            sx = kSamplePositions[sample][0];
            sy = kSamplePositions[sample][1];
        }
        const std::size_t plane = std::size_t(sample) * tile.target.sampleStride;
        std::uint32_t* const depthPlane = tile.target.depth + plane;
        std::uint32_t* const idPlane = tile.target.ids + plane;
        std::uint32_t* const winnerPlane = tile.winner + sample * TileState::kPlane;
        for (int by = y0 & ~7; by <= y1; by += 8) {
            for (int bx = x0 & ~7; bx <= x1; bx += 8) {
                // Classify the 8×8 block against each edge: outside (skip), inside, or partial.
                std::int32_t rowBase[3];
                std::int32_t dx[3], dy[3];
                int partial = 0;
                bool reject = false;
                for (int e = 0; e < 3; ++e) {
                    const Edge& edge = edges[e];
                    const std::int64_t f0 = edge.k - std::int64_t(edge.dx) * bx + std::int64_t(edge.dy) * by;
                    const std::int64_t lo = f0 - 7 * max0(edge.dx) + 7 * min0(edge.dy);
                    const std::int64_t hi = f0 - 7 * min0(edge.dx) + 7 * max0(edge.dy);
                    if (hi < 0) {
                        reject = true;
                        break;
                    }
                    if (lo < 0) {  // |f0| < 7·(|dx| + |dy|) < 2^31 here (Rasterizer.h bounds the coordinates)
                        rowBase[partial] = std::int32_t(f0);
                        dx[partial] = edge.dx;
                        dy[partial] = edge.dy;
                        ++partial;
                    }
                }
                if (reject) continue;

                const int ry0 = by > y0 ? by : y0;
                const int ry1 = by + 7 < y1 ? by + 7 : y1;
                const I8 px = lane + simd::splati(bx);
                const I8 columns = simd::gt(px, simd::splati(x0 - 1)) & simd::gt(simd::splati(x1 + 1), px);
                F8 pxf = simd::tofloat(px);
                if constexpr (Samples > 1) pxf = pxf + simd::splat(sx);
                for (int y = ry0; y <= ry1; ++y) {
                    I8 mask = columns;
                    for (int e = 0; e < partial; ++e) {
                        const I8 f = simd::splati(rowBase[e] + dy[e] * (y - by)) - simd::splati(dx[e]) * lane;
                        mask = simd::andnot(simd::sra(f, 31), mask);  // f ≥ 0
                    }
                    if (simd::laneBits(mask) == 0) continue;
                    I8 pass = mask;
                    if (t.depthTest) {  // DepthMode::Off skips the depth plane, the read and the write
                        const float fy = Samples > 1 ? float(y) + sy : float(y);
                        F8 z = simd::fma(dzdy, simd::splat(fy), simd::fma(dzdx, pxf, z0));
                        std::uint32_t* depthRow = depthPlane + std::size_t(y) * stride + bx;
                        I8 zi;
                        if (reversed) {
                            // D32F: lp_build_depth_clamp's min(z, 1) then max(·, 0), minps/maxps taking
                            // the second operand on a tie or NaN, so −0 and NaN never get through and
                            // the bits order as the floats do: GL_GREATER is an integer ">".
                            zi = simd::bits(simd::max(simd::min(z, one), zero));
                            pass = mask & simd::gt(zi, simd::loadi(depthRow));
                        } else {
                            z = simd::min(simd::max(z, zero), one);
                            zi = simd::toIntRound(z * zscale);
                            pass = mask & simd::gt(simd::loadi(depthRow), zi);
                        }
                        if (simd::laneBits(pass) == 0) continue;
                        simd::storeMasked(depthRow, pass, zi);
                    }
                    if (myIndex == kNoWinner) {
                        myIndex = std::uint32_t(tile.won.size());
                        tile.won.push_back(&t);
                    }
                    std::uint32_t* winnerRow = winnerPlane + (y - tile.y0) * kTileSize + (bx - tile.x0);
                    simd::storeMasked(winnerRow, pass, simd::splati(std::int32_t(myIndex)));
                    // Ids now, not at shading: a later draw that does not write ids may win the pixel's
                    // colour and must leave this id in place.
                    if (t.writesId) simd::storeMasked(idPlane + std::size_t(y) * stride + bx, pass, id);
                }
            }
        }
    }
}

void raster(const Triangle& t, TileState& tile) {
    if (tile.target.samples > 1)
        rasterSamples<kMaxSamples>(t, tile);
    else
        rasterSamples<1>(t, tile);
}

// ---------------------------------------------------------------------------------------------
// Texture sampling (Shading.h), one lane at a time.

inline float decode(const SoftwareTexture& tex, std::uint32_t texel, int channel) {
    const DecodeTable& table = channel < 3 ? *tex.rgb : unormDecode();
    return table[(texel >> (8 * channel)) & 0xFFu];
}

inline float fractOf(float a) { return a - std::floor(a); }
inline float fractSafe(float a) { return std::fmin(fractOf(a), 0.99999994f); }
inline bool isPowerOfTwo(int n) { return (n & (n - 1)) == 0; }
inline std::int32_t ifloor(float a) { return simd::cvtRoundDown(a); }

// AoS (8-bit) linear: texel indices and 8-bit weight along one axis.
inline void aosLinearAxis(float coord, int size, Wrap wrap, int* i0, int* i1, int* weight) {
    const int last = size - 1;
    int c0;
    if (wrap == Wrap::Repeat && !isPowerOfTwo(size)) {
        float f = fractOf(coord) * float(size);
        f = f * 256.0f;
        c0 = std::int32_t(std::uint32_t(simd::cvtRound(f)) - 128u);  // wraps like the JIT for NaN/Inf
        *weight = c0 & 255;
        c0 >>= 8;
        if (c0 < 0) c0 = last;
        if (c0 > last) c0 = last;
        *i0 = c0;
        *i1 = c0 != last ? c0 + 1 : 0;
        return;
    }
    c0 = std::int32_t(std::uint32_t(simd::cvtRound(coord * float(size * 256))) - 128u);
    *weight = c0 & 255;
    c0 >>= 8;
    if (wrap == Wrap::Repeat) {
        c0 &= last;
        *i0 = c0;
        *i1 = c0 != last ? c0 + 1 : 0;
    } else {  // clamp to edge
        const bool lower = c0 >= 0, upper = c0 < last;
        if (!lower) c0 = 0;
        if (!upper) c0 = last;
        *i0 = c0;
        *i1 = c0 + (lower && upper ? 1 : 0);
    }
}

inline int aosNearestAxis(float coord, int size, Wrap wrap) {
    const int last = size - 1;
    if (wrap == Wrap::Repeat) {
        if (isPowerOfTwo(size)) return ifloor(coord * float(size)) & last;
        return simd::cvtTrunc(fractSafe(coord) * float(size));
    }
    const int c = ifloor(coord * float(size));
    return c < 0 ? 0 : (c > last ? last : c);
}

// 8-bit lerp with 8-bit weights, rounded (Shading.h).
inline std::uint32_t lerp8(int w, std::uint32_t a, std::uint32_t b) {
    std::uint32_t out = 0;
    for (int c = 0; c < 4; ++c) {
        const int v0 = int((a >> (8 * c)) & 0xFFu), v1 = int((b >> (8 * c)) & 0xFFu);
        const int v = v0 + ((w * (v1 - v0) + 128) >> 8);
        out |= std::uint32_t(v) << (8 * c);
    }
    return out;
}

// SoA (float) coordinate along one axis, linear filter.
inline void soaLinearAxis(float coord, int size, Wrap wrap, int* i0, int* i1, float* weight) {
    const int last = size - 1;
    const float length = float(size);
    float c;
    switch (wrap) {
        case Wrap::Repeat:
            c = (isPowerOfTwo(size) ? coord : fractOf(coord)) * length - 0.5f;
            break;
        case Wrap::ClampToEdge:
            c = std::fmin(coord * length, length) - 0.5f;
            c = std::fmax(c, 0.0f);
            break;
        case Wrap::MirroredRepeat:
        default: {
            const float half = coord * 0.5f;
            const float f = half - std::nearbyint(half);
            c = std::fmax(std::fabs(f + f), 0.0f) * length - 0.5f;
            break;
        }
    }
    int c0 = ifloor(c);
    *weight = c - float(c0);
    int c1 = c0 + 1;
    switch (wrap) {
        case Wrap::Repeat:
            if (isPowerOfTwo(size)) {
                c0 &= last;
                c1 &= last;
            } else {
                if (c0 < 0) c0 = last;
                if (c1 == size) c1 = 0;
            }
            break;
        case Wrap::ClampToEdge:
            if (c1 > last) c1 = last;
            break;
        case Wrap::MirroredRepeat:
        default:
            if (c0 < 0) c0 = 0;
            if (c1 > last) c1 = last;
            break;
    }
    *i0 = c0 < 0 ? 0 : (c0 > last ? last : c0);  // only NaN/Inf coordinates need this
    *i1 = c1 < 0 ? 0 : (c1 > last ? last : c1);
}

inline int soaNearestAxis(float coord, int size, Wrap wrap) {
    const int last = size - 1;
    int c;
    switch (wrap) {
        case Wrap::Repeat:
            if (isPowerOfTwo(size)) return ifloor(coord * float(size)) & last;
            c = simd::cvtTrunc(fractSafe(coord) * float(size));
            break;
        case Wrap::ClampToEdge:
            c = simd::cvtTrunc(coord * float(size));
            break;
        case Wrap::MirroredRepeat:
        default: {
            const float half = coord * 0.5f;
            const float f = half - std::nearbyint(half);
            c = simd::cvtTrunc(std::fmax(std::fabs(f + f), 0.0f) * float(size));
            break;
        }
    }
    return c < 0 ? 0 : (c > last ? last : c);
}

// A level's texel at (s, t) with one filter, on the AoS path: the packed bytes.
inline std::uint32_t aosTexel(const SoftwareTexture& tex, const SoftwareTexture::Level& level, Filter filter, float s,
                              float t) {
    const std::uint32_t* texels = level.texels.data();
    const int w = level.width, h = level.height;
    if (filter == Filter::Nearest)
        return texels[std::size_t(aosNearestAxis(t, h, tex.wrapT)) * w + aosNearestAxis(s, w, tex.wrapS)];
    int x0, x1, y0, y1, ws, wt;
    aosLinearAxis(s, w, tex.wrapS, &x0, &x1, &ws);
    aosLinearAxis(t, h, tex.wrapT, &y0, &y1, &wt);
    const std::uint32_t row0 = lerp8(ws, texels[std::size_t(y0) * w + x0], texels[std::size_t(y0) * w + x1]);
    const std::uint32_t row1 = lerp8(ws, texels[std::size_t(y1) * w + x0], texels[std::size_t(y1) * w + x1]);
    return lerp8(wt, row0, row1);
}

// The same on the SoA path: four decoded floats.
inline void soaTexel(const SoftwareTexture& tex, const SoftwareTexture::Level& level, Filter filter, float s, float t,
                     float out[4]) {
    const std::uint32_t* texels = level.texels.data();
    const int w = level.width, h = level.height;
    if (filter == Filter::Nearest) {
        const std::uint32_t texel =
            texels[std::size_t(soaNearestAxis(t, h, tex.wrapT)) * w + soaNearestAxis(s, w, tex.wrapS)];
        for (int c = 0; c < 4; ++c) out[c] = decode(tex, texel, c);
        return;
    }
    int x0, x1, y0, y1;
    float ws, wt;
    soaLinearAxis(s, w, tex.wrapS, &x0, &x1, &ws);
    soaLinearAxis(t, h, tex.wrapT, &y0, &y1, &wt);
    const std::uint32_t t00 = texels[std::size_t(y0) * w + x0], t01 = texels[std::size_t(y0) * w + x1];
    const std::uint32_t t10 = texels[std::size_t(y1) * w + x0], t11 = texels[std::size_t(y1) * w + x1];
    for (int c = 0; c < 4; ++c) {
        const float a00 = decode(tex, t00, c), a01 = decode(tex, t01, c), a10 = decode(tex, t10, c),
                    a11 = decode(tex, t11, c);
        const float r0 = simd::fmas(ws, a01 - a00, a00);
        const float r1 = simd::fmas(ws, a11 - a10, a10);
        out[c] = simd::fmas(wt, r1 - r0, r0);
    }
}

// The level of detail of one pixel's quad (Shading.h): the coordinates' differences across the
// quad, and what they select in a texture.
struct Footprint {
    float dsdx = 0.0f, dtdx = 0.0f, dsdy = 0.0f, dtdy = 0.0f;
};
struct Lod {
    bool minified = false;
    int level0 = 0, level1 = 0;
    float blend = 0.0f;  // of level1, mipmaps linear only
};

inline Lod levelOfDetail(const SoftwareTexture& tex, const Footprint& f) {
    const float width = float(tex.levels[0].width), height = float(tex.levels[0].height);
    const float sx = f.dsdx * width, sy = f.dsdy * width, tx = f.dtdx * height, ty = f.dtdy * height;
    const float rx = sx * sx + tx * tx, ry = sy * sy + ty * ty;
    const float rho2 = rx > ry ? rx : ry;  // maxps
    const int last = int(tex.levels.size()) - 1;
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(rho2);
    const int exponent = int((bits >> 23) & 0xFFu) - 127;
    Lod lod;
    if (tex.mipmaps != MipFilter::Linear) {
        lod.minified = rho2 > 1.0f;
        if (tex.mipmaps == MipFilter::Nearest) lod.level0 = std::clamp((exponent + 1) >> 1, 0, last);
        lod.level1 = lod.level0;
        return lod;
    }
    const float mantissa = std::bit_cast<float>((bits & 0x007FFFFFu) | 0x3F800000u);
    const float value = (float(exponent - 1) + mantissa) * 0.5f;
    lod.minified = value > 0.0f;
    const float whole = std::floor(value);
    if (!(whole >= 0.0f)) return lod;  // level 0 alone (NaN cannot reach here: its exponent is 128)
    if (whole >= float(last)) {
        lod.level0 = lod.level1 = last;
        return lod;
    }
    lod.level0 = int(whole);
    lod.level1 = lod.level0 + 1;
    lod.blend = value - whole;
    return lod;
}

// Texel at (s, t) as four floats; `footprint` is read only where the texture needs a level of
// detail (SoftwareTexture::lod).
inline void sample(const SoftwareTexture& tex, float s, float t, const Footprint& footprint, float out[4]) {
    Lod lod;
    if (tex.lod()) lod = levelOfDetail(tex, footprint);
    const Filter filter = lod.minified ? tex.minFilter : tex.filter;
    const SoftwareTexture::Level& level0 = tex.levels[std::size_t(lod.level0)];
    const bool blend = lod.blend > 0.0f;
    if (tex.aos) {
        std::uint32_t texel = aosTexel(tex, level0, filter, s, t);
        if (blend) {  // the weight in 8 bits, truncated
            const std::uint32_t next = aosTexel(tex, tex.levels[std::size_t(lod.level1)], filter, s, t);
            texel = lerp8(int(lod.blend * 256.0f), texel, next);
        }
        for (int c = 0; c < 4; ++c) out[c] = decode(tex, texel, c);
        return;
    }
    soaTexel(tex, level0, filter, s, t, out);
    if (!blend) return;
    float next[4];
    soaTexel(tex, tex.levels[std::size_t(lod.level1)], filter, s, t, next);
    for (int c = 0; c < 4; ++c) out[c] = simd::fmas(lod.blend, next[c] - out[c], out[c]);
}

// A texture at eight pixels' coordinates (s, t) and their quads' footprints; lanes not in `lanes`
// read 0.
inline void sampleLanes(const SoftwareTexture& tex, const float s[8], const float t[8], const Footprint footprints[8],
                        unsigned lanes, F8 out[4]) {
    float rgba[4][8];
    for (int l = 0; l < 8; ++l) {
        float texel[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        if (lanes & (1u << l)) sample(tex, s[l], t[l], footprints[l], texel);
        for (int c = 0; c < 4; ++c) rgba[c][l] = texel[c];
    }
    for (int c = 0; c < 4; ++c) out[c] = simd::loadf(rgba[c]);
}

// ---------------------------------------------------------------------------------------------
// Shading (Shading.h)

struct Plane {
    float a0, dadx, dady;
};

// The BRDF of pipeline/Backend.h in the operations mesh.frag gives llvmpipe: dot products reduced
// from the last component, normalize as v · (1 / sqrt(dot(v, v))), clamp as min(max(x, 0), 1),
// mix written out as a·(1 − t) + b·t, no fused operations.
constexpr float kPi = 3.14159265f;        // mesh.frag's constants, as GLSL reads them
constexpr float kDielectricF0 = 0.04f;

struct Vec3 {
    F8 x, y, z;
};

inline F8 saturate(F8 a) { return simd::min(simd::max(a, simd::splat(0.0f)), simd::splat(1.0f)); }
inline F8 pow5(F8 x) {
    const F8 x2 = x * x;
    return (x2 * x2) * x;
}

// pipeline/Brdf.h's split-sum fit, eight lanes at a time, in the order brdf::dfg states. (Written
// out here rather than instantiated from Brdf.h's template: that would be compiled without this
// file's SIMD target, and F8 cannot cross between the two: passing one by value crashed.)
inline F8 dfgPolynomial(const std::array<float, 18>& c, F8 x, F8 r, F8 u, F8 f5) {
    const auto k = [&c](int i) { return simd::splat(c[std::size_t(i)]); };
    const F8 inR = k(0) + r * (k(1) + r * (k(2) + r * (k(3) + r * (k(4) + r * k(5)))));
    const F8 inX = x * ((k(6) + r * (k(7) + r * k(8))) + x * k(9));
    const F8 inU = u * (((k(10) + r * (k(11) + r * (k(12) + r * k(13)))) + x * k(14)) + u * k(15));
    const F8 inF = f5 * (k(16) + r * k(17));
    return ((inR + inX) + inU) + inF;
}
inline void dfg(F8 x, F8 r, F8& a, F8& b) {
    const F8 one = simd::splat(1.0f);
    const F8 alpha = r * r;
    const F8 u = x * (one / simd::sqrt(simd::max(x * x + simd::splat(4.0f) * (alpha * alpha), simd::splat(1.0e-30f))));
    const F8 f5 = pow5(one - x);
    a = saturate(dfgPolynomial(brdf::kDfgA, x, r, u, f5));
    b = saturate(dfgPolynomial(brdf::kDfgB, x, r, u, f5));
}
inline F8 dot(const Vec3& a, const Vec3& b) { return (a.z * b.z + a.y * b.y) + a.x * b.x; }
inline Vec3 normalize(const Vec3& a) {
    const F8 rsq = simd::splat(1.0f) / simd::sqrt(dot(a, a));
    return {a.x * rsq, a.y * rsq, a.z * rsq};
}

// mesh.frag's ggx(): the GGX lobe's visibility × distribution at alpha² (visibility 0 where its
// denominator is 0).
inline F8 ggx(F8 nl, F8 nv, F8 nh, F8 alpha2) {
    const F8 zero = simd::splat(0.0f), one = simd::splat(1.0f);
    const F8 sum =
        nl * simd::sqrt((nv * nv) * (one - alpha2) + alpha2) + nv * simd::sqrt((nl * nl) * (one - alpha2) + alpha2);
    const F8 visibility = simd::selectf(simd::lt(zero, sum), simd::splat(0.5f) / sum, zero);
    const F8 f = (nh * nh) * (alpha2 - one) + one;
    return visibility * (alpha2 / simd::max(simd::splat(kPi) * (f * f), simd::splat(1.0e-30f)));
}

// The Khronos renderer's getIBLGGXFresnel (mesh.frag's iblFresnel).
inline F8 iblFresnel(F8 f0, F8 r, F8 c5, F8 a, F8 b) {
    const F8 one = simd::splat(1.0f);
    const F8 fss = (f0 + (simd::max(one - r, f0) - f0) * c5) * a + b;
    const F8 ems = one - (a + b);
    const F8 favg = f0 + (one - f0) / simd::splat(21.0f);
    return fss + (ems * fss) * favg / (one - favg * ems);
}

struct Light {
    explicit Light(const DrawShading& s)
        : eye{simd::splat(s.eye.x), simd::splat(s.eye.y), simd::splat(s.eye.z)},
          metallicFactor(simd::splat(s.metallic)),
          roughnessFactor(simd::splat(s.roughness)),
          environment(simd::splat(s.environment)),
          occlusionStrength(simd::splat(s.occlusionStrength)),
          environmentSpecular(s.environmentSpecular),
          mix(metalMixOf(s.metallic, s.metallicRoughness != nullptr, s.specularGlossiness)),
          emission{simd::splat(s.emission.r), simd::splat(s.emission.g), simd::splat(s.emission.b)},
          lights(s.lights),
          map(s.environmentMap) {
        if (map)
            for (int i = 0; i < 9; ++i)
                for (int c = 0; c < 3; ++c) sh[i][c] = simd::splat(map->sh[std::size_t(i)][c]);
    }

    // The environment map's diffuse light E(n)/π (mesh.frag's environmentDiffuse), at least 0, or
    // the uniform environment's radiance.
    void diffuseLight(const Vec3& n, F8 out[3]) const {
        if (!map) {
            out[0] = out[1] = out[2] = environment;
            return;
        }
        const F8 zero = simd::splat(0.0f), one = simd::splat(1.0f), three = simd::splat(3.0f);
        const F8 b[9] = {
            zero, n.y, n.z, n.x, n.x * n.y, n.y * n.z, three * (n.z * n.z) - one, n.x * n.z, n.x * n.x - n.y * n.y};
        for (int c = 0; c < 3; ++c) {
            F8 e = sh[0][c];
            for (int i = 1; i < 9; ++i) e = e + sh[i][c] * b[i];
            out[c] = simd::max(e, zero);
        }
    }

    // The environment map's specular light toward v from a surface of normal n and roughness r
    // (mesh.frag's environmentSpecular: the level's texels bilinear, the levels linear, as llvmpipe
    // filters a float texture), or the uniform environment's radiance.
    void specularLight(const Vec3& n, const Vec3& v, F8 r, F8 out[3]) const {
        if (!map) {
            out[0] = out[1] = out[2] = environment;
            return;
        }
        const F8 twice = simd::splat(2.0f) * dot(n, v);
        const Vec3 d = normalize({n.x * twice - v.x, n.y * twice - v.y, n.z * twice - v.z});
        constexpr int kLanes = simd::kLanes;
        float x[kLanes], y[kLanes], z[kLanes], roughness[kLanes], rgb[3][kLanes];
        simd::storef(x, d.x);
        simd::storef(y, d.y);
        simd::storef(z, d.z);
        simd::storef(roughness, r);
        for (int lane = 0; lane < kLanes; ++lane) {
            const glm::vec3 c = sampleEnvironment(*map, equirectUv({x[lane], y[lane], z[lane]}),
                                                  roughness[lane] * float(EnvironmentMap::kSpecularLevels - 1));
            for (int k = 0; k < 3; ++k) rgb[k][lane] = c[k];
        }
        for (int k = 0; k < 3; ++k) out[k] = simd::loadf(rgb[k]);
    }

    // What the maps give one pixel (mesh.frag): the material's factors where there is no map.
    struct Surface {
        F8 metallic, roughness;
        const F8* occlusion;  // the occlusion map's red, or nullptr: none
        F8 emission[3];
        const F8* specular = nullptr;  // specular-glossiness: the dielectric's f0 per channel (no metal)
        const F8* coat = nullptr;      // the clear coat's factor × its map, or nullptr: no coat
        F8 coatRoughness{};
        Vec3 coatNormal{};
        Vec3 position{};  // world space: where the punctual lights are seen from
    };
    // mix(dielectric, metal, metallic) as mesh.frag's metalMix writes it.
    F8 metalMix(F8 dielectric, F8 metal, F8 metallic) const {
        if (mix == MetalMix::Dielectric) return dielectric;
        if (mix == MetalMix::Metal) return metal;
        return dielectric * (simd::splat(1.0f) - metallic) + metal * metallic;
    }

    // Linear rgb of base colour `base` at a pixel with normal n and view direction v (both unit).
    void shade(const F8 base[4], const Vec3& n, const Vec3& v, const Surface& surface, F8 out[3]) const {
        const F8 zero = simd::splat(0.0f), one = simd::splat(1.0f), pi = simd::splat(kPi);
        const F8 f0 = simd::splat(kDielectricF0);
        const F8 metallic = surface.metallic;
        const F8 r = surface.roughness;
        const F8 alpha2 = (r * r) * (r * r);
        const F8 nv = saturate(dot(n, v));
        const F8 cv = pow5(one - nv);

        // The environment.
        F8 dielectric[3], metal[3] = {zero, zero, zero};  // (no metal terms with specular-glossiness)
        F8 diffuse[3], reflected[3];
        diffuseLight(n, diffuse);
        if (!environmentSpecular) {
            for (int c = 0; c < 3; ++c) dielectric[c] = base[c] * diffuse[c];  // its diffuse lobe alone
        } else {
            specularLight(n, v, r, reflected);
            F8 a, b;
            dfg(nv, r, a, b);
            if (surface.specular) {
                for (int c = 0; c < 3; ++c) {
                    const F8 fd = iblFresnel(surface.specular[c], r, cv, a, b);
                    dielectric[c] = (base[c] * diffuse[c]) * (one - fd) + reflected[c] * fd;
                }
            } else {
                const F8 fd = iblFresnel(f0, r, cv, a, b);
                for (int c = 0; c < 3; ++c) {
                    dielectric[c] = (base[c] * diffuse[c]) * (one - fd) + reflected[c] * fd;
                    if (mix != MetalMix::Dielectric) metal[c] = iblFresnel(base[c], r, cv, a, b) * reflected[c];
                }
            }
        }
        // The clear coat over the environment's colour; the light's is then gathered from 0.
        F8 k = zero, coated[3] = {zero, zero, zero};
        if (surface.coat) {
            k = *surface.coat * (f0 + (one - f0) * pow5(one - saturate(dot(surface.coatNormal, v))));
            const F8 occlusion = surface.occlusion ? one + occlusionStrength * (*surface.occlusion - one) : one;
            F8 coatLight[3] = {zero, zero, zero};  // the coat's reflection of the environment
            if (environmentSpecular) specularLight(surface.coatNormal, v, surface.coatRoughness, coatLight);
            for (int c = 0; c < 3; ++c) {
                coated[c] = surface.specular ? dielectric[c] : metalMix(dielectric[c], metal[c], metallic);
                coated[c] = environmentSpecular ? coated[c] * (one - k) + coatLight[c] * k : coated[c] * (one - k);
                if (surface.occlusion) coated[c] = coated[c] * occlusion;
                dielectric[c] = metal[c] = zero;
            }
        } else if (surface.occlusion) {
            const F8 occlusion = one + occlusionStrength * (*surface.occlusion - one);
            for (int c = 0; c < 3; ++c) {
                dielectric[c] = dielectric[c] * occlusion;
                if (!surface.specular) metal[c] = metal[c] * occlusion;
            }
        }

        // The lights: each light's l and E per pixel, its lobes summed into the dielectric and metal
        // terms (and the clear coat's), in light order. The default directional light is the
        // one-light case: with l and E the same in every channel, these are mesh.frag's operations
        // for it as well as for FRUGAL_LIGHTS (DrawShading::lights).
        const Vec3& nc = surface.coatNormal;
        const F8 cr = surface.coatRoughness;
        const F8 coatAlpha2 = (cr * cr) * (cr * cr);
        const F8 ncv = surface.coat ? saturate(dot(nc, v)) : zero;
        F8 coatSpecular[3] = {zero, zero, zero};
        for (const FrameLight& light : lights) {
            Vec3 l;
            F8 e[3];
            lightAt(light, surface.position, l, e);
            const Vec3 h = normalize({l.x + v.x, l.y + v.y, l.z + v.z});
            const F8 nl = saturate(dot(n, l)), nh = saturate(dot(n, h)), vh = saturate(dot(v, h));
            const F8 lobe = ggx(nl, nv, nh, alpha2);
            const F8 ch = pow5(one - vh);
            for (int c = 0; c < 3; ++c) {
                const F8 radiance = e[c] * nl;
                const F8 specular = radiance * lobe;
                if (surface.specular) {
                    const F8 fl = surface.specular[c] + (one - surface.specular[c]) * ch;
                    dielectric[c] = dielectric[c] + ((base[c] * (radiance / pi)) * (one - fl) + specular * fl);
                } else {
                    const F8 fl = f0 + (one - f0) * ch;
                    dielectric[c] = dielectric[c] + ((base[c] * (radiance / pi)) * (one - fl) + specular * fl);
                    if (mix != MetalMix::Dielectric) metal[c] = metal[c] + (base[c] + (one - base[c]) * ch) * specular;
                }
            }
            if (surface.coat) {
                const F8 ncl = saturate(dot(nc, l));
                const F8 coatLobe = ncl * ggx(ncl, ncv, saturate(dot(nc, h)), coatAlpha2);
                for (int c = 0; c < 3; ++c) coatSpecular[c] = coatSpecular[c] + e[c] * coatLobe;
            }
        }
        for (int c = 0; c < 3; ++c) {
            const F8 lit = surface.specular ? dielectric[c] : metalMix(dielectric[c], metal[c], metallic);
            out[c] = surface.coat
                         ? (coated[c] + (lit * (one - k) + coatSpecular[c] * k)) + surface.emission[c] * (one - k)
                         : lit + surface.emission[c];
        }
    }

    // ShadingModel::Lambert's rgb (mesh.frag's FRUGAL_LAMBERT): the environment's radiance plus each
    // light's E·(n·l)/π, on the base colour, plus the emission.
    void lambert(const F8 base[4], const Vec3& n, const Vec3& position, const F8 emitted[3], F8 out[3]) const {
        const F8 pi = simd::splat(kPi);
        F8 irradiance[3];
        diffuseLight(n, irradiance);
        for (const FrameLight& light : lights) {
            Vec3 l;
            F8 e[3];
            lightAt(light, position, l, e);
            const F8 nl = saturate(dot(n, l)) / pi;
            for (int c = 0; c < 3; ++c) irradiance[c] = irradiance[c] + e[c] * nl;
        }
        for (int c = 0; c < 3; ++c) out[c] = base[c] * irradiance[c] + emitted[c];
    }

    // The direction l toward `light` and its intensity e at world position p, as mesh.frag's lightAt
    // (for the default directional light: l = toLight, e = its intensity).
    static void lightAt(const FrameLight& light, const Vec3& p, Vec3& l, F8 e[3]) {
        const F8 zero = simd::splat(0.0f), one = simd::splat(1.0f);
        for (int c = 0; c < 3; ++c) e[c] = simd::splat(light.intensity[c]);
        const Vec3 axis{simd::splat(light.direction.x), simd::splat(light.direction.y), simd::splat(light.direction.z)};
        l = {simd::neg(axis.x), simd::neg(axis.y), simd::neg(axis.z)};
        if (light.type == LightType::Directional) return;
        const Vec3 pointToLight{simd::splat(light.position.x) - p.x, simd::splat(light.position.y) - p.y,
                                simd::splat(light.position.z) - p.z};
        l = normalize(pointToLight);
        const F8 d2 = dot(pointToLight, pointToLight);
        F8 fade = one / d2;
        if (light.range > 0.0f) {
            const F8 q = d2 / simd::splat(light.range * light.range);
            fade = simd::max(simd::min(one - q * q, one), zero) / d2;
        }
        for (int c = 0; c < 3; ++c) e[c] = e[c] * fade;
        if (light.type == LightType::Spot) {
            const F8 cosine = simd::neg(dot(axis, l)), outer = simd::splat(light.outerCos);
            const F8 t = (cosine - outer) / simd::splat(light.innerCos - light.outerCos);
            const F8 inside = simd::selectf(simd::lt(cosine, simd::splat(light.innerCos)), t * t, one);
            const F8 cone = simd::selectf(simd::lt(outer, cosine), inside, zero);
            for (int c = 0; c < 3; ++c) e[c] = e[c] * cone;
        }
    }

    Vec3 eye;
    F8 metallicFactor, roughnessFactor, environment, occlusionStrength;
    bool environmentSpecular;
    // The draw's side of the metal mix (Backend.h): the metal terms are not computed for a
    // dielectric (the dielectric's are, as mesh.frag leaves them to its compiler).
    MetalMix mix;
    F8 emission[3];
    std::span<const FrameLight> lights;
    const EnvironmentMap* map;  // DrawShading::environmentMap
    F8 sh[9][3]{};              // its coefficients, when there is one
};

// FrameParams::tonemap on a pixel's linear rgb, in mesh.frag's operations (pipeline/Backend.h).
void toneMap(ToneMap op, F8 rgb[3]) {
    const F8 zero = simd::splat(0.0f), one = simd::splat(1.0f);
    if (op == ToneMap::PbrNeutral) {
        const float start = 0.8f - 0.04f, d = 1.0f - start;  // folded in float, as the compiler folds them
        const F8 x = simd::min(rgb[0], simd::min(rgb[1], rgb[2]));
        const F8 offset =
            simd::selectf(simd::lt(x, simd::splat(0.08f)), x - (simd::splat(6.25f) * x) * x, simd::splat(0.04f));
        F8 c[3];
        for (int k = 0; k < 3; ++k) c[k] = rgb[k] - offset;
        const F8 peak = simd::max(c[0], simd::max(c[1], c[2]));
        const F8 newPeak = one - simd::splat(d * d) / ((peak + simd::splat(d)) - simd::splat(start));
        const F8 scale = newPeak / peak;
        const F8 g = one - one / (simd::splat(0.15f) * (peak - newPeak) + one);
        const I8 below = simd::lt(peak, simd::splat(start));
        for (int k = 0; k < 3; ++k) rgb[k] = simd::selectf(below, c[k], (c[k] * scale) * (one - g) + newPeak * g);
        return;
    }
    if (op != ToneMap::Aces) return;
    // The matrices by columns, as GLSL's mat3 constructor takes them; each product summed from the
    // first column.
    static constexpr float in[3][3] = {
        {0.59719f, 0.07600f, 0.02840f}, {0.35458f, 0.90834f, 0.13383f}, {0.04823f, 0.01566f, 0.83777f}};
    static constexpr float out[3][3] = {
        {1.60475f, -0.10208f, -0.00327f}, {-0.53108f, 1.10813f, -0.07276f}, {-0.07367f, -0.00605f, 1.07602f}};
    const auto product = [](const float(&m)[3][3], const F8 v[3], F8 r[3]) {
        for (int k = 0; k < 3; ++k)
            r[k] = (simd::splat(m[0][k]) * v[0] + simd::splat(m[1][k]) * v[1]) + simd::splat(m[2][k]) * v[2];
    };
    F8 c[3], fitted[3];
    product(in, rgb, c);
    for (int k = 0; k < 3; ++k) {
        const F8 a = c[k] * (c[k] + simd::splat(0.0245786f)) - simd::splat(0.000090537f);
        const F8 b = c[k] * (simd::splat(0.983729f) * c[k] + simd::splat(0.4329510f)) + simd::splat(0.238081f);
        fitted[k] = a / b;
    }
    product(out, fitted, c);
    for (int k = 0; k < 3; ++k) rgb[k] = simd::min(simd::max(c[k], zero), one);
}

template <int Samples>
void shadeSamples(std::uint32_t index, const DrawShading& shading, TileState& tile) {
    const Triangle& t = *tile.won[index];
    const int x0 = t.x0 > tile.x0 ? t.x0 : tile.x0;
    const int x1 = t.x1 < tile.x1 - 1 ? t.x1 : tile.x1 - 1;
    const int y0 = t.y0 > tile.y0 ? t.y0 : tile.y0;
    const int y1 = t.y1 < tile.y1 - 1 ? t.y1 : tile.y1 - 1;

    // Plane equations (Rasterizer.h, 4.): 1/w linear, the varyings premultiplied by 1/w. A
    // multisampled target's planes are at the pixels' corners, read at their centres (6.): the
    // offsets are 0.5 and 0 or 0 and 0.5 (adding 0 is exact).
    const SetupVertex& v0 = *t.v[0];
    const SetupVertex& v1 = *t.v[1];
    const SetupVertex& v2 = *t.v[2];
    constexpr int samples = Samples;
    constexpr float offset = samples > 1 ? 0.0f : 0.5f;
    // Pixel coordinates + 0.5 when multisampled (the one-sample case adds nothing).
    const auto centred = [](auto v) {
        if constexpr (samples == 1)
            return v;
        else if constexpr (std::is_same_v<decltype(v), float>)
            return v + 0.5f;
        else
            return v + simd::splat(0.5f);
    };
    const float x0c = v0.x - offset, y0c = v0.y - offset;
    const float dx01 = v0.x - v1.x, dy01 = v0.y - v1.y;
    const float dx20 = v2.x - v0.x, dy20 = v2.y - v0.y;
    const float e = dx01 * dy20, f = dy01 * dx20;
    const float ooa = 1.0f / (e - f);
    const float dx20o = dx20 * ooa, dy20o = dy20 * ooa, dx01o = dx01 * ooa, dy01o = dy01 * ooa;
    const auto plane = [&](float a0, float a1, float a2) {
        const float da01 = a0 - a1, da20 = a2 - a0;
        Plane p;
        p.dadx = da01 * dy20o - da20 * dy01o;
        p.dady = da20 * dx01o - da01 * dx20o;
        p.a0 = a0 - (p.dadx * x0c + p.dady * y0c);
        return p;
    };
    const Plane w = plane(v0.oow, v1.oow, v2.oow);
    const bool textured = shading.texture != nullptr;
    const bool mapped = shading.mapped();
    const bool colored = shading.colors;
    const bool normalMapped = shading.normalMap != nullptr;
    const bool tangentSpace = shading.tangentSpace();
    const bool lod = shading.lod();
    Plane a[kAttributes];
    // Varyings eight at a time (the same operations per lane as plane()), the rest alone; the
    // tangent basis (12–17) only for a normal map.
    const int planes = tangentSpace ? kAttributes : 12;
    int first = 0;
    for (; first + 8 <= planes; first += 8) {
        const F8 a0 = simd::loadf(v0.a + first) * simd::splat(v0.oow);
        const F8 a1 = simd::loadf(v1.a + first) * simd::splat(v1.oow);
        const F8 a2 = simd::loadf(v2.a + first) * simd::splat(v2.oow);
        const F8 da01 = a0 - a1, da20 = a2 - a0;
        const F8 dadx = da01 * simd::splat(dy20o) - da20 * simd::splat(dy01o);
        const F8 dady = da20 * simd::splat(dx01o) - da01 * simd::splat(dx20o);
        const F8 at0 = a0 - (dadx * simd::splat(x0c) + dady * simd::splat(y0c));
        float s0[8], sx[8], sy[8];
        simd::storef(s0, at0);
        simd::storef(sx, dadx);
        simd::storef(sy, dady);
        for (int i = 0; i < 8; ++i) a[first + i] = {s0[i], sx[i], sy[i]};
    }
    for (int i = first; i < planes; ++i) a[i] = plane(v0.a[i] * v0.oow, v1.a[i] * v1.oow, v2.a[i] * v2.oow);
    // The varyings this draw reads: normal, world position, and colour and uv when it has them.
    int used[kAttributes];
    int usedCount = 0;
    for (int i = 0; i < kAttributes; ++i)
        if ((!shading.unlit && (i < 3 || (i >= 9 && i < 12))) || (colored && i >= 3 && i < 7) ||
            (mapped && i >= 7 && i < 9) || (tangentSpace && i >= 12))
            used[usedCount++] = i;

    const F8 zero = simd::splat(0.0f), one = simd::splat(1.0f), c255 = simd::splat(255.0f);
    const Light light(shading);
    const F8 factor[4] = {simd::splat(shading.factor.r), simd::splat(shading.factor.g), simd::splat(shading.factor.b),
                          simd::splat(shading.factor.a)};
    const I8 me = simd::splati(std::int32_t(index));
    const I8 lane = simd::ramp(0);
    const std::uint32_t stride = std::uint32_t(tile.target.stride);

    for (int y = y0; y <= y1; ++y) {
        const F8 py = simd::splat(centred(float(y)));
        std::uint32_t* winnerRow = tile.winner + (y - tile.y0) * kTileSize;
        for (int bx = x0 & ~7; bx <= x1; bx += 8) {
            // The samples this triangle owns (one for a single-sampled target), and the pixels with any.
            I8 owned[kMaxSamples];
            I8 mask = simd::splati(0);
            for (int k = 0; k < samples; ++k) {
                owned[k] = simd::eq(simd::loadi(winnerRow + k * TileState::kPlane + (bx - tile.x0)), me);
                mask = mask | owned[k];
            }
            if (simd::laneBits(mask) == 0) continue;
            const F8 px = centred(simd::tofloat(lane + simd::splati(bx)));
            // A plane at these pixels of row `row`.
            const auto at = [&](const Plane& p, F8 row) {
                return simd::fma(simd::splat(p.dady), row, simd::fma(simd::splat(p.dadx), px, simd::splat(p.a0)));
            };
            const F8 oow = one / at(w, py);
            F8 value[kAttributes];
            for (int k = 0; k < usedCount; ++k) value[used[k]] = at(a[used[k]], py) * oow;

            float s[8] = {}, tt[8] = {};
            const unsigned lanes = simd::laneBits(mask);
            if (mapped) {
                simd::storef(s, value[7]);
                simd::storef(tt, value[8]);
            }
            // Each pixel's quad, where a texture needs its level of detail: uvs interpolated as
            // above on the quads' two rows (helper pixels included), differences across each quad.
            Footprint footprints[8];
            if (lod) {
                float u[2][8], v[2][8];
                for (int row = 0; row < 2; ++row) {
                    const F8 qy = simd::splat(centred(float((y & ~1) + row)));
                    const F8 r = one / at(w, qy);
                    simd::storef(u[row], at(a[7], qy) * r);
                    simd::storef(v[row], at(a[8], qy) * r);
                }
                for (int l = 0; l < 8; ++l) {
                    const int left = l & ~1;  // bx is even: lane parity is x parity
                    footprints[l] = {u[0][left + 1] - u[0][left], v[0][left + 1] - v[0][left], u[1][left] - u[0][left],
                                     v[1][left] - v[0][left]};
                }
            }
            F8 texel[4] = {one, one, one, one};
            if (textured) sampleLanes(*shading.texture, s, tt, footprints, lanes, texel);
            F8 base[4];
            for (int c = 0; c < 4; ++c) base[c] = (colored ? factor[c] * value[3 + c] : factor[c]) * texel[c];
            if (shading.alphaMode == AlphaMode::Mask) {
                const I8 killed = simd::lt(base[3], simd::splat(shading.alphaCutoff)) & mask;
                if (simd::laneBits(killed) != 0) {
                    for (int k = 0; k < samples; ++k) {
                        simd::storeMasked(winnerRow + k * TileState::kPlane + (bx - tile.x0), killed & owned[k],
                                          simd::splati(std::int32_t(kKilled)));
                        owned[k] = simd::andnot(killed, owned[k]);
                    }
                    mask = simd::andnot(killed, mask);
                    if (simd::laneBits(mask) == 0) continue;
                }
            }

            F8 linear[3] = {base[0], base[1], base[2]};
            if (shading.bare) {  // mesh.frag's FRUGAL_BARE
                F8 emission[3] = {light.emission[0], light.emission[1], light.emission[2]};
                if (shading.emissive) {
                    F8 emitted[4];
                    sampleLanes(*shading.emissive, s, tt, footprints, lanes, emitted);
                    for (int c = 0; c < 3; ++c) emission[c] = emission[c] * emitted[c];
                }
                for (int c = 0; c < 3; ++c) linear[c] = emission[c] + linear[c];
            } else if (!shading.unlit) {
                Vec3 n = normalize({value[0], value[1], value[2]});
                if (!t.front) n = {simd::neg(n.x), simd::neg(n.y), simd::neg(n.z)};
                F8 emission[3] = {light.emission[0], light.emission[1], light.emission[2]};
                if (shading.emissive) {
                    F8 emitted[4];
                    sampleLanes(*shading.emissive, s, tt, footprints, lanes, emitted);
                    for (int c = 0; c < 3; ++c) emission[c] = emission[c] * emitted[c];
                }
                if (shading.lambert) {
                    light.lambert(base, n, {value[9], value[10], value[11]}, emission, linear);
                } else {
                    Vec3 tangent{}, bitangent{};
                    if (tangentSpace) {
                        tangent = normalize({value[12], value[13], value[14]});
                        bitangent = normalize({value[15], value[16], value[17]});
                        if (!t.front) {
                            tangent = {simd::neg(tangent.x), simd::neg(tangent.y), simd::neg(tangent.z)};
                            bitangent = {simd::neg(bitangent.x), simd::neg(bitangent.y), simd::neg(bitangent.z)};
                        }
                    }
                    // A normal map's vector: rgb · 2 − 1, x and y · scale, normalised, in the basis.
                    const auto mappedNormal = [&](const SoftwareTexture& map, float scaleFactor, const Vec3& normal) {
                        F8 stored[4];
                        sampleLanes(map, s, tt, footprints, lanes, stored);
                        const F8 two = simd::splat(2.0f), scale = simd::splat(scaleFactor);
                        const Vec3 m = normalize(
                            {(stored[0] * two - one) * scale, (stored[1] * two - one) * scale, stored[2] * two - one});
                        return Vec3{(tangent.x * m.x + bitangent.x * m.y) + normal.x * m.z,
                                    (tangent.y * m.x + bitangent.y * m.y) + normal.y * m.z,
                                    (tangent.z * m.x + bitangent.z * m.y) + normal.z * m.z};
                    };
                    Vec3 coatNormal = n;  // the clear coat's: before the base normal map
                    if (shading.clearcoatNormalMap)
                        coatNormal = mappedNormal(*shading.clearcoatNormalMap, shading.clearcoatNormalScale, n);
                    if (normalMapped) n = normalize(mappedNormal(*shading.normalMap, shading.normalScale, n));
                    const Vec3 v =
                        normalize({light.eye.x - value[9], light.eye.y - value[10], light.eye.z - value[11]});
                    Light::Surface surface{
                        light.metallicFactor, light.roughnessFactor, nullptr, {emission[0], emission[1], emission[2]}};
                    F8 map[4], specular[3];
                    if (shading.specularGlossiness) {
                        F8 glossiness = simd::splat(shading.glossiness);
                        for (int c = 0; c < 3; ++c) specular[c] = simd::splat(shading.specular[c]);
                        if (shading.specularGlossinessMap) {
                            sampleLanes(*shading.specularGlossinessMap, s, tt, footprints, lanes, map);
                            for (int c = 0; c < 3; ++c) specular[c] = specular[c] * map[c];
                            glossiness = glossiness * map[3];
                        }
                        surface.specular = specular;
                        surface.roughness = one - glossiness;
                    }
                    if (shading.metallicRoughness) {
                        sampleLanes(*shading.metallicRoughness, s, tt, footprints, lanes, map);
                        surface.metallic = surface.metallic * map[2];
                        surface.roughness = surface.roughness * map[1];
                    }
                    F8 occlusion[4];
                    if (shading.occlusion) {
                        sampleLanes(*shading.occlusion, s, tt, footprints, lanes, occlusion);
                        surface.occlusion = &occlusion[0];
                    }
                    F8 coat = simd::splat(shading.clearcoat);
                    if (shading.clearcoat > 0.0f) {
                        surface.coatRoughness = simd::splat(shading.clearcoatRoughness);
                        if (shading.clearcoatMap) {
                            sampleLanes(*shading.clearcoatMap, s, tt, footprints, lanes, map);
                            coat = coat * map[0];
                        }
                        if (shading.clearcoatRoughnessMap) {
                            sampleLanes(*shading.clearcoatRoughnessMap, s, tt, footprints, lanes, map);
                            surface.coatRoughness = surface.coatRoughness * map[1];
                        }
                        surface.coat = &coat;
                        surface.coatNormal = coatNormal;
                    }
                    surface.position = {value[9], value[10], value[11]};
                    light.shade(base, n, v, surface, linear);
                }
            }

            toneMap(shading.tonemap, linear);
            if (tile.target.linear != nullptr) {  // a float target: the linear colour as it is
                const F8 alpha = shading.alphaMode == AlphaMode::Blend ? simd::min(simd::max(base[3], zero), one) : one;
                float rgba[4][8];
                for (int c = 0; c < 3; ++c) simd::storef(rgba[c], linear[c]);
                simd::storef(rgba[3], alpha);
                float* const row = tile.target.linear + (std::size_t(y) * stride + std::size_t(bx)) * 4;
                for (int k = 0; k < samples; ++k) {
                    float* const sampleRow = row + std::size_t(k) * tile.target.sampleStride * 4;
                    for (unsigned bitsLeft = simd::laneBits(owned[k]); bitsLeft != 0; bitsLeft &= bitsLeft - 1) {
                        const int l = __builtin_ctz(bitsLeft);
                        const float src[4] = {rgba[0][l], rgba[1][l], rgba[2][l], rgba[3][l]};
                        float* const pixel = sampleRow + std::size_t(l) * 4;
                        if (shading.alphaMode == AlphaMode::Blend)
                            blendLinear(src, pixel);
                        else
                            std::memcpy(pixel, src, sizeof src);
                    }
                }
                continue;
            }
            // Colour: linear rgb encoded lane by lane (ColorEncoding); alpha converted as it is.
            std::uint32_t rgb[8] = {};
            for (int c = 0; c < 3; ++c) {
                float values[8];
                simd::storef(values, linear[c]);
                for (int l = 0; l < 8; ++l) rgb[l] |= std::uint32_t(ColorEncoding::encode(values[l])) << (8 * c);
            }
            std::uint32_t* const colorRow = tile.target.color + std::size_t(y) * stride + bx;
            if (shading.alphaMode != AlphaMode::Blend) {
                const I8 color = simd::loadi(rgb) | simd::splati(std::int32_t(0xFF000000u));
                for (int k = 0; k < samples; ++k)
                    simd::storeMasked(colorRow + std::size_t(k) * tile.target.sampleStride, owned[k], color);
                continue;
            }
            const F8 alpha = simd::min(simd::max(base[3], zero), one);
            std::uint32_t src[8];
            simd::storei(src, simd::loadi(rgb) | simd::sll(simd::toIntRound(alpha * c255), 24));
            for (int k = 0; k < samples; ++k) {  // each sample over its own colour
                std::uint32_t* const sampleRow = colorRow + std::size_t(k) * tile.target.sampleStride;
                for (unsigned bitsLeft = simd::laneBits(owned[k]); bitsLeft != 0; bitsLeft &= bitsLeft - 1) {
                    const int l = __builtin_ctz(bitsLeft);
                    sampleRow[l] = blendOver(src[l], sampleRow[l]);
                }
            }
        }
    }
}

void shade(std::uint32_t index, const DrawShading& shading, TileState& tile) {
    if (tile.target.samples > 1)
        shadeSamples<kMaxSamples>(index, shading, tile);
    else
        shadeSamples<1>(index, shading, tile);
}

}  // namespace

inline Kernels kernelTable(const char* name) { return Kernels{name, &transform, &raster, &shade}; }
