"""Benchmark of the site path (issue 25's keys, measured here rather than as chapter 19 rows: a wall time on a
shared machine is a benchmark, not a reproduced number).

- ``site_mesh_s``: chapter 19's four-layer borehole site with two strips (three boreholes, 30 m x 12 m,
  h_fine = 0.125 m): gmsh mesh + build, after one warm-up build; goal <= 2 s.
- ``site_solve_per_dof_vs_structured``: chapter 19's level two-borehole site (one strip under a 400 kN/m
  column, linear: one factorisation and one solve) on the gmsh mesh and on the structured block, solve time
  per DOF, best of three each, both measured in this run; goal <= 1.3.
"""

import time

from goals import verdict

import ssi  # noqa: F401  (first: keys numba's cache)
from ssi.elements.section import homogeneous
from ssi.scene import ColumnLoad, Contact, Foundation, MeshSize, SoilLayer
from ssi.scene.site import Borehole, Site, Strip

MESH = MeshSize(h_fine=0.125, h_coarse=2.0)
SECTION = homogeneous(0.5, 30e9, 0.2)
CONTACT = Contact(kn=1e10, kt=1e9)
TWO = [SoilLayer(3.0, E=20e6, nu=0.3, unit_weight=18e3), SoilLayer(7.0, E=60e6, nu=0.25, unit_weight=20e3)]
FOUR = [
    SoilLayer(1.0, E=10e6, nu=0.3, unit_weight=18e3),
    SoilLayer(1.0, E=30e6, nu=0.3, unit_weight=19e3),
    SoilLayer(1.0, E=50e6, nu=0.3, unit_weight=19e3),
    SoilLayer(1.0, E=80e6, nu=0.3, unit_weight=20e3),
]
BOREHOLES = [
    Borehole(-10.0, [-2.0, -4.0, -7.0]),
    Borehole(0.0, [-2.5, -2.5, -6.0]),
    Borehole(10.0, [-3.5, -5.0, -8.0]),
]


def two_strips() -> Site:
    return Site(
        30.0,
        12.0,
        FOUR,
        boreholes=BOREHOLES,
        mesh=MESH,
        strips=[
            Strip(Foundation(-6.0, -4.0, SECTION), CONTACT),
            Strip(Foundation(3.0, 5.0, SECTION), CONTACT),
        ],
        loads=[ColumnLoad(-5.0, N=300e3), ColumnLoad(4.0, N=200e3)],
    )


def level_site(mesher: str) -> Site:
    return Site(
        20.0,
        10.0,
        TWO,
        boreholes=[Borehole(-5.0, [-3.0]), Borehole(5.0, [-3.0])],
        strips=[Strip(Foundation(-1.0, 1.0, SECTION), CONTACT)],
        loads=[ColumnLoad(0.0, N=400e3)],
        mesh=MESH,
        mesher=mesher,
    )


def solve_per_dof(mesher: str) -> float:
    built = level_site(mesher).build()
    built.solve()  # warm-up: kernels compiled, caches filled
    best = float("inf")
    for _ in range(3):
        t0 = time.perf_counter()
        built.solve()
        best = min(best, time.perf_counter() - t0)
    return best / built.model.n_dof


def main() -> None:
    two_strips().build()  # warm-up (the first gmsh call, plate and interface kernels)
    t0 = time.perf_counter()
    two_strips().build()
    mesh_s = time.perf_counter() - t0
    print(f"site_mesh_s: {mesh_s:.3f}" + verdict(mesh_s, "<=", 2.0, " s"))
    ratio = solve_per_dof("gmsh") / solve_per_dof("structured")
    print(f"site_solve_per_dof_vs_structured: {ratio:.3f}" + verdict(ratio, "<=", 1.3))


if __name__ == "__main__":
    main()
