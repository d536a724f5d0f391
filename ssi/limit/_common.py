"""Helpers both bounds share: scales, element gradients, boundary edges with their elements and normals."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .geometry import Site
from .mesh import TriMesh


@dataclass
class Scales:
    """Non-dimensional units of one problem: length ``L`` [m], stress ``S`` [Pa], and ``k`` the size of the
    reference load in S L units (the load factor's variable is mu = k lambda, of order one)."""

    L: float
    S: float
    k: float


def scales(site: Site) -> Scales:
    L = site.length_scale
    s = [m.c for m in site.materials] + [m.gamma * L for m in site.materials]
    ref = 0.0
    for i, j, b in site.segments:
        if b is not None and b.kind == "free":
            length = float(np.hypot(*(site.points[j] - site.points[i])))
            s += [abs(b.dead_at(*site.points[i])), abs(b.dead_at(*site.points[j])), abs(b.pressure_ref)]
            ref += abs(b.pressure_ref) * length
    for f in site.footings:
        s += [float(np.hypot(*f.load_ref)) / L, float(np.hypot(*f.load_dead)) / L]
        s += [abs(f.moment_ref) / L**2, abs(f.moment_dead) / L**2]
        ref += float(np.hypot(*f.load_ref)) + abs(f.moment_ref) / L
    S = max(max(s), 1e-12)
    if site.scale_all:  # lambda scales the dead loads and the weight too: they are part of the reference
        for i, j, b in site.segments:
            if b is not None and b.kind == "free":
                length = float(np.hypot(*(site.points[j] - site.points[i])))
                ref += 0.5 * (abs(b.dead_at(*site.points[i])) + abs(b.dead_at(*site.points[j]))) * length
        for f in site.footings:
            ref += float(np.hypot(*f.load_dead)) + abs(f.moment_dead) / L
        ref += max(m.gamma for m in site.materials) * L * L  # the weight's order of magnitude
        if ref == 0.0:
            raise ValueError("the site has no load at all: no weight, no dead load, no reference load")
    if ref == 0.0:
        raise ValueError("the site has no reference load: give a footing load_ref or a pressure_ref")
    return Scales(L, S, ref / (S * L))


def gradients(xy: np.ndarray, tri: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(b, c, A): dL_k/dx = b_k / (2A), dL_k/dz = c_k / (2A) of the barycentric coordinates L_k, (n_el, 3)
    each, and the areas (n_el,)."""
    p = xy[tri]
    x, z = p[..., 0], p[..., 1]
    b = np.stack([z[:, 1] - z[:, 2], z[:, 2] - z[:, 0], z[:, 0] - z[:, 1]], axis=1)
    c = np.stack([x[:, 2] - x[:, 1], x[:, 0] - x[:, 2], x[:, 1] - x[:, 0]], axis=1)
    A = 0.5 * (b[:, 0] * c[:, 1] - b[:, 1] * c[:, 0])
    return b, c, A


@dataclass
class BoundaryEdges:
    """Each boundary edge: nodes (p, q), its element, the local vertices of p and q in it, the outward unit
    normal n (n_b, 2), length (n_b,), the midside-node edge index, and the site segment."""

    p: np.ndarray
    q: np.ndarray
    el: np.ndarray
    lp: np.ndarray
    lq: np.ndarray
    n: np.ndarray
    length: np.ndarray
    edge: np.ndarray
    seg: np.ndarray


def boundary_edges(mesh: TriMesh, xy: np.ndarray) -> BoundaryEdges:
    edges, el_edge = mesh.edges()
    index = {tuple(e): i for i, e in enumerate(edges)}
    owner = {}
    for e in range(mesh.n_el):
        for k in range(3):
            owner.setdefault(int(el_edge[e, k]), []).append(e)
    p, q = mesh.bnd[:, 0], mesh.bnd[:, 1]
    eid = np.array([index[(min(a, b), max(a, b))] for a, b in zip(p, q)], np.int64)
    el = np.array([owner[i][0] for i in eid], np.int64)
    if any(len(owner[i]) != 1 for i in eid):
        raise ValueError("a labelled boundary segment runs through the inside of the domain")
    t = mesh.tri[el]
    lp = np.argmax(t == p[:, None], axis=1)
    lq = np.argmax(t == q[:, None], axis=1)
    d = xy[q] - xy[p]
    length = np.hypot(d[:, 0], d[:, 1])
    n = np.stack([d[:, 1], -d[:, 0]], axis=1) / length[:, None]
    return BoundaryEdges(p, q, el, lp, lq, n, length, eid, mesh.bnd_seg.copy())


def interior_edges(mesh: TriMesh) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Interior edges: (e1, k1, e2, k2, edge index), the two elements and their local side numbers."""
    edges, el_edge = mesh.edges()
    flat = el_edge.ravel()
    order = np.argsort(flat, kind="stable")
    sorted_e = flat[order]
    same = np.flatnonzero(sorted_e[1:] == sorted_e[:-1])
    a, b = order[same], order[same + 1]
    return a // 3, a % 3, b // 3, b % 3, sorted_e[same]


def strength(material, S: float) -> tuple[float, float, float]:
    """(2 c cos phi / S, sin phi, cos phi) of a material."""
    phi = math.radians(material.phi_deg)
    return 2.0 * material.c * math.cos(phi) / S, math.sin(phi), math.cos(phi)
