#!/usr/bin/python3
"""Cheap analytic fit of the split-sum environment BRDF ("DFG" LUT) used by
the Khronos glTF Sample Renderer (GGX, height-correlated Smith visibility).

    A(x,r) = E_H[ 4 (1-Fc) Vis(x,NdotL,alpha) VdotH NdotL / NdotH ]
    B(x,r) = E_H[ 4   Fc   Vis(x,NdotL,alpha) VdotH NdotL / NdotH ]

x = NdotV, r = perceptual roughness, alpha = r^2, H ~ GGX importance
sampling (pdf D(H) NdotH), Fc = (1-VdotH)^5, L = reflect(-V,H), NdotL > 0.

Steps:
  1. The exact A, B are computed by deterministic quadrature (see
     dfg_exact) on a 257x257 grid (x, r = k/256, edges included) and at the
     128x128 texel centres of the reference LUT.
  2. An analytic form is fitted: least squares, then IRLS over L_p norms
     with p increasing up to 128 (close to minimax).
  3. The errors are measured with the formula evaluated in float32 in the
     exact Horner order that is printed as C++ and GLSL at the end.

Usage: /usr/bin/python3 dfg_fit.py [--cache FILE.npz] [--search]
  --cache   store/load the exact tables (skips the ~50 s quadrature).
  --search  also rerun the term selection (backward elimination, ~1-2 min)
            that produced TERMS below.
Only numpy is needed.
"""
import argparse
import os
import time

import numpy as np

# --------------------------------------------------------------------------
# 1. Exact function by quadrature
# --------------------------------------------------------------------------
# H is parametrised by zeta = ln(tan(theta_h)/alpha) and phi. With
# u1 = GGX-CDF variable (xi.y in the Khronos shader) we have
# tan^2(theta_h) = alpha^2 u1/(1-u1), i.e. u1 = logistic(2 zeta) and
# du1 = 2 u1 (1-u1) dzeta: GGX importance sampling is exact in this variable
# and the integrand is smooth in zeta for every alpha (no clustering of the
# interesting region near u1 -> 1 when alpha is small).
# The phi integral is taken over [0, phi_max(theta_h)], the part of the
# circle where NdotL > 0 (solved in closed form), by Gauss-Legendre, and the
# theta_h range is split where phi_max starts to drop below pi and where it
# reaches 0 (theta_h = (pi/2 -+ theta_v)/2), so that every piece is smooth.
ZMIN, ZMAX = -9.0, 20.0   # truncation of zeta: neglected mass < 2e-8


def _gl_panels(n_panels, n_nodes):
    g, w = np.polynomial.legendre.leggauss(n_nodes)
    e = np.linspace(0.0, 1.0, n_panels + 1)
    h = np.diff(e)
    t = (e[:-1, None] + (g[None, :] + 1.0) * 0.5 * h[:, None]).ravel()
    return t, (w[None, :] * 0.5 * h[:, None]).ravel()


def _dfg_chunk(x, r, n1, n2, nn, nphi):
    alpha = np.maximum(r * r, 1e-12)      # r = 0 is evaluated as alpha = 1e-12
    a2 = alpha * alpha
    tv = np.arccos(np.clip(x, 0.0, 1.0))
    th1 = 0.5 * (0.5 * np.pi - tv)        # below: full phi range has NdotL > 0
    th2 = 0.5 * (0.5 * np.pi + tv)        # above: no phi has NdotL > 0
    la = np.log(alpha)
    with np.errstate(divide='ignore'):
        z1 = np.clip(np.log(np.tan(th1)) - la, ZMIN, ZMAX)
        z2 = np.clip(np.log(np.tan(th2)) - la, ZMIN, ZMAX)
    t1, w1 = _gl_panels(n1, nn)
    t2, w2 = _gl_panels(n2, nn)
    # grading towards both ends of the partial segment (sqrt-type end points)
    m = t2 - np.sin(2 * np.pi * t2) / (2 * np.pi)
    dm = 1.0 - np.cos(2 * np.pi * t2)
    Z = np.concatenate([ZMIN + (z1 - ZMIN)[:, None] * t1,
                        z1[:, None] + (z2 - z1)[:, None] * m], 1)
    W = np.concatenate([(z1 - ZMIN)[:, None] * w1,
                        (z2 - z1)[:, None] * (w2 * dm)], 1)
    full = np.concatenate([np.ones(t1.size, bool), np.zeros(t2.size, bool)])
    u1 = 0.5 * (1.0 + np.tanh(Z))
    W = W * 2.0 * u1 * (1.0 - u1)
    T = alpha[:, None] * np.exp(Z)        # tan(theta_h)
    ch = 1.0 / np.sqrt(1.0 + T * T)
    sh = T * ch
    xv = x[:, None]
    sv = np.sqrt(np.maximum(0.0, 1.0 - xv * xv))
    den = sv * sh
    with np.errstate(divide='ignore', invalid='ignore'):
        c0 = (xv / (2 * ch) - xv * ch) / den          # NdotL > 0 <=> cos(phi) > c0
    c0 = np.where(den > 0, c0, np.where(xv * (1 - 2 * ch * ch) < 0, -1.0, 1.0))
    phimax = np.where(full[None, :], np.pi, np.arccos(np.clip(c0, -1.0, 1.0)))
    gp, wp = np.polynomial.legendre.leggauss(nphi)
    phi = (gp + 1.0) * 0.5 * phimax[..., None]
    Wt = (W * phimax / (2 * np.pi))[..., None] * wp  # phi symmetric: [0,pi] x 2
    voh = sv[..., None] * sh[..., None] * np.cos(phi) + xv[..., None] * ch[..., None]
    nol = np.maximum(2.0 * voh * ch[..., None] - xv[..., None], 0.0)
    a2b = a2[:, None, None]
    vden = (nol * np.sqrt(xv[..., None] ** 2 * (1 - a2b) + a2b)
            + xv[..., None] * np.sqrt(nol * nol * (1 - a2b) + a2b))
    with np.errstate(divide='ignore', invalid='ignore'):
        f = np.where(nol > 0, 2.0 * nol * voh / (vden * ch[..., None]), 0.0)  # 4*0.5*...
    f = f * Wt
    Bv = np.sum(f * (1.0 - voh) ** 5, axis=(1, 2))
    Av = np.sum(f, axis=(1, 2)) - Bv
    return Av, Bv


def dfg_exact(x, r, n1=32, n2=32, nn=5, nphi=10, chunk=256):
    """Exact A, B at arrays (x, r). Default nodes: |error| < ~5e-6."""
    x = np.asarray(x, np.float64).ravel()
    r = np.asarray(r, np.float64).ravel()
    A = np.empty(x.size)
    B = np.empty(x.size)
    for i in range(0, x.size, chunk):
        A[i:i + chunk], B[i:i + chunk] = _dfg_chunk(x[i:i + chunk], r[i:i + chunk],
                                                    n1, n2, nn, nphi)
    return A, B


def dfg_bruteforce(x, r, nu=2048, nv=1024):
    """The Khronos estimator verbatim, with the Hammersley points replaced by
    a nu x nv midpoint grid in (xi.y, xi.x). Independent sanity check only
    (O(1e-4) accurate: the integrand has kinks)."""
    a2 = r ** 4
    V = np.array([np.sqrt(1 - x * x), 0.0, x])
    phi = 2 * np.pi * (np.arange(nv) + 0.5) / nv
    sa = sb = 0.0
    for i0 in range(0, nu, 256):
        u = (np.arange(i0, min(i0 + 256, nu)) + 0.5) / nu
        ct = np.sqrt((1 - u) / (1 + (a2 - 1) * u))[:, None]
        st = np.sqrt(1 - ct * ct)
        H = (st * np.cos(phi), st * np.sin(phi), ct * np.ones_like(phi))
        voh = np.maximum(V[0] * H[0] + V[2] * H[2], 0.0)
        nol = 2 * voh * H[2] - V[2]
        nol_c = np.maximum(nol, 1e-30)
        vis = 0.5 / (nol_c * np.sqrt(x * x * (1 - a2) + a2) + x * np.sqrt(nol_c ** 2 * (1 - a2) + a2))
        t = np.where(nol > 0, vis * voh * nol / H[2], 0.0)
        fc = (1 - voh) ** 5
        sa += np.sum((1 - fc) * t)
        sb += np.sum(fc * t)
    return 4 * sa / (nu * nv), 4 * sb / (nu * nv)


# --------------------------------------------------------------------------
# 2. The analytic form
# --------------------------------------------------------------------------
# Variables (all cheap):  alpha = r*r
#   u  = x / sqrt(x^2 + C_U*alpha^2)   in [0,1]; the one sqrt (+ division),
#        = x * inversesqrt(...). u captures the grazing boundary layer of the
#        exact function, which lives at NdotV ~ alpha (see README).
#   f5 = (1-x)^5                        (Fresnel weight, exact at r = 0)
# A and B are polynomials in (x, r, u, f5) over the same monomial set,
# evaluated by nested Horner (f5 outermost, then u, x, r innermost):
# cost = (len(TERMS)-1) multiply-adds per output.
C_U = 4.0
VARS = ('x', 'r', 'u', 'f5')          # exponent tuple order in TERMS
NEST = ('f5', 'u', 'x', 'r')          # Horner nesting, outermost first
# Chosen set (18 terms), found by backward elimination from 112 monomials
# (rerun with --search). TERMS_20 = TERMS + the two terms last removed.
TERMS = [(0, 0, 0, 0), (0, 1, 0, 0), (0, 2, 0, 0), (0, 3, 0, 0), (0, 4, 0, 0),
         (0, 5, 0, 0), (1, 0, 0, 0), (1, 1, 0, 0), (1, 2, 0, 0), (2, 0, 0, 0),
         (0, 0, 1, 0), (0, 1, 1, 0), (0, 2, 1, 0), (0, 3, 1, 0), (1, 0, 1, 0),
         (0, 0, 2, 0), (0, 0, 0, 1), (0, 1, 0, 1)]
TERMS_20 = TERMS + [(3, 0, 0, 0), (2, 0, 1, 0)]
XA_EXTRA = np.array([1e-4, 3e-4, 6e-4, 1e-3, 1.5e-3, 2e-3, 2.7e-3, 3.3e-3])
# Baseline at the same budget: plain bivariate polynomial, total degree <= 5.
TERMS_POLY5 = [(i, j, 0, 0) for i in range(6) for j in range(6) if i + j <= 5]


def features(x, r, dtype=np.float32):
    """Exactly the shader's set-up computations, in `dtype`."""
    x = np.asarray(x, dtype)
    r = np.asarray(r, dtype)
    one = dtype(1.0)
    a = r * r
    a2 = a * a
    w = np.maximum(x * x + dtype(C_U) * a2, dtype(1e-30))
    u = x * (one / np.sqrt(w))
    y = one - x
    y2 = y * y
    f5 = y2 * y2 * y
    return {'x': x, 'r': r, 'u': u, 'f5': f5}


def horner(terms, c='c'):
    """Nested Horner expression for the monomial set; returns (expr, order):
    coefficient c[i] multiplies the monomial terms[order[i]]."""
    idx = {v: VARS.index(v) for v in VARS}
    order = []

    def build(group, levels):
        if not levels:
            assert len(group) == 1
            order.append(group[0])
            return '%s[%%d]' % c, True
        v = levels[0]
        K = max(t[idx[v]] for t in group)
        subs = []
        for k in range(K + 1):
            sg = [t for t in group if t[idx[v]] == k]
            assert sg, 'monomial set is not downward closed'
            subs.append(sg)
        # build lowest power first so that coefficients are numbered left to right
        parts = [build(sg, levels[1:]) for sg in subs]
        expr, simple = parts[K]
        for k in range(K - 1, -1, -1):
            inner = expr if simple else '(%s)' % expr
            expr, simple = '%s + %s*%s' % (parts[k][0], v, inner), False
        return expr, simple

    expr, _ = build(sorted(terms), list(NEST))
    n = expr.count('%d')
    expr = expr % tuple(range(n))
    return expr, order


def design(feat, terms):
    cols = []
    for t in terms:
        m = np.ones(feat['x'].shape, np.float64)
        for v, k in zip(VARS, t):
            if k:
                m = m * feat[v].astype(np.float64) ** k
        cols.append(m.ravel())
    return np.stack(cols, 1)


def lp_fit(M, f, ps=(4, 8, 16, 32, 64, 128), iters=15):
    """Least squares, then Newton-type IRLS on ||e||_p with backtracking, p
    increasing (-> minimax). Returns the coefficients with the smallest max
    error seen, and the pure least-squares solution."""
    c = np.linalg.lstsq(M, f, rcond=None)[0]
    c_ls = c.copy()
    best = (np.abs(M @ c - f).max(), c.copy())

    def lpn(e, p):
        s = np.abs(e).max()
        return s * np.mean((np.abs(e) / s) ** p) ** (1.0 / p)

    for p in ps:
        for _ in range(iters):
            e = M @ c - f
            s = np.abs(e).max()
            w = np.maximum(np.abs(e) / s, 1e-8) ** ((p - 2) / 2.0)
            cn = np.linalg.lstsq(M * w[:, None], f * w, rcond=None)[0]
            L0, t = lpn(e, p), 1.0
            while t > 1e-3:
                ct = c + t * (cn - c)
                if lpn(M @ ct - f, p) < L0:
                    c = ct
                    break
                t *= 0.5
            else:
                break
            m = np.abs(M @ c - f).max()
            if m < best[0]:
                best = (m, c.copy())
    return best[1], c_ls


def eval_form(coef, terms, x, r):
    """Evaluate in float32 with exactly the printed Horner expression."""
    expr, order = horner(terms)
    feat = features(x, r, np.float32)
    c = np.asarray([coef[terms.index(t)] for t in order], np.float32)
    val = eval(expr, {}, dict(feat, c=c))
    return np.clip(val, np.float32(0), np.float32(1))


def karis_mobile(x, r):
    """UE4 mobile EnvBRDFApprox (fitted to a different LUT; context only)."""
    x = np.asarray(x, np.float32)
    r = np.asarray(r, np.float32)
    c0 = np.array([-1, -0.0275, -0.572, 0.022], np.float32)
    c1 = np.array([1, 0.0425, 1.04, -0.04], np.float32)
    q = [r * c0[i] + c1[i] for i in range(4)]
    a004 = np.minimum(q[0] * q[0], np.exp2(np.float32(-9.28) * x)) * q[0] + q[1]
    return np.float32(-1.04) * a004 + q[2], np.float32(1.04) * a004 + q[3]


def bilinear_clamp(T, x, r):
    n = T.shape[0]
    px, pr = x * n - 0.5, r * n - 0.5
    i0, j0 = np.floor(px).astype(int), np.floor(pr).astype(int)
    fx, fr = px - i0, pr - j0
    i1, j1 = np.clip(i0 + 1, 0, n - 1), np.clip(j0 + 1, 0, n - 1)
    i0, j0 = np.clip(i0, 0, n - 1), np.clip(j0, 0, n - 1)
    return (T[i0, j0] * (1 - fx) * (1 - fr) + T[i1, j0] * fx * (1 - fr)
            + T[i0, j1] * (1 - fx) * fr + T[i1, j1] * fx * fr)


# --------------------------------------------------------------------------
# optional: term selection (how TERMS was found)
# --------------------------------------------------------------------------
def backward_select(A, B, feat, start, sizes, sub):
    """Backward elimination keeping the set downward closed; score of a set =
    max over A,B of (max|e| + 3 rms|e|) after a least-squares fit (sets of
    24 terms or more) or a short L8 IRLS fit (smaller sets), on a sub-grid
    that is denser near x = 0 and r = 0."""
    f = [F[sub].ravel() for F in (A, B)]
    fs = {v: feat[v][sub].astype(np.float64).ravel() for v in VARS}
    cols = {t: np.prod([fs[v] ** k for v, k in zip(VARS, t)], 0) for t in start}
    S = list(start)
    out = {}

    def score(M):
        s = 0.0
        for ff in f:
            c = np.linalg.lstsq(M, ff, rcond=None)[0]
            for _ in range(4 if M.shape[1] < 24 else 0):   # plain LS while large
                e = M @ c - ff
                w = np.maximum(np.abs(e) / np.abs(e).max(), 1e-4) ** 3
                c = c + (np.linalg.lstsq(M * w[:, None], ff * w, rcond=None)[0] - c) * (2 / 7)
            e = M @ c - ff
            s = max(s, np.abs(e).max() + 3 * np.sqrt(np.mean(e * e)))
        return s

    while len(S) > min(sizes):
        rem = [t for t in S if any(t) and not any(
            tuple(t[:m] + (t[m] + 1,) + t[m + 1:]) in S for m in range(len(VARS)))]
        best = min(rem, key=lambda q: score(np.stack([cols[t] for t in S if t != q], 1)))
        S.remove(best)
        if len(S) in sizes:
            out[len(S)] = sorted(S)
    return out


# --------------------------------------------------------------------------
def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--cache', help='npz file to store/load the exact tables')
    ap.add_argument('--search', action='store_true', help='rerun the term selection')
    args = ap.parse_args()
    t_start = time.time()
    np.set_printoptions(linewidth=120)
    P = print

    g = np.linspace(0.0, 1.0, 257)
    X, R = np.meshgrid(g, g, indexing='ij')            # [ix, jr]
    tc = (np.arange(128) + 0.5) / 128
    XC, RC = np.meshgrid(tc, tc, indexing='ij')
    # extra fitting rows inside the first grid cell in x (the grazing layer
    # lives at x ~ alpha and would otherwise only be controlled at grid nodes)
    XA, RA = np.meshgrid(XA_EXTRA, g, indexing='ij')

    # ---- quadrature checks ----
    P('== Quadrature checks')
    xs = g[::8]
    A0, B0 = dfg_exact(xs, np.zeros_like(xs))
    P('r = 0 limit, x = 0..1 step 1/32: max|A - (1-(1-x)^5)| = %.1e, max|B - (1-x)^5| = %.1e'
      % (np.abs(A0 - (1 - (1 - xs) ** 5)).max(), np.abs(B0 - (1 - xs) ** 5).max()))
    rng = np.random.default_rng(7)
    xr = np.concatenate([rng.random(120), np.zeros(20), np.ones(20), rng.random(20) * 0.02, rng.random(20)])
    rr = np.concatenate([rng.random(120), rng.random(40), rng.random(20), np.ones(20) * rng.choice([1 / 256, 1.0], 20)])
    Ad, Bd = dfg_exact(xr, rr)
    Ah, Bh = dfg_exact(xr, rr, 96, 96, 6, 32)
    P('default vs 3x finer nodes, %d points (incl. x=0, x=1, r=1/256, r=1): max diff %.1e'
      % (xr.size, max(np.abs(Ad - Ah).max(), np.abs(Bd - Bh).max())))
    pts = [(0.1, 0.3), (0.5, 0.5), (0.9, 0.2), (0.3, 0.8), (1.0, 1.0), (0.05, 0.6)]
    Aq, Bq = dfg_exact([p[0] for p in pts], [p[1] for p in pts])
    dbf = [0.0, 0.0]
    for k, n in enumerate((512, 2048)):
        for (px, pr), a, b in zip(pts, Aq, Bq):
            ab, bb = dfg_bruteforce(px, pr, n, n)
            dbf[k] = max(dbf[k], abs(ab - a), abs(bb - b))
    P('literal Khronos estimator on an NxN midpoint grid in (xi.y, xi.x), %d points: '
      'max diff %.1e (N=512), %.1e (N=2048)' % (len(pts), dbf[0], dbf[1]))

    # ---- exact tables ----
    if args.cache and os.path.exists(args.cache):
        z = np.load(args.cache)
        A, B, AC, BC, AA, BA = (z[k] for k in ('A', 'B', 'AC', 'BC', 'AA', 'BA'))
        P('exact tables loaded from', args.cache)
    else:
        t0 = time.time()
        A, B = (v.reshape(X.shape) for v in dfg_exact(X, R))
        AC, BC = (v.reshape(XC.shape) for v in dfg_exact(XC, RC))
        AA, BA = (v.reshape(XA.shape) for v in dfg_exact(XA, RA))
        P('exact tables: 257x257 grid + 128x128 texel centres + %dx257 extra in %.0f s'
          % (XA_EXTRA.size, time.time() - t0))
        if args.cache:
            np.savez(args.cache, A=A, B=B, AC=AC, BC=BC, AA=AA, BA=BA)
    E = A + B

    def where(e):
        i = np.unravel_index(np.argmax(np.abs(e)), e.shape)
        return 'x=%.4f r=%.4f' % (g[i[0]], g[i[1]])

    # ---- reference LUT ----
    P('\n== Khronos reference set-up: 128x128 LUT, texel centres, bilinear, clamp-to-edge')
    AL_, BL_ = bilinear_clamp(AC, X, R), bilinear_clamp(BC, X, R)
    inner = (X >= 0.5 / 128) & (X <= 1 - 0.5 / 128) & (R >= 0.5 / 128) & (R <= 1 - 0.5 / 128)
    for nm, e in (('A', AL_ - A), ('B', BL_ - B), ('0.04A+B', 0.04 * (AL_ - A) + BL_ - B),
                  ('A+B', AL_ + BL_ - E)):
        P('  LUT - exact %-8s max %.4f (%s)  rms %.5f | inside texel-centre square: max %.4f'
          % (nm, np.abs(e).max(), where(e), np.sqrt(np.mean(e * e)), np.abs(e[inner]).max()))
    rl = np.abs(0.04 * (AL_ - A) + BL_ - B) / (0.04 * A + B)
    P('  relative error of 0.04A+B: median %.4f, 90%% < %.4f, max %.2f at %s'
      % (np.median(rl), np.percentile(rl, 90), rl.max(), where(rl)))

    # ---- fit ----
    P('\n== Fits (errors: formula in float32, clamped to [0,1], vs exact, 257x257 grid incl. edges)')
    feat64 = features(X, R, np.float64)
    featfit = features(np.concatenate([X.ravel(), XA.ravel()]),
                       np.concatenate([R.ravel(), RA.ravel()]), np.float64)

    def fit(terms):
        M = design(featfit, terms)
        cA, _ = lp_fit(M, np.concatenate([A.ravel(), AA.ravel()]))
        cB, _ = lp_fit(M, np.concatenate([B.ravel(), BA.ravel()]))
        return cA, cB

    def errors(fa, fb):
        eA, eB = fa.astype(np.float64) - A, fb.astype(np.float64) - B
        return eA, eB

    def line(tag, eA, eB):
        e4 = 0.04 * eA + eB
        e1 = eA + eB
        P('  %-34s A max %.4f rms %.4f | B max %.4f rms %.4f | 0.04A+B max %.4f | A+B max %.4f'
          % (tag, np.abs(eA).max(), np.sqrt(np.mean(eA ** 2)), np.abs(eB).max(),
             np.sqrt(np.mean(eB ** 2)), np.abs(e4).max(), np.abs(e1).max()))

    kA, kB = karis_mobile(X, R)
    line('Karis mobile approx. (UE4 LUT!)', *errors(kA, kB))
    for tag, terms in (('poly deg<=5 in (x,r), 21 terms', TERMS_POLY5),
                       ('chosen, 18 terms (43 op)', TERMS),
                       ('same + 2 terms (47 op)', TERMS_20)):
        cA, cB = fit(terms)
        eA, eB = errors(eval_form(cA, terms, X, R), eval_form(cB, terms, X, R))
        line(tag, eA, eB)
        if terms is TERMS:
            coefA, coefB, errA, errB = cA, cB, eA, eB

    # ---- details for the chosen form ----
    P('\n== Chosen form: details')
    for nm, e in (('A', errA), ('B', errB), ('0.04A+B', 0.04 * errA + errB), ('A+B', errA + errB)):
        P('  %-8s max %.4f at %s, rms %.5f, 99%% of |e| < %.4f | max for x>=1/16: %.4f, r>=1/4: %.4f'
          % (nm, np.abs(e).max(), where(e), np.sqrt(np.mean(e * e)), np.percentile(np.abs(e), 99),
             np.abs(e[X >= 1 / 16]).max(), np.abs(e[R >= 0.25]).max()))
    fA, fB = eval_form(coefA, TERMS, X, R), eval_form(coefB, TERMS, X, R)
    rel = np.abs(0.04 * errA + errB) / (0.04 * A + B)
    P('  relative error of 0.04A+B (dielectric): median %.3f, 90%% < %.3f, max %.2f at %s'
      % (np.median(rel), np.percentile(rel, 90), rel.max(), where(rel)))
    P('  formula - 128^2 LUT (what the Khronos renderer uses): A max %.4f, B max %.4f'
      % (np.abs(fA - AL_).max(), np.abs(fB - BL_).max()))
    # off the grid: random points, 3 x 2000 (uniform / x < 1/256 / log-uniform x, small r)
    rng = np.random.default_rng(11)
    k = 2000
    xo = np.concatenate([rng.random(k), rng.random(k) / 256, 10 ** rng.uniform(-6, -2, k)])
    ro = np.concatenate([rng.random(k), rng.random(k), rng.random(k) * 0.3])
    Ao, Bo = dfg_exact(xo, ro)
    eAo = eval_form(coefA, TERMS, xo, ro) - Ao
    eBo = eval_form(coefB, TERMS, xo, ro) - Bo
    lAo = bilinear_clamp(AC, xo, ro) - Ao
    lBo = bilinear_clamp(BC, xo, ro) - Bo
    P('  off-grid, %d random points (a third with x < 1/256, a third with x in [1e-6,1e-2], r < 0.3):'
      % xo.size)
    P('      formula: A max %.4f, B max %.4f, A+B max %.4f | 128^2 LUT: A max %.4f, B max %.4f'
      % (np.abs(eAo).max(), np.abs(eBo).max(), np.abs(eAo + eBo).max(),
         np.abs(lAo).max(), np.abs(lBo).max()))
    # sensitivity to an approximate rsqrt (x86 rsqrtps: rel. error <= 1.5*2^-12)
    expr, order = horner(TERMS)
    ft = features(X, R, np.float32)
    dev = 0.0
    for s in (1 + 1.5 * 2.0 ** -12, 1 - 1.5 * 2.0 ** -12):
        ft2 = dict(ft, u=np.minimum(ft['u'] * np.float32(s), np.float32(1)))
        for cf, ref in ((coefA, fA), (coefB, fB)):
            c = np.asarray([cf[TERMS.index(t)] for t in order], np.float32)
            dev = max(dev, np.abs(np.clip(eval(expr, {}, dict(ft2, c=c)), 0, 1) - ref).max())
    P('  change if u comes from an unrefined rsqrtps (rel. err 3.7e-4): %.1e' % dev)

    if args.search:
        P('\n== Term selection (backward elimination)')
        ii = np.unique(np.r_[0:8, 8:32:2, 32:257:4, 256])
        start = [(i, j, k, l) for i in range(5) for j in range(6) for k in range(4)
                 for l in range(2) if i + j + k <= 5 and (l == 0 or i + j + k <= 3)]
        sets = backward_select(A, B, feat64, start, (20, 18), np.ix_(ii, ii))
        for n in sorted(sets):
            P('  %d terms:' % n, sets[n])

    # ---- code ----
    n = len(TERMS)
    ca = [coefA[TERMS.index(t)] for t in order]
    cb = [coefB[TERMS.index(t)] for t in order]
    def fl(v):
        t = '%.9g' % np.float32(v)
        return t if ('.' in t or 'e' in t) else t + '.0'
    expr_cpp, _ = horner(TERMS, 'c')
    expr_glsl, _ = horner(TERMS, 'kDfg')
    P('\n== C++ (pseudo code; float2 = the project\'s 2-vector; works unchanged with a SIMD float type F)')
    P('// split-sum DFG, GGX + height-correlated Smith (Khronos glTF Sample Renderer LUT).')
    P('// x = NdotV in [0,1], r = perceptual roughness in [0,1]. Generated by research/shading/dfg_fit.py')
    P('constexpr float kDfgU = %sf;' % fl(C_U))
    for nm, cc in (('kDfgA', ca), ('kDfgB', cb)):
        P('constexpr float %s[%d] = {  // Horner order, see dfgPoly' % (nm, n))
        for i in range(0, n, 6):
            P('    ' + ', '.join(fl(v) + 'f' for v in cc[i:i + 6]) + (',' if i + 6 < n else '};'))
    P('template <class F> inline F dfgPoly(const float* c, F x, F r, F u, F f5) {')
    P('    return %s;' % expr_cpp)
    P('}')
    P('inline float2 dfg(float x, float r) {')
    P('    const float a  = r * r;')
    P('    const float w  = std::max(x * x + kDfgU * (a * a), 1e-30f);')
    P('    const float u  = x / std::sqrt(w);        // x * rsqrt(w)')
    P('    const float y  = 1.0f - x, y2 = y * y;')
    P('    const float f5 = y2 * y2 * y;')
    P('    return float2(std::clamp(dfgPoly(kDfgA, x, r, u, f5), 0.0f, 1.0f),')
    P('                  std::clamp(dfgPoly(kDfgB, x, r, u, f5), 0.0f, 1.0f));')
    P('}')
    P('\n== GLSL')
    P('const float kDfgU = %s;' % fl(C_U))
    P('const vec2 kDfg[%d] = vec2[%d](' % (n, n))
    P(',\n'.join('    vec2(%s, %s)' % (fl(a), fl(b)) for a, b in zip(ca, cb)) + ');')
    P('vec2 dfg(float x, float r) {  // x = NdotV, r = perceptual roughness, both in [0,1]')
    P('    float a = r * r;')
    P('    float u = x * inversesqrt(max(x * x + kDfgU * (a * a), 1e-30));')
    P('    float y = 1.0 - x, y2 = y * y, f5 = y2 * y2 * y;')
    P('    vec2 p = %s;' % expr_glsl)
    P('    return clamp(p, 0.0, 1.0);')
    P('}')
    P('\ntotal run time %.0f s' % (time.time() - t_start))


if __name__ == '__main__':
    main()
