// The occlusion pass's quick triangle test, eight triangles at a time (OcclusionKernels.h
// verdictsAvx2), included by the files that compile it for a target: OcclusionAvx2.cpp (AVX2, the
// corners' attributes gathered) and OcclusionAvx512.cpp (the same operations, the attributes looked
// up by AVX-512 permutes from a cluster's 64 vertices). Each includes it inside an unnamed
// namespace, after <immintrin.h> and its target pragma, so that each copy is compiled for its own.
// `Fetch` gives the corners' attributes for eight vertex indices: fx, fy (__m256i: setup's
// fixed-point position, or kUnfixed) and x, y, z (__m256: the window position).

inline __m256i load8(const std::uint16_t* p) {
    return _mm256_cvtepu16_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
}
// ⌈a / 256⌉ and ⌊a / 256⌋, arithmetic shifts (Rasterizer.h detail::ceilDiv256, floorDiv256).
inline __m256i ceil256(__m256i a) { return _mm256_sub_epi32(_mm256_setzero_si256(), _mm256_srai_epi32(_mm256_sub_epi32(_mm256_setzero_si256(), a), 8)); }
inline __m256i floor256(__m256i a) { return _mm256_srai_epi32(a, 8); }
inline __m256i lessThan(__m256i a, __m256i b) { return _mm256_cmpgt_epi32(b, a); }
// Far-ness bounds lo ≤ the stored value ≤ hi at pixels whose plane value is z, `slack` its rounding
// bound and `up` the 24-bit step (Occlusion.cpp triangleMaySeen): D24 stores the clamped z, D32F
// (`halfZ`) is read as its negation. std::clamp(v, 0, 1) is min(1, max(0, v)) in this operand
// order (a NaN stays), as the scalar loops compute it.
inline void depthBounds(__m256 z, __m256 slack, __m256 up, bool halfZ, __m256& lo, __m256& hi) {
    const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f);
    if (!halfZ) {
        lo = _mm256_min_ps(one, _mm256_max_ps(zero, _mm256_sub_ps(z, slack)));
        hi = _mm256_add_ps(_mm256_min_ps(one, _mm256_add_ps(z, slack)), up);
    } else {
        lo = _mm256_sub_ps(zero, _mm256_min_ps(one, _mm256_max_ps(zero, _mm256_add_ps(z, slack))));
        hi = _mm256_add_ps(_mm256_sub_ps(zero, _mm256_min_ps(one, _mm256_max_ps(zero, _mm256_sub_ps(z, slack)))), up);
    }
}

// verdictsAvx2's work (OcclusionKernels.h), with the corners' attributes from `fetch`.
template <class Fetch>
inline void verdictsBody(const Fetch& fetch, const std::uint16_t* c0, const std::uint16_t* c1,
                         const std::uint16_t* c2, std::uint32_t count, bool cullBack, const raster::Viewport& vp,
                         int rowLo, int rowHi, std::uint8_t* verdict, const SmallTriangles& out) {
    const int width = vp.width;
    const __m256i zero = _mm256_setzero_si256(), one = _mm256_set1_epi32(1);
    const __m256 fzero = _mm256_setzero_ps(), fone = _mm256_set1_ps(1.0f), fhalf = _mm256_set1_ps(0.5f);
    const __m256 absMask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
    const __m256 targetW = _mm256_set1_ps(float(vp.width)), targetH = _mm256_set1_ps(float(vp.height));
    constexpr float kUnit = 1.0f / 16777216.0f;
    const __m256 slackScale = _mm256_set1_ps(8.0f * kUnit), slackAdd = _mm256_set1_ps(2.0f * kUnit);
    const __m256 slackGrow = _mm256_set1_ps(1.0f + 1e-6f), step24 = _mm256_set1_ps(2.0f * kUnit);
    const __m256i unfixed = _mm256_set1_epi32(kUnfixed), quick = _mm256_set1_epi32(kQuickExtent);
    const __m256i lastX = _mm256_set1_epi32(width - 1), rowFirst = _mm256_set1_epi32(rowLo), rowLast = _mm256_set1_epi32(rowHi);
    const bool medium8 = out.edge != nullptr;  // kMedium asked for
    for (std::uint32_t i = 0; i < count; i += 8) {
        const __m256i i0 = load8(c0 + i), i1 = load8(c1 + i), i2 = load8(c2 + i);
        __m256i X0 = fetch.fx(i0), X1 = fetch.fx(i1), X2 = fetch.fx(i2);
        __m256i Y0 = fetch.fy(i0), Y1 = fetch.fy(i1), Y2 = fetch.fy(i2);
        const __m256i keep = _mm256_or_si256(
            _mm256_or_si256(_mm256_cmpeq_epi32(X0, unfixed), _mm256_cmpeq_epi32(X1, unfixed)),
            _mm256_or_si256(_mm256_cmpeq_epi32(X2, unfixed),
                            _mm256_or_si256(_mm256_cmpeq_epi32(Y0, unfixed),
                                            _mm256_or_si256(_mm256_cmpeq_epi32(Y1, unfixed), _mm256_cmpeq_epi32(Y2, unfixed)))));
        // Setup's bounds (Rasterizer.h setupEdges), on the target's columns and the rows looked at.
        const __m256i minX = _mm256_min_epi32(X0, _mm256_min_epi32(X1, X2)), maxX = _mm256_max_epi32(X0, _mm256_max_epi32(X1, X2));
        const __m256i minY = _mm256_min_epi32(Y0, _mm256_min_epi32(Y1, Y2)), maxY = _mm256_max_epi32(Y0, _mm256_max_epi32(Y1, Y2));
        const __m256i x0 = _mm256_max_epi32(ceil256(minX), zero), x1 = _mm256_min_epi32(floor256(maxX), lastX);
        const __m256i y0 = _mm256_max_epi32(ceil256(minY), rowFirst), y1 = _mm256_min_epi32(floor256(maxY), rowLast);
        const __m256i empty = _mm256_or_si256(_mm256_cmpgt_epi32(x0, x1), _mm256_cmpgt_epi32(y0, y1));
        // Small enough for 32 bits (the extent is exact: |X| < 2^26), and at most 2 × 2 pixel centres.
        const __m256i dx = _mm256_sub_epi32(x1, x0), dy = _mm256_sub_epi32(y1, y0);
        const __m256i within = _mm256_and_si256(lessThan(_mm256_sub_epi32(maxX, minX), quick),
                                                lessThan(_mm256_sub_epi32(maxY, minY), quick));
        const __m256i small = _mm256_and_si256(
            within, _mm256_and_si256(lessThan(dx, _mm256_set1_epi32(2)), lessThan(dy, _mm256_set1_epi32(2))));
        // At most 8 columns, larger than small (and asked for).
        const __m256i medium = medium8 ? _mm256_andnot_si256(small, _mm256_and_si256(within, lessThan(dx, _mm256_set1_epi32(8))))
                                       : zero;
        // Area and facing; a front face swaps v0 and v1 (setupEdges). Within the extent nothing
        // overflows: differences are below 2^12, products below 2^24.
        const __m256i area = _mm256_sub_epi32(_mm256_mullo_epi32(_mm256_sub_epi32(X0, X1), _mm256_sub_epi32(Y2, Y0)),
                                              _mm256_mullo_epi32(_mm256_sub_epi32(X2, X0), _mm256_sub_epi32(Y0, Y1)));
        const __m256i front = lessThan(area, zero);
        __m256i culled = _mm256_cmpeq_epi32(area, zero);
        if (cullBack) culled = _mm256_or_si256(culled, _mm256_andnot_si256(front, _mm256_set1_epi32(-1)));
        {
            const __m256i sx = _mm256_blendv_epi8(X0, X1, front), sy = _mm256_blendv_epi8(Y0, Y1, front);
            X1 = _mm256_blendv_epi8(X1, X0, front), Y1 = _mm256_blendv_epi8(Y1, Y0, front);
            X0 = sx, Y0 = sy;
        }
        // Edges relative to the first pixel centre (256·x0, 256·y0), within the extent of the
        // vertices: pixel (x0 + a, y0 + b) is inside edge i when
        // dcdx·(X_i − 256·x0) − dcdy·(Y_i − 256·y0) + tie − 1 − 256·dcdx·a + 256·dcdy·b ≥ 0
        // (Rasterizer.h 3., the same inequality as k − dx·px + dy·py ≥ 0 with k from absolute c).
        const __m256i ox = _mm256_slli_epi32(x0, 8), oy = _mm256_slli_epi32(y0, 8);
        const __m256i Xs[3] = {X0, X1, X2}, Ys[3] = {Y0, Y1, Y2};
        __m256i m00 = zero, m10 = zero, m01 = zero, m11 = zero;
        __m256i edges[3], stepsX[3], stepsY[3];
        for (int e = 0; e < 3; ++e) {
            const int f = e == 2 ? 0 : e + 1;
            const __m256i dcdx = _mm256_sub_epi32(Ys[e], Ys[f]), dcdy = _mm256_sub_epi32(Xs[e], Xs[f]);
            const __m256i tie = _mm256_or_si256(lessThan(dcdx, zero),
                                                _mm256_and_si256(_mm256_cmpeq_epi32(dcdx, zero), _mm256_cmpgt_epi32(dcdy, zero)));
            // tie is −1 (all ones) where the rule adds 1; c − 1 is then c − tie − 1.
            __m256i c = _mm256_sub_epi32(_mm256_mullo_epi32(dcdx, _mm256_sub_epi32(Xs[e], ox)),
                                         _mm256_mullo_epi32(dcdy, _mm256_sub_epi32(Ys[e], oy)));
            c = _mm256_sub_epi32(_mm256_sub_epi32(c, tie), one);
            const __m256i stepX = _mm256_slli_epi32(dcdx, 8), stepY = _mm256_slli_epi32(dcdy, 8);
            edges[e] = c, stepsX[e] = stepX, stepsY[e] = stepY;
            m00 = _mm256_or_si256(m00, c);
            m10 = _mm256_or_si256(m10, _mm256_sub_epi32(c, stepX));
            m01 = _mm256_or_si256(m01, _mm256_add_epi32(c, stepY));
            m11 = _mm256_or_si256(m11, _mm256_add_epi32(_mm256_sub_epi32(c, stepX), stepY));
        }
        // A sample is inside every edge when the OR of the three is not negative.
        const __m256i right = _mm256_cmpgt_epi32(dx, zero), up = _mm256_cmpgt_epi32(dy, zero);
        __m256i covered = _mm256_cmpgt_epi32(m00, _mm256_set1_epi32(-1));
        covered = _mm256_or_si256(covered, _mm256_and_si256(right, _mm256_cmpgt_epi32(m10, _mm256_set1_epi32(-1))));
        covered = _mm256_or_si256(covered, _mm256_and_si256(up, _mm256_cmpgt_epi32(m01, _mm256_set1_epi32(-1))));
        covered = _mm256_or_si256(covered, _mm256_and_si256(_mm256_and_si256(right, up),
                                                            _mm256_cmpgt_epi32(m11, _mm256_set1_epi32(-1))));
        // kKeep over everything; then an empty box drops; then a lane too large for the quick test is
        // tested in full; a small one drops when degenerate, culled or covering no centre, and is
        // kSmall otherwise (kKeep when its depth plane is too steep).
        // A medium lane drops when degenerate or culled, and is kMedium otherwise (kTest when its
        // plane is too steep: the full test then finds whether it covers a centre).
        const __m256i smallSeen = _mm256_andnot_si256(empty, _mm256_and_si256(small, _mm256_andnot_si256(culled, covered)));
        const __m256i mediumLive = _mm256_andnot_si256(empty, _mm256_andnot_si256(culled, medium));
        const __m256i large = _mm256_andnot_si256(
            empty, _mm256_andnot_si256(_mm256_or_si256(small, _mm256_and_si256(medium, culled)), _mm256_set1_epi32(-1)));
        __m256i v = _mm256_and_si256(large, one);
        if (_mm256_movemask_epi8(_mm256_andnot_si256(keep, _mm256_or_si256(smallSeen, mediumLive))) != 0) {
            // The depth plane in setup order (raster::setupDepthPlane: a front face swaps v0 and v1), every
            // operation rounded to float.
            const __m256i j0 = _mm256_blendv_epi8(i0, i1, front), j1 = _mm256_blendv_epi8(i1, i0, front);
            const __m256 x0f = fetch.x(j0), y0f = fetch.y(j0), z0f = fetch.z(j0);
            const __m256 x1f = fetch.x(j1), y1f = fetch.y(j1), z1f = fetch.z(j1);
            const __m256 x2f = fetch.x(i2), y2f = fetch.y(i2), z2f = fetch.z(i2);
            const __m256 x0c = _mm256_sub_ps(x0f, fhalf), y0c = _mm256_sub_ps(y0f, fhalf);
            const __m256 dx01 = _mm256_sub_ps(x0f, x1f), dy01 = _mm256_sub_ps(y0f, y1f);
            const __m256 dx20 = _mm256_sub_ps(x2f, x0f), dy20 = _mm256_sub_ps(y2f, y0f);
            const __m256 ooa = _mm256_div_ps(fone, _mm256_sub_ps(_mm256_mul_ps(dx01, dy20), _mm256_mul_ps(dy01, dx20)));
            const __m256 dx20o = _mm256_mul_ps(dx20, ooa), dy20o = _mm256_mul_ps(dy20, ooa);
            const __m256 dx01o = _mm256_mul_ps(dx01, ooa), dy01o = _mm256_mul_ps(dy01, ooa);
            const __m256 da01 = _mm256_sub_ps(z0f, z1f), da20 = _mm256_sub_ps(z2f, z0f);
            const __m256 dzdx = _mm256_sub_ps(_mm256_mul_ps(da01, dy20o), _mm256_mul_ps(da20, dy01o));
            const __m256 dzdy = _mm256_sub_ps(_mm256_mul_ps(da20, dx01o), _mm256_mul_ps(da01, dx20o));
            const __m256 plane0 = _mm256_sub_ps(z0f, _mm256_add_ps(_mm256_mul_ps(dzdx, x0c), _mm256_mul_ps(dzdy, y0c)));
            // depthSlack, in the same order.
            const __m256 size = _mm256_add_ps(_mm256_add_ps(_mm256_and_ps(plane0, absMask), _mm256_mul_ps(_mm256_and_ps(dzdx, absMask), targetW)),
                                              _mm256_mul_ps(_mm256_and_ps(dzdy, absMask), targetH));
            const __m256 slack = _mm256_mul_ps(_mm256_add_ps(_mm256_mul_ps(slackScale, size), slackAdd), slackGrow);
            const __m256i steep = _mm256_castps_si256(_mm256_cmp_ps(slack, fone, _CMP_NLT_UQ));
            // The draw module's cull stage on the given order (raster::drawModuleKeepsFront): a sliver it
            // may drop hides nothing.
            // (v0 and v1 in the given order: swapped back where setup swapped them.)
            const __m256 swapped = _mm256_castsi256_ps(front);
            const __m256 xa = _mm256_blendv_ps(x0f, x1f, swapped), ya = _mm256_blendv_ps(y0f, y1f, swapped);
            const __m256 xb = _mm256_blendv_ps(x1f, x0f, swapped), yb = _mm256_blendv_ps(y1f, y0f, swapped);
            const __m256 det = _mm256_sub_ps(_mm256_mul_ps(_mm256_sub_ps(xa, x2f), _mm256_sub_ps(yb, y2f)),
                                             _mm256_mul_ps(_mm256_sub_ps(ya, y2f), _mm256_sub_ps(xb, x2f)));
            __m256i occludes = _mm256_castps_si256(_mm256_cmp_ps(det, fzero, _CMP_NLE_UQ));
            if (!cullBack) occludes = _mm256_set1_epi32(-1);
            // Far-ness bounds at the four pixel centres (Occlusion.cpp triangleMaySeen):
            // z = (plane0 + dzdy·py) + dzdx·px.
            const __m256 px0 = _mm256_cvtepi32_ps(x0), px1 = _mm256_cvtepi32_ps(_mm256_add_epi32(x0, one));
            const __m256 py0 = _mm256_cvtepi32_ps(y0), py1 = _mm256_cvtepi32_ps(_mm256_add_epi32(y0, one));
            const __m256 row0 = _mm256_add_ps(plane0, _mm256_mul_ps(dzdy, py0)), row1 = _mm256_add_ps(plane0, _mm256_mul_ps(dzdy, py1));
            const __m256 zs[4] = {_mm256_add_ps(row0, _mm256_mul_ps(dzdx, px0)), _mm256_add_ps(row0, _mm256_mul_ps(dzdx, px1)),
                                  _mm256_add_ps(row1, _mm256_mul_ps(dzdx, px0)), _mm256_add_ps(row1, _mm256_mul_ps(dzdx, px1))};
            for (int k = 0; k < 4; ++k) {
                __m256 lo, hi;
                depthBounds(zs[k], slack, step24, vp.halfZ, lo, hi);
                _mm256_storeu_ps(out.lo + std::size_t(k) * out.stride + i, lo);
                _mm256_storeu_ps(out.hi + std::size_t(k) * out.stride + i, hi);
            }
            // Covered pixels: bit a + 2b.
            const __m256i notNegative = _mm256_set1_epi32(-1);
            __m256i bitsCovered = _mm256_and_si256(_mm256_cmpgt_epi32(m00, notNegative), one);
            bitsCovered = _mm256_or_si256(bitsCovered, _mm256_and_si256(_mm256_and_si256(right, _mm256_cmpgt_epi32(m10, notNegative)), _mm256_set1_epi32(2)));
            bitsCovered = _mm256_or_si256(bitsCovered, _mm256_and_si256(_mm256_and_si256(up, _mm256_cmpgt_epi32(m01, notNegative)), _mm256_set1_epi32(4)));
            bitsCovered = _mm256_or_si256(bitsCovered, _mm256_and_si256(_mm256_and_si256(_mm256_and_si256(right, up), _mm256_cmpgt_epi32(m11, notNegative)), _mm256_set1_epi32(8)));
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(out.x0 + i), x0);
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(out.y0 + i), y0);
            const __m128i bits16 = _mm_packus_epi32(_mm256_castsi256_si128(bitsCovered), _mm256_extracti128_si256(bitsCovered, 1));
            _mm_storel_epi64(reinterpret_cast<__m128i*>(out.covered + i), _mm_packus_epi16(bits16, bits16));
            const __m256i occ = _mm256_and_si256(occludes, one);
            const __m128i occ16 = _mm_packus_epi32(_mm256_castsi256_si128(occ), _mm256_extracti128_si256(occ, 1));
            _mm_storel_epi64(reinterpret_cast<__m128i*>(out.occludes + i), _mm_packus_epi16(occ16, occ16));
            v = _mm256_blendv_epi8(v, _mm256_blendv_epi8(_mm256_set1_epi32(3), _mm256_set1_epi32(2), steep), smallSeen);
            if (_mm256_movemask_epi8(_mm256_andnot_si256(keep, mediumLive)) != 0) {
                _mm256_storeu_si256(reinterpret_cast<__m256i*>(out.x1 + i), x1);
                _mm256_storeu_si256(reinterpret_cast<__m256i*>(out.y1 + i), y1);
                for (int e = 0; e < 3; ++e) {
                    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out.edge + std::size_t(e) * out.stride + i), edges[e]);
                    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out.edge + std::size_t(3 + e) * out.stride + i), stepsX[e]);
                    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out.edge + std::size_t(6 + e) * out.stride + i), stepsY[e]);
                }
                _mm256_storeu_ps(out.plane + i, plane0);
                _mm256_storeu_ps(out.plane + std::size_t(out.stride) + i, dzdx);
                _mm256_storeu_ps(out.plane + 2 * std::size_t(out.stride) + i, dzdy);
                _mm256_storeu_ps(out.plane + 3 * std::size_t(out.stride) + i, slack);
                v = _mm256_blendv_epi8(v, _mm256_blendv_epi8(_mm256_set1_epi32(4), one, steep), mediumLive);
            }
        }
        v = _mm256_blendv_epi8(v, _mm256_set1_epi32(2), keep);
        // Eight 32-bit verdicts to eight bytes.
        const __m128i packed16 = _mm_packus_epi32(_mm256_castsi256_si128(v), _mm256_extracti128_si256(v, 1));
        _mm_storel_epi64(reinterpret_cast<__m128i*>(verdict + i), _mm_packus_epi16(packed16, packed16));
    }
}
