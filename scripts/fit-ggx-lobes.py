#!/usr/bin/env python3
"""Fit eight normalized Phong lobes to the glTF GGX specular lobe over a (N·v, roughness) grid
and write core/ibl/src/ggx_fitted_lobes_table.inc (core/ibl/include/mipgloss/ibl/ggx_fitted_lobes.h
says what is stored; docs/material-truth.md, "Fitted lobes", the objective and what it buys).

    /usr/bin/python3 scripts/fit-ggx-lobes.py            # about 10 minutes
    /usr/bin/python3 scripts/fit-ggx-lobes.py --from-json /tmp/ggx-fitted-lobes.json   # rewrite the table

Needs numpy and scipy (Debian: python3-numpy, python3-scipy). Not run by the build: the table is
data, and its test (tests/core/ibl/test_ggx_fitted_lobes.cpp) measures what the table gives.

The frame: N = z, v = (sin θ, 0, cos θ), R = (−sin θ, 0, cos θ), e1 = (cos θ, 0, sin θ) (toward
N), e2 = y. A lobe is (q1, q2, η, ω): direction normalize(R + α(q1 e1 + q2 e2)), exponent
n = e^(−η)/α² − 2, weight softmax(ω). The objective at one node, over a quadrature of the whole
sphere (polar about R, dense near it: θ' = π t²):
    J = ∫ (p − p̂)² / ∫ p²  +  λ · mean_T (∫ T·(p − p̂))²,     λ = 10,
p the specular lobe D·G2/(4 N·v) of a white metal, normalized to 1, zero below the horizon; p̂ the
weighted sum of the lobes, each over the whole sphere; T the test functions: 73 half-spaces (edges
through the lobe at eight azimuths about R and nine offsets, 0, ±0.5, ±1, ±2, ±4 times 2α, and the
lower hemisphere) and the eight spherical harmonics of orders 1 and 2 (what a smooth sky reads),
each of these weighted as the 73 half-spaces together (MOMENTS = 1). Without the moments the fit
at r 0.6 had a lower J and read a soft sky worse than the visible normals (CPU model, forest:
10.7 % against 8.7 %; with them 1.2 %).
L-BFGS with the analytic gradient, row by row (fit()): a lobe k is the same lobe at neighbouring
nodes, so the nodes interpolate.
"""
import json
import os
import sys

import numpy as np
import scipy.optimize as so

K = 8
LAMBDA = 10.0
MOMENTS = 1.0
# Two variants tried and not adopted (docs/material-truth.md, "Refits tried"); None is the
# committed table's fit.
# --least-exponent N: the widest lobe a fit may use (1: a clamped cosine), by bounds on η. In the
# committed fit n is clamped at 0, where the kernel's gradient in the lobe's direction and exponent
# vanishes: lobes that reach it stay there, pointing wherever they were (r 0.3: 2–4 % of the weight
# on a hemisphere tilted 23° across the plane of incidence).
LEAST_EXPONENT = None
# --anchor: each node also refitted from the row below's at the same N·v, drawn toward it by
# ANCHOR × the free fit's J per unit squared distance, and kept where its J is within
# CONSISTENT_SHARE of the free fit's (fit_node), so that rows interpolate.
ANCHOR = None
CONSISTENT_SHARE = 1.25
# Up to r 0.9, where the mean lobe (ggx_sampling.h, meanLobeShare) has taken over: at r 1 the mean
# lobe reads forest 0.6 % and these lobes 8.2 % (CPU model), and from r 0.85 the fit leaves a mean
# of up to 0.03 across the plane of incidence (0.09 at r 1).
ROUGHNESS = [round(0.1 + 0.05 * i, 3) for i in range(17)]  # kFittedLeastRoughness, kFittedRoughnessStep
COS_NODES = 12                                            # kFittedCosNodes
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "core", "ibl", "src", "ggx_fitted_lobes_table.inc")


def cos_view_of(column):
    x = column / (COS_NODES - 1)
    theta = (1 - (1 - x) ** 2) * np.pi / 2
    return max(np.cos(theta), 0.02)


def radical_inverse(k):
    return int(format(k, "032b")[::-1], 2) * 2.3283064365386963e-10


def frame(mu):
    s = np.sqrt(max(0, 1 - mu * mu))
    v = np.array([s, 0, mu])
    R = np.array([-s, 0, mu])
    if s > 1e-9:
        e1 = np.array([0, 0, 1.0]) - mu * R
        e1 /= np.linalg.norm(e1)
    else:
        e1 = np.array([1.0, 0, 0])
    e2 = np.cross(R, e1)
    return v, R, e1, e2


def quadrature(mu, nt=220, nphi=96):
    v, R, e1, e2 = frame(mu)
    t = (np.arange(nt) + 0.5) / nt
    th = np.pi * t * t
    dth = 2 * np.pi * t / nt
    ph = (np.arange(nphi) + 0.5) / nphi * 2 * np.pi
    TH, PH = np.meshgrid(th, ph, indexing="ij")
    W = np.sin(TH) * dth[:, None] * (2 * np.pi / nphi)
    L = (np.cos(TH)[..., None] * R + np.sin(TH)[..., None] * (np.cos(PH)[..., None] * e1 + np.sin(PH)[..., None] * e2)).reshape(-1, 3)
    return L, W.reshape(-1)


def ggx_lobe(alpha, mu, L):
    """The specular lobe f·(N·l) of a white metal (F = 1), and its (1 − v·h)⁵ part."""
    v, R, e1, e2 = frame(mu)
    a2 = alpha * alpha
    cl = L[:, 2]
    h = L + v
    h /= np.linalg.norm(h, axis=1)[:, None]
    D = a2 / (np.pi * (h[:, 2] ** 2 * (a2 - 1) + 1) ** 2)
    lam = lambda c: (-1 + np.sqrt(1 + a2 * (1 - c * c) / np.maximum(c * c, 1e-12))) / 2
    G2 = 1 / (1 + lam(mu) + lam(np.maximum(cl, 1e-9)))
    p = np.where(cl > 0, D * G2 / (4 * mu), 0.0)
    vh = np.clip(h @ v, 0, 1)
    return p, p * (1 - vh) ** 5


def visible_normal_lookups(alpha, mu):
    """ggx_sampling.h's eight lookups: (light, exponent, weight)."""
    v, R, e1, e2 = frame(mu)
    a2 = alpha * alpha
    vh = np.array([alpha * v[0], alpha * v[1], v[2]])
    vh /= np.linalg.norm(vh)
    ls = vh[0] ** 2 + vh[1] ** 2
    t1 = np.array([-vh[1], vh[0], 0]) / np.sqrt(ls) if ls > 0 else np.array([1.0, 0, 0])
    t2 = np.cross(vh, t1)
    g1 = 2 * mu / (mu + np.sqrt(a2 + (1 - a2) * mu * mu))
    out = []
    for k in range(K):
        u1 = (k + 0.5) / K
        r = np.sqrt(u1)
        phi = 2 * np.pi * radical_inverse(k)
        p1 = r * np.cos(phi)
        s = 0.5 * (1 + vh[2])
        p2 = (1 - s) * np.sqrt(max(0, 1 - p1 * p1)) + s * r * np.sin(phi)
        nh = p1 * t1 + p2 * t2 + np.sqrt(max(0, 1 - p1 * p1 - p2 * p2)) * vh
        h = np.array([alpha * nh[0], alpha * nh[1], max(0, nh[2])])
        h /= np.linalg.norm(h)
        vd = np.clip(v @ h, 0, 1)
        l = 2 * vd * h - v
        cl = l[2]
        d = h[2] ** 2 * (a2 - 1) + 1
        pdf = g1 * a2 / (np.pi * d * d) / (4 * mu)
        n = max(0, 2 * np.pi * K * pdf / 2 - 1)
        den = cl * np.sqrt(mu * mu * (1 - a2) + a2) + mu * np.sqrt(cl * cl * (1 - a2) + a2)
        w = 2 * cl * mu / (den * g1) if cl > 0 else 0
        out.append((l, n, w))
    return out


def parameters_of(lookups, alpha, mu):
    v, R, e1, e2 = frame(mu)
    P = []
    for l, n, w in lookups:
        g = l / max(l @ R, 1e-3)
        P += [(g @ e1) / alpha, (g @ e2) / alpha, np.log(1 / (n + 2) / alpha ** 2), np.log(max(w, 1e-6))]
    return np.array(P)


def lobes(P, alpha, mu, L, grad=False):
    v, R, e1, e2 = frame(mu)
    P = P.reshape(K, 4)
    om = P[:, 3]
    w = np.exp(om - om.max())
    w /= w.sum()
    values, dq, dn = [], [], []
    for k in range(K):
        g = R + alpha * (P[k, 0] * e1 + P[k, 1] * e2)
        gl = np.linalg.norm(g)
        d = g / gl
        # Clamped at 0 (no gradient there) in the committed fit; with --least-exponent, bounds on η
        # keep n ≥ LEAST_EXPONENT (fit_node) and it is not clamped.
        n = np.exp(-P[k, 2]) / alpha ** 2 - 2
        clamped = LEAST_EXPONENT is None and n <= 0
        n = max(n, 0.0) if LEAST_EXPONENT is None else n
        c = np.clip(L @ d, 0, None)
        lc = np.log(np.maximum(c, 1e-300))
        Pk = (n + 1) / (2 * np.pi) * np.where(c > 0, np.exp(n * lc), 0)
        values.append(Pk)
        if grad:
            dPn = np.where(c > 0, Pk * (1 / (n + 1) + lc), 0)
            dn.append(0 * Pk if clamped else -(n + 2) * dPn)
            base = (n + 1) / (2 * np.pi) * n * np.where(c > 0, np.exp((n - 1) * lc), 0)
            dq.append([base * alpha * ((L @ e1) - c * (d @ e1)) / gl, base * alpha * ((L @ e2) - c * (d @ e2)) / gl])
    V = np.array(values)
    ph = w @ V
    return (ph, V, w, dq, dn) if grad else (ph, V, w)


def test_functions(alpha, mu, L):
    """The half-spaces, then the moments: x, y, z, xy, yz, xz, z² − ⅓, x² − y² (the spherical
    harmonics of orders 1 and 2), each weighted MOMENTS times a half-space's whole share."""
    v, R, e1, e2 = frame(mu)
    T = []
    scale = max(alpha, 0.01)
    for b in np.arange(8) * np.pi / 4:
        m = np.cos(b) * e1 + np.sin(b) * e2
        for offset in [-4, -2, -1, -0.5, 0, 0.5, 1, 2, 4]:
            T.append((L @ m) > np.sin(np.clip(offset * scale * 2, -1.5, 1.5)))
    T.append(L[:, 2] < 0.0)
    T = np.array(T, dtype=float)
    x, y, z = L[:, 0], L[:, 1], L[:, 2]
    S = np.array([x, y, z, x * y, y * z, x * z, z * z - 1 / 3, x * x - y * y]) * np.sqrt(MOMENTS * len(T))
    return np.vstack([T, S])


def objective(P, alpha, mu, L, W, p, T, P2, anchor=None, beta=0.0):
    ph, V, w, dq, dn = lobes(P, alpha, mu, L, True)
    r = p - ph
    Wr = W * r
    s = T @ Wr
    nt = len(T)
    J = (r @ Wr) / P2 + LAMBDA / nt * (s @ s)
    dJ = -(2 * Wr / P2 + 2 * LAMBDA / nt * (W * (T.T @ s)))
    g = np.zeros((K, 4))
    for k in range(K):
        g[k, 0] = w[k] * (dJ @ dq[k][0])
        g[k, 1] = w[k] * (dJ @ dq[k][1])
        g[k, 2] = w[k] * (dJ @ dn[k])
        g[k, 3] = w[k] * (dJ @ (V[k] - ph))
    g = g.reshape(-1)
    if anchor is not None:
        d = P - anchor
        J += beta * (d @ d)
        g = g + 2 * beta * d
    return J, g


def fit_node(alpha, mu, start, anchor=None):
    """The fitted parameters, J, the visible normals' J, the albedo and each lobe's edge share."""
    L, W = quadrature(mu)
    p, pB = ggx_lobe(alpha, mu, L)
    E = p @ W
    pn = p / E
    P2 = (pn * pn) @ W
    T = test_functions(alpha, mu, L)
    Pv = parameters_of(visible_normal_lookups(alpha, mu), alpha, mu)
    Pv_clamped = Pv.copy()
    Pv_clamped[2::4] = np.minimum(Pv_clamped[2::4], -np.log(2 * alpha * alpha))  # the visible normals' n ≥ 0
    Jv, _ = objective(Pv_clamped, alpha, mu, L, W, pn, T, P2)
    # η ≤ −ln((LEAST_EXPONENT + 2)·α²), so n ≥ LEAST_EXPONENT; the rest free.
    most = np.inf if LEAST_EXPONENT is None else -np.log((LEAST_EXPONENT + 2) * alpha * alpha)
    bounds = None if LEAST_EXPONENT is None else [(None, most) if i % 4 == 2 else (None, None) for i in range(4 * K)]
    def within(P):  # a start inside the bounds
        P = np.array(P, dtype=float)
        P[2::4] = np.minimum(P[2::4], most)
        return P
    x0 = within(Pv if start is None else start)
    res = so.minimize(objective, x0, args=(alpha, mu, L, W, pn, T, P2), jac=True, bounds=bounds,
                      method="L-BFGS-B", options={"maxiter": 400})
    # The row below's arrangement at this N·v (`anchor`), refitted from there and drawn gently toward
    # it, where it fits nearly as well (J within CONSISTENT_SHARE of the free fit's): where many
    # arrangements fit as well (head-on, lobes turned about R; toward grazing, a lobe that moved
    # from one role to another) the row below's, so that rows interpolate.
    if anchor is not None and ANCHOR is not None:
        beta = ANCHOR * res.fun / max(float((res.x - anchor) @ (res.x - anchor)), 1e-2)
        near = so.minimize(objective, within(anchor), args=(alpha, mu, L, W, pn, T, P2, anchor, beta), jac=True, bounds=bounds,
                           method="L-BFGS-B", options={"maxiter": 400})
        nearJ, _ = objective(near.x, alpha, mu, L, W, pn, T, P2)
        if nearJ <= CONSISTENT_SHARE * res.fun:
            res = near
    res.fun, _ = objective(res.x, alpha, mu, L, W, pn, T, P2)
    ph, V, w = lobes(res.x, alpha, mu, L)
    share = (V @ (W * pB)) / np.maximum(V @ (W * p), 1e-30)
    return {"P": res.x.tolist(), "share": share.tolist(), "J": float(res.fun), "Jvisible": float(Jv), "E": float(E)}


def fit():
    """Row by row: each row's first column (N·v = 1) from the row before's (the first row's from the
    visible normals), each later column from its neighbour toward N·v = 1. So lobe k is the same
    lobe at neighbouring columns, which the renderer interpolates between; continuing each column
    through the rows instead lets neighbouring columns' lobes drift apart (a lower J at every node
    and a worse picture between them: forest r 0.7, CPU model, 8.6 % against 1.3 %)."""
    columns = [[] for _ in range(COS_NODES)]
    first = None
    for r in ROUGHNESS:
        start = first
        for column in range(COS_NODES):
            anchor = np.array(columns[column][-1]["P"]) if columns[column] else None
            node = fit_node(r * r, cos_view_of(column), start, anchor)
            start = np.array(node["P"])
            if column == 0:
                first = start
            columns[column].append(node)
            print(f"r {r:.2f} column {column}: J {node['J']:.5f} (visible normals {node['Jvisible']:.4f})", flush=True)
    return columns  # [column][row]


def aligned(columns):
    """Each row's lobes reordered, one order for the whole row, to match the row below: a node's
    order is only storage, and the renderer interpolates lobe k between rows as between columns.
    Within a row lobe k is already the same lobe along N·v (fit()); the order minimizes the
    distance in (q1, q2, η, ln w) summed over the row's columns."""
    from scipy.optimize import linear_sum_assignment
    out = [[dict(node) for node in column] for column in columns]
    def lobes_of(node):
        P = np.array(node["P"]).reshape(K, 4)
        lw = P[:, 3] - P[:, 3].max() - np.log(np.exp(P[:, 3] - P[:, 3].max()).sum())
        return np.column_stack([P[:, :3], lw])
    for row in range(1, len(out[0])):
        cost = np.zeros((K, K))
        for column in out:
            a, b = lobes_of(column[row - 1]), lobes_of(column[row])
            cost += ((a[:, None, :] - b[None, :, :]) ** 2).sum(axis=2)
        _, order = linear_sum_assignment(cost)
        for column in out:
            here = np.array(column[row]["P"]).reshape(K, 4)
            column[row]["P"] = here[order].reshape(-1).tolist()
            column[row]["share"] = list(np.array(column[row]["share"])[order])
    return out


def write(columns, path=OUT):
    columns = aligned(columns)
    with open(path, "w") as f:
        f.write("// Written by scripts/fit-ggx-lobes.py: [roughness row][N·v column][lobe][q1, q2, η, weightA, weightB].\n")
        f.write(f"// Rows r = {ROUGHNESS[0]} + {ROUGHNESS[1] - ROUGHNESS[0]:.2f}·i; columns x = i/{COS_NODES - 1}. Each node's objective\n")
        f.write("// (fitted, and the eight visible normals'), as a comment after it.\n")
        for row in range(len(ROUGHNESS)):
            f.write("{\n")
            for column in range(COS_NODES):
                node = columns[column][row]
                P = np.array(node["P"]).reshape(K, 4)
                w = np.exp(P[:, 3] - P[:, 3].max())
                w /= w.sum()
                share = np.array(node["share"])
                # Weights below 1e-12 are written as 0 (a lobe no fragment can see).
                tidy = lambda x: 0.0 if abs(x) < 1e-12 else x
                lobes_text = ", ".join("{%.9g, %.9g, %.9g, %.9g, %.9g}" % (P[k, 0], P[k, 1], P[k, 2], tidy(w[k] * (1 - share[k])), tidy(w[k] * share[k]))
                                       for k in range(K))
                f.write(f"  {{{lobes_text}}},  // r {ROUGHNESS[row]:.2f} N·v {cos_view_of(column):.3f}: J {node['J']:.2e} ({node['Jvisible']:.2e})\n")
            f.write("},\n")


if __name__ == "__main__":
    if len(sys.argv) > 2 and sys.argv[1] == "--from-json":  # write the table from a saved fit
        write([column[:len(ROUGHNESS)] for column in json.load(open(sys.argv[2]))])
    else:
        args = sys.argv[1:]
        if "--least-exponent" in args:
            LEAST_EXPONENT = float(args[args.index("--least-exponent") + 1])
        if "--anchor" in args:
            ANCHOR = 0.01
        columns = fit()
        json.dump(columns, open(os.path.join("/tmp", "ggx-fitted-lobes.json"), "w"))
        write(columns)
