"""The SECANT_SOFTENING tangent flag (issue 31, item 2): the concrete's secant modulus sig / e where a point
loads on its cracked tension envelope, the exact consistent tangent everywhere else, and internal forces and
histories that do not depend on the flag.

Tolerances: the flag changes only which modulus is returned, so stresses, histories, forces and the
matrices of points off the softening envelope are compared bit for bit; the secant sig / e is the same
division the law does, so it is compared to 1e-14 (relative: a few ulps of the division)."""

from dataclasses import replace

import numpy as np
import pytest

# (name, strain, committed history) in every branch of the law: test_concrete_steel's table (pytest puts
# tests/ on sys.path)
from test_concrete_steel import CONCRETE_BRANCHES

from ssi.core.model import System
from ssi.core.protocol import CONSISTENT, SECANT_SOFTENING
from ssi.elements.plate import PlateStrip
from ssi.elements.section import paper_rc_section
from ssi.lab.examples import chapter11_foundation
from ssi.materials import rc
from ssi.materials.concrete import C_E0, P_EPS_C, P_EPS_CU, P_FC, concrete_constants, irreversible_strain
from ssi.materials.layer_laws import CONCRETE, N_LAYER_HIST, STEEL, layer_update
from ssi.solver import Settings, path


def concrete():
    return rc.concrete_params(30.0e6, 30.0e9, 0.0022, 3.0e6, 100.0, 0.1, 500.0e6 / 200.0e9, alpha_ts=0.5)


def hist(*values):
    h = np.zeros(N_LAYER_HIST)
    h[: len(values)] = values
    return h


def rc_test_section():
    conc = rc.concrete_params(fc=30e6, E0=30e9, eps_c=0.002, fr=3e6, Gf=100.0, ls=0.1, eps_y=2.5e-3)
    steel = rc.steel_params(fy=500e6, Es=200e9, EH=2e9)
    return paper_rc_section(0.5, 0.05, 1.5e-3, 0.8e-3, (CONCRETE, conc), (STEEL, steel))


def one_element(section, x, **kw):
    xy = np.column_stack([np.asarray(x, float), np.zeros(3)])
    return PlateStrip(xy[None], np.arange(9)[None], section, **kw)


# the branches loading on the cracked tension envelope (the third after a compression: from its irreversible
# strain)
SOFTENING = {"softening", "tension stiffening", "reloading tension after compression"}


@pytest.mark.parametrize("name,eps,h", CONCRETE_BRANCHES, ids=[b[0] for b in CONCRETE_BRANCHES])
def test_concrete_secant_where_softening_exact_elsewhere(name, eps, h):
    p = concrete()
    h_c, h_s = np.zeros(N_LAYER_HIST), np.zeros(N_LAYER_HIST)
    sig, tau, e_t, g_t = layer_update(CONCRETE, p, eps, 1e-4, h, h_c, CONSISTENT)
    sig_s, tau_s, e_s, g_s = layer_update(CONCRETE, p, eps, 1e-4, h, h_s, SECANT_SOFTENING)
    assert (sig_s, tau_s, g_s) == (sig, tau, g_t) and np.array_equal(h_s, h_c)
    if name in SOFTENING:
        assert e_t < 0.0  # the exact tangent is negative there ...
        const = concrete_constants(p)
        e = eps + irreversible_strain(h[0], const[C_E0], p[P_FC], p[P_EPS_C], p[P_EPS_CU])
        assert e_s == pytest.approx(sig / e, rel=1e-14) and e_s > 0.0  # ... the secant is not
    else:
        assert e_s == e_t


def test_cracked_envelope_secant_is_the_unloading_modulus():
    """The secant returned while loading on the envelope is the modulus the point unloads along from there."""
    p = concrete()
    eps = 3e-4
    h_new = np.zeros(N_LAYER_HIST)
    sig, _, e_s, _ = layer_update(CONCRETE, p, eps, 0.0, hist(0.0, 2e-4), h_new, SECANT_SOFTENING)
    sig_u, _, e_u, _ = layer_update(CONCRETE, p, 0.5 * eps, 0.0, h_new, np.zeros(N_LAYER_HIST), CONSISTENT)
    assert e_s == pytest.approx(e_u, rel=1e-14) and sig_u == pytest.approx(0.5 * sig, rel=1e-14)


def bent(g, kap, eps0=2.0e-5):
    x = g.coords[0, :, 0]
    u = np.zeros((1, 9))
    u[0, 0::3] = eps0 * x
    u[0, 1::3] = 0.5 * kap * x**2
    u[0, 2::3] = kap * x
    return u


@pytest.mark.parametrize("self_bending", ["initial", "chord", "tangent"])
def test_plate_forces_independent_of_the_flag(self_bending):
    g = one_element(rc_test_section(), x=(0.0, 0.5, 1.0), self_bending=self_bending)
    assert g.secant_softening
    for kap in (1e-5, 0.004, 0.02):  # elastic; cracked bottom; yielding bottom steel
        u = bent(g, kap)
        f1, k1, s1 = g.evaluate(u, u, g.initial_state(), CONSISTENT)
        f2, k2, s2 = g.evaluate(u, u, g.initial_state(), SECANT_SOFTENING)
        assert np.array_equal(f1, f2) and np.array_equal(s1, s2)
        if kap == 1e-5 or self_bending == "tangent":  # nothing softens, or the flag is not honoured
            assert np.array_equal(k1, k2)


def test_plate_secant_stiffer_than_the_tangent_where_cracked():
    """With the initial self-bending term each layer enters the section matrix as h_n e (1, -z; -z, z^2):
    replacing the negative tangent of the softening layers by their positive secant adds a positive
    semi-definite matrix, non-zero in a cracked state."""
    g = one_element(rc_test_section(), x=(0.0, 0.5, 1.0), self_bending="initial")
    u = bent(g, 0.004)
    k1 = g.evaluate(u, u, g.initial_state(), CONSISTENT)[1][0]
    k2 = g.evaluate(u, u, g.initial_state(), SECANT_SOFTENING)[1][0]
    diff = k2 - k1
    scale = np.abs(k1).max()
    assert np.abs(diff - diff.T).max() <= 1e-12 * scale
    eig = np.linalg.eigvalsh(0.5 * (diff + diff.T))
    assert eig.min() >= -1e-10 * scale and eig.max() > 1e-4 * scale


def test_model_gives_the_flag_only_to_groups_that_declare_it():
    """Soil and interface groups get CONSISTENT when the solver asks for SECANT_SOFTENING."""
    model = chapter11_foundation(0.5).build().model
    system = System(model)
    u, states = system.start(0.0)
    rng = np.random.default_rng(3)
    u = u + 1e-4 * rng.standard_normal(u.shape)
    f1, k1, _ = system.evaluate(u, u, states, CONSISTENT)
    f2, k2, _ = system.evaluate(u, u, states, SECANT_SOFTENING)
    assert np.array_equal(f1, f2)
    assert any(isinstance(gr, PlateStrip) for gr in model.groups)
    for gr, a, b in zip(model.groups, k1, k2):
        if not gr.secant_softening:
            assert np.array_equal(a, b), gr.name


def test_secant_on_poor_contraction_passes_the_fine_strip_without_a_failed_step(monkeypatch):
    """Chapter 11's scene at h = 0.125 m, 10 targets, with the policy's ``secant_rule = "poor"``: the run
    completes without a failed step. Measured on the same commit with the rule "never" (the consistent
    tangent, as on main c58d17b): 6 failed steps, 56 steps, 98 factorisations; with "poor": 0, 11, 56."""
    monkeypatch.setattr(path, "POLICY", replace(path.POLICY, secant_rule="poor"))
    out = chapter11_foundation(0.125).build().solve(n_steps=10, settings=Settings(control="work"))
    res = out.solver_result
    assert out.status == "completed" and res.load_factor[-1] == 1.0
    assert res.cuts == 0, f"{res.cuts} failed steps"
