# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""K-means clustering of convection order parameters (Psi1, Psi2) and the classification of a
vibrated bed's state into 0, 1 or 2 convection rolls (Risso et al. 2005, Fig. 4).

Risso's reading of the (Psi1, Psi2) plane:
- no convection: both order parameters vanish; samples scatter about the origin with the
  finite-N noise of the sums;
- one roll: Psi1 is distinctly nonzero (its sign is the sense of rotation), Psi2 any sign;
- two rolls: Psi1 vanishes, Psi2 is distinctly nonzero (positive when the gas rises in the middle).
When states coexist (jumps between clockwise and counter-clockwise rolls, or between one and two
rolls), the samples form several clusters; K-means finds their centres.
"""
import numpy as np
from scipy.cluster.vq import kmeans2

ROLLS = {0: "no convection", 1: "one roll", 2: "two rolls"}


def kmeans(X, k, seed=0, restarts=10, iters=300):
    """K-means by scipy.cluster.vq.kmeans2 (k-means++ seeding), best of `restarts` runs by
    within-cluster sum of squares, every run drawn from one generator seeded with `seed` (the
    same X and seed give the same result). Returns (centres (k, d), labels (n,), inertia)."""
    X = np.asarray(X, dtype=float)
    n = len(X)
    if not 1 <= k <= n:
        raise ValueError(f"k = {k} must be between 1 and the number of samples ({n})")
    rng = np.random.default_rng(seed)
    best = None
    for _ in range(restarts):
        C, labels = kmeans2(X, k, iter=iters, minit="++", missing="warn", seed=rng)
        inertia = float(((X - C[labels]) ** 2).sum())
        if best is None or inertia < best[2]:
            best = (C, labels, inertia)
    return best


def _spread(X, labels, C):
    """Pooled within-cluster standard deviation per coordinate."""
    r = X - C[labels]
    dof = max(len(X) - len(C), 1)
    return float(np.sqrt((r ** 2).sum() / (dof * X.shape[1])))


def cluster_states(X, kmax=3, seed=0, separation=4.0):
    """Clusters of the (Psi1, Psi2) samples X (n, 2): K-means with k = kmax, then clusters whose
    centres lie closer than `separation` pooled standard deviations are merged, so a single state
    gives one cluster and coexisting states give one cluster each. Returns a list of dicts
    (centre, weight, rolls, label) sorted by weight, and the pooled spread."""
    X = np.asarray(X, dtype=float)
    k = min(kmax, len(X))
    C, labels, _ = kmeans(X, k, seed=seed)
    sigma = _spread(X, labels, C)
    # merge the closest pair while it is closer than the separation
    groups = [[j] for j in range(k)]
    while len(groups) > 1:
        cents = [X[np.isin(labels, g)].mean(axis=0) for g in groups]
        best = None
        for a in range(len(groups)):
            for b in range(a + 1, len(groups)):
                d = np.hypot(*(cents[a] - cents[b]))
                if best is None or d < best[0]:
                    best = (d, a, b)
        if best[0] >= separation * sigma:
            break
        _, a, b = best
        groups[a] += groups[b]
        del groups[b]
    out = []
    for g in groups:
        sel = np.isin(labels, g)
        c = X[sel].mean(axis=0)
        out.append({"centre": c, "weight": float(sel.mean()), "n": int(sel.sum()),
                    "rolls": rolls_of(c, sigma, separation)})
    out.sort(key=lambda s: -s["weight"])
    for s in out:
        s["label"] = ROLLS[s["rolls"]]
    return out, sigma


def rolls_of(centre, sigma, separation=4.0):
    """0, 1 or 2 rolls for a cluster centre (Psi1, Psi2): no convection when the centre is within
    separation/2 pooled standard deviations of the origin (indistinguishable from the noise of a
    static bed), otherwise one roll when |Psi1| >= |Psi2| and two rolls when |Psi2| > |Psi1|."""
    p1, p2 = float(centre[0]), float(centre[1])
    if np.hypot(p1, p2) < 0.5 * separation * sigma:
        return 0
    return 1 if abs(p1) >= abs(p2) else 2


def classify(X, **kw):
    """The state of a run: the rolls of its heaviest cluster, the weights of every state found
    (coexistence when more than one has weight >= 0.1), and the clusters themselves."""
    clusters, sigma = cluster_states(X, **kw)
    weights = {0: 0.0, 1: 0.0, 2: 0.0}
    for c in clusters:
        weights[c["rolls"]] += c["weight"]
    present = sorted(r for r, w in weights.items() if w >= 0.1)
    return {"rolls": clusters[0]["rolls"], "weights": weights, "coexisting": present,
            "clusters": clusters, "sigma": sigma}
