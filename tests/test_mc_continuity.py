"""The soil and contact laws are continuous functions of the strain (gap) increment across every boundary of
their return regions (issue 31: is the controlled path's residual floor a jump of a law?).

For random committed stresses and pairs of increments a, b whose updates end in different branches, the
segment a -> b is bisected 45 times onto the branch boundary (the bracket is then 2^-45 |b - a| ~ 1e-17
strain wide) and the stresses on its two ends are compared. A continuous law gives a difference of the order
of the round-off of its region tests (1e-12 of the stress scale; measured at most ~2e-11 on these draws);
a return to a wrong branch, or a branch that does not meet its neighbour, is of the order of the plastic
correction itself (>= 1e-3 of the stress scale). The tolerance 1e-9 of the stress scale lies between the two
by orders of magnitude either way. The references are the law's own outputs on the other side of the
boundary: the claim checked is continuity, not a value.
"""

import numpy as np
import pytest

from ssi.core.protocol import CONSISTENT
from ssi.materials.interface_law import H_OPEN, H_STATUS, N_HIST, OPEN, interface_params, interface_update
from ssi.materials.soil_laws import mohr_coulomb_params, soil_update

E, NU = 20e6, 0.3
BISECTIONS = 45
JUMP_TOL = 1e-9  # of the stress scale: round-off ~1e-12 below it, a missed branch ~1e-3 above (docstring)


def _soil(kind, p, deps, sig0):
    s, h, D = np.zeros(4), np.zeros(2), np.zeros((4, 4))
    soil_update(kind, p, deps, sig0, np.zeros(2), s, h, D, CONSISTENT)
    return int(h[1]), s


def _boundary_jump(update, a, b):
    """(branch below, branch above, |output jump|) at the branch boundary on the segment a -> b."""
    code_a, _ = update(a)
    lo, hi = 0.0, 1.0
    for _ in range(BISECTIONS):
        mid = 0.5 * (lo + hi)
        if update(a + mid * (b - a))[0] == code_a:
            lo = mid
        else:
            hi = mid
    c_lo, s_lo = update(a + lo * (b - a))
    c_hi, s_hi = update(a + hi * (b - a))
    return c_lo, c_hi, float(np.linalg.norm(s_hi - s_lo))


@pytest.mark.parametrize(
    "c, phi, psi",
    [(0.0, 30.0, 0.0), (1e3, 35.0, 5.0), (10e3, 25.0, 0.0), (10e3, 30.0, 30.0), (5e3, 0.0, 0.0)],
)
def test_mohr_coulomb_return_is_continuous_across_its_region_boundaries(c, phi, psi):
    """Elastic / plane / edge / apex boundaries of the implicit return (the zoo's soils: psi = 0 on a
    cohesionless and a cohesive layer, psi = 5 deg on phi = 35 deg; associated; Tresca)."""
    kind, p = mohr_coulomb_params(E, NU, c, phi, psi)
    rng = np.random.default_rng(7)
    crossed = set()
    for _ in range(1500):
        sig0 = rng.uniform(-60e3, 10e3, 4)
        sig0[2] *= 0.5
        a = np.append(rng.normal(size=3) * 1e-3, 0.0)
        b = a + np.append(rng.normal(size=3) * 1e-3, 0.0)

        def update(d, sig0=sig0):
            return _soil(kind, p, d, sig0)

        if update(a)[0] == update(b)[0]:
            continue
        lo, hi, jump = _boundary_jump(update, a, b)
        scale = np.abs(sig0).max() + 2.0 * E * max(np.abs(a).max(), np.abs(b).max())
        assert jump <= JUMP_TOL * scale, (lo, hi, jump, scale, sig0, a, b)
        crossed.add(frozenset((lo, hi)))
    # the draws reach every kind of boundary the material has (0 elastic, 1 plane, 2/3 edges, 4 apex)
    expected = {frozenset(x) for x in [(0, 1), (1, 2), (1, 3)]}
    if phi > 0.0:
        expected |= {frozenset(x) for x in [(2, 4), (3, 4)]}
    assert expected <= crossed, crossed


@pytest.mark.parametrize("phi, psi", [(20.0, 0.0), (30.0, 30.0)])
def test_interface_law_is_continuous_across_stick_slip_open(phi, psi):
    """Stick / slip / open boundaries of the contact law from a closed and from an open point (the zoo's
    contact: c = 0, psi_i = 0 or phi_i)."""
    kn = 1e10
    p = interface_params(1e9, kn, phi, 0.0, psi)
    rng = np.random.default_rng(3)
    crossed = set()
    for _ in range(1500):
        h0 = np.zeros(N_HIST)
        if rng.random() < 0.3:
            h0[H_STATUS], h0[H_OPEN], t0 = OPEN, rng.uniform(0.0, 1e-5), np.zeros(2)
        else:
            t0 = np.array([rng.uniform(-3e4, 3e4), rng.uniform(-1e5, 0.0)])
        a = rng.normal(size=2) * 1e-5
        b = a + rng.normal(size=2) * 1e-5

        def update(dg, t0=t0, h0=h0):
            t, h, D = np.zeros(2), np.zeros(N_HIST), np.zeros((2, 2))
            return int(interface_update(p, dg, t0, h0, t, h, D, 1)), t

        if update(a)[0] == update(b)[0]:
            continue
        lo, hi, jump = _boundary_jump(update, a, b)
        scale = np.abs(t0).max() + kn * max(np.abs(a).max(), np.abs(b).max())
        assert jump <= JUMP_TOL * scale, (lo, hi, jump, scale, t0, h0, a, b)
        crossed.add(frozenset((lo, hi)))
    assert {frozenset(x) for x in [(0, 1), (1, 2), (0, 2)]} <= crossed, crossed
