"""Benchmark of issue 16, item 4: the Mohr–Coulomb soil kernel per Gauss point against its arithmetic.

``soil_mc_ns_per_gp``: wall time of the forces-only Q8 kernel (modified Newton's residual) per Gauss point
on 50 000 elements of an implicit Mohr–Coulomb soil (phi = 20 deg, c = 10 kPa), with the stress states of a
loaded soil (a mix of elastic and plastic points, measured and printed), best of 5 in one process after JIT.
``soil_mc_consistent_ns_per_gp``: the same with the consistent tangent (element matrices filled).

``plate_rc_ns_per_layer_point``: the plate strip's kernel (forces and consistent tangent) per layer point
(elements x points x layers) on 2 000 elements of chapter 11's RC section (9 concrete and 2 steel layers, the
chord self-bending term: 2 extra law calls per concrete layer at the bending points), bent to curvatures of
1e-4 to 5e-2 1/m from a committed cracked and crushed history (printed: the cracked fraction); the crack band
as the scenes set it, per layer. ``plate_rc_point_band_ns_per_layer_point``: the same with the band width set
per point (``crack_band="point"``, the beam studies): the concrete law's constants are then recomputed at
every point.

``soil_mc_arithmetic_ns_per_gp``: what the arithmetic alone would cost on this machine: the operation count
of one point (counted by hand from the kernel, below) times the time of one scalar floating-point operation,
one square root and one division, each measured in the same run by small numba loops. Goal: the kernel
within 3x of it.
"""

import math
import time

import numpy as np
from goals import verdict
from numba import njit

import ssi  # noqa: F401  (first: it keys numba's cache on the package sources before numba is imported)
from ssi.core.protocol import CONSISTENT, FORCES_ONLY
from ssi.elements.plate import PlateStrip
from ssi.elements.soil_q8 import SoilQ8
from ssi.lab.examples import chapter11_section
from ssi.materials.layer_laws import CONCRETE
from ssi.materials.soil_laws import material_table, mohr_coulomb_params

N_EL = 50_000
# Operation count of one 2x2-rule point of the forces-only kernel (additions and multiplications), counted
# from the code:
#   Jacobian 8 nodes x 4 entries x 2 = 64; det 3 and its inverse (1 division); physical gradients
#   8 x 2 x 3 = 48; strain increment 8 x 8 = 64; trial stress 18; in-plane principal values and axes
#   (half-angle formulas) 12, 2 square roots, 2 divisions; ordering 3 compares; yield check 9;
#   forces 8 x 2 x 5 = 80; weight 1  -> about 302 operations, 2 square roots, 3 divisions.
# A plastic point adds the plane return with d(sig)/d(trial) (~50, 2 divisions), the stress back on the axes
# (~25) and the plastic strain norm (~25, 3 divisions, 1 square root): counted for the plastic fraction
# measured below. (Until the principal axes took the half-angle formulas, an elastic point also paid atan2,
# cos and sin, and every point the material's sin(phi), sin(psi) and sqrt(k).)
FLOPS_ELASTIC, SQRT_ELASTIC, DIV_ELASTIC = 302, 2, 3
FLOPS_PLASTIC_EXTRA, SQRT_PLASTIC_EXTRA, DIV_PLASTIC_EXTRA = 100, 1, 5


@njit(cache=True)
def _flop_loop(n, x):
    # 8 independent multiply-add chains: what a scalar kernel with some instruction-level parallelism gets
    a0 = a1 = a2 = a3 = a4 = a5 = a6 = a7 = 0.0
    for _ in range(n):
        a0 = a0 * x + 1.0
        a1 = a1 * x + 2.0
        a2 = a2 * x + 3.0
        a3 = a3 * x + 4.0
        a4 = a4 * x + 5.0
        a5 = a5 * x + 6.0
        a6 = a6 * x + 7.0
        a7 = a7 * x + 8.0
    return a0 + a1 + a2 + a3 + a4 + a5 + a6 + a7  # 16 operations per iteration


@njit(cache=True)
def _sqrt_loop(n, x):
    s = 0.0
    for i in range(n):
        t = x + 1e-9 * i
        s += math.sqrt(t) + math.sqrt(t + 1.0)
    return s  # 2 square roots (and 4 additions, not subtracted: the estimate errs towards fast)


@njit(cache=True)
def _div_loop(n, x):
    s = 0.0
    for i in range(n):
        t = x + 1e-9 * i
        s += 1.0 / t + 2.0 / (t + 1.0)
    return s  # 2 divisions


def best(fn, repeat=5):
    out = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t0)
    return min(out)


def machine_rates():
    """(ns per scalar operation, ns per square root, ns per division), each best of 5."""
    n = 20_000_000
    _flop_loop(10, 0.5)
    _sqrt_loop(10, 0.5)
    _div_loop(10, 0.5)
    t_flop = best(lambda: _flop_loop(n, 0.999999)) / (16 * n) * 1e9
    t_sqrt = best(lambda: _sqrt_loop(n // 4, 0.5)) / (2 * (n // 4)) * 1e9
    t_div = best(lambda: _div_loop(n // 4, 0.5)) / (2 * (n // 4)) * 1e9
    return t_flop, t_sqrt, t_div


def loaded_group():
    """50 000 distorted Q8 elements of one MC soil with stresses around yield and a strain increment."""
    rng = np.random.default_rng(0)
    ref = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1], [0, -1], [1, 0], [0, 1], [-1, 0]], float)
    corners = ref[:4] + rng.uniform(-0.2, 0.2, (N_EL, 4, 2))
    mids = 0.5 * (corners + np.roll(corners, -1, axis=1))
    coords = np.concatenate([corners, mids], axis=1) * 0.25
    kinds, params = material_table([mohr_coulomb_params(20e6, 0.3, 10e3, 20.0)])
    group = SoilQ8(coords, np.arange(N_EL * 16).reshape(N_EL, 16), 0, kinds, params)
    state = group.initial_state()
    p = rng.uniform(-150e3, -10e3, (N_EL, 4))
    state[:, :, 0] = p + rng.normal(0, 25e3, p.shape)
    state[:, :, 1] = p + rng.normal(0, 25e3, p.shape)
    state[:, :, 2] = rng.normal(0, 15e3, p.shape)
    state[:, :, 3] = p
    du = rng.normal(0.0, 2e-4, (N_EL, 16))
    return group, du, state


def bent_rc_strip(crack_band, n_el=2_000):
    """(group, u_el, committed state) of chapter 11's RC section, elements 0.2 m long, random curvatures."""
    rng = np.random.default_rng(1)
    coords = np.zeros((n_el, 3, 2))
    coords[:, :, 0] = 0.2 * np.arange(n_el)[:, None] + np.array([0.0, 0.1, 0.2])
    group = PlateStrip(
        coords, np.arange(9 * n_el).reshape(n_el, 9), chapter11_section(), crack_band=crack_band
    )
    xs = coords[:, :, 0] - coords[:, :1, 0]
    kap = rng.choice([1e-4, 1e-3, 1e-2, 5e-2], n_el) * rng.choice([-1.0, 1.0], n_el)
    u_el = np.zeros((n_el, 9))
    u_el[:, 0::3] = rng.uniform(-2e-3, 1e-3, (n_el, 1)) * xs
    u_el[:, 2::3] = kap[:, None] * xs
    u_el[:, 1::3] = 0.5 * kap[:, None] * xs**2
    _, _, state = group.evaluate(1.5 * u_el[::-1], None, group.initial_state(), CONSISTENT)
    return group, u_el, state


def plate_ns_per_layer_point(crack_band):
    group, u_el, state = bent_rc_strip(crack_band)
    group.evaluate(u_el, None, state, CONSISTENT)
    n_points = group.n_el * group.n_ip * group.section.n_layer
    cracked = float(np.mean(state[..., group.section.kind == CONCRETE, 1] > 0.0))
    return best(lambda: group.evaluate(u_el, None, state, CONSISTENT)) / n_points * 1e9, cracked


def main():
    group, du, state = loaded_group()
    n_gp = group.n_el * len(group.gw)
    _, _, new = group.evaluate(du, du, state, FORCES_ONLY)
    plastic = float(np.mean(new[:, :, 5] > 0))
    t_forces = best(lambda: group.evaluate(du, du, state, FORCES_ONLY)) / n_gp * 1e9
    group.evaluate(du, du, state, CONSISTENT)
    t_consistent = best(lambda: group.evaluate(du, du, state, CONSISTENT)) / n_gp * 1e9
    t_flop, t_sqrt, t_div = machine_rates()
    arith = (
        FLOPS_ELASTIC * t_flop
        + SQRT_ELASTIC * t_sqrt
        + DIV_ELASTIC * t_div
        + plastic * (FLOPS_PLASTIC_EXTRA * t_flop + SQRT_PLASTIC_EXTRA * t_sqrt + DIV_PLASTIC_EXTRA * t_div)
    )
    print(f"soil_mc_plastic_fraction: {plastic:.3f}")
    print(f"machine_ns_per_flop: {t_flop:.3f}")
    print(f"machine_ns_per_sqrt: {t_sqrt:.2f}")
    print(f"machine_ns_per_division: {t_div:.2f}")
    print(f"soil_mc_arithmetic_ns_per_gp: {arith:.1f}")
    print(f"soil_mc_ns_per_gp: {t_forces:.1f}{verdict(t_forces, '<=', 3 * arith, ' ns = 3 x arithmetic')}")
    print(f"soil_mc_over_arithmetic: {t_forces / arith:.2f}{verdict(t_forces / arith, '<=', 3.0)}")
    print(f"soil_mc_consistent_ns_per_gp: {t_consistent:.1f}")
    t_plate, cracked = plate_ns_per_layer_point(None)
    print(f"plate_rc_cracked_fraction: {cracked:.3f}")
    print(f"plate_rc_ns_per_layer_point: {t_plate:.1f}")
    print(f"plate_rc_point_band_ns_per_layer_point: {plate_ns_per_layer_point('point')[0]:.1f}")


if __name__ == "__main__":
    main()
