"""The mechanism certificate of a limit on the controlled path (ssi/solver/mechanism.py, issue 31 item 4).

Expected values come from closed forms -- the dissipation of a block sliding on a Tresca contact, c L per
unit slip; Prandtl's bearing capacity; the laws' own energy (a tanh spring stores all its work) -- never
from the code under test.
"""

from dataclasses import replace

import numpy as np
import pytest

from ssi.core.model import Model
from ssi.elements.interface import add_interface
from ssi.elements.soil_q8 import SoilQ8
from ssi.elements.spring import ELASTOPLASTIC, TANH
from ssi.elements.supports import spring_chain
from ssi.materials.interface_law import interface_params
from ssi.materials.soil_laws import ELASTIC, elastic_params, material_table
from ssi.solver import LIMIT_LOAD, Settings, run
from ssi.solver.mechanism import MECHANISM_TOL, increment_energy

L_BLOCK, H_BLOCK = 2.0, 1.0  # block width and height [m]
C_CONTACT = 10e3  # the contact's cohesion [Pa] (phi = 0: Tresca), so the block slides at H = c L = 20 kN/m
H_REF = 1e4  # reference horizontal load [N/m]: the block slides at lambda = c L / H_REF = 2
DEAD = 5e4  # dead vertical load on the block [N/m]


def _sliding_block(phi_deg=0.0, psi_deg=0.0):
    """One elastic Q8 block on a contact (default Tresca: phi = psi = 0, c = 10 kPa: associated) over fixed
    ground nodes, the reference load horizontal on the block's base nodes (consistent shares 1/6, 4/6, 1/6,
    so the contact shear is uniform and nothing overturns) and a dead vertical load pressing it down."""
    model = Model()
    corners = [(0.0, 0.0), (L_BLOCK, 0.0), (L_BLOCK, H_BLOCK), (0.0, H_BLOCK)]
    mids = [(L_BLOCK / 2, 0.0), (L_BLOCK, H_BLOCK / 2), (L_BLOCK / 2, H_BLOCK), (0.0, H_BLOCK / 2)]
    block = model.add_nodes(np.array(corners + mids), 2)
    ground = model.add_nodes(np.array([(0.0, 0.0), (L_BLOCK / 2, 0.0), (L_BLOCK, 0.0)]), 2)
    kinds, params = material_table([(ELASTIC, elastic_params(1e8, 0.3))])
    model.add_group(SoilQ8(model.coords[block][None], model.element_dofs(block[None]), 0, kinds, params))
    base = [block[0], block[4], block[1]]  # left to right: the block lies on the left of the walk (above)
    add_interface(model, [base], [ground], interface_params(1e9, 1e9, phi_deg, C_CONTACT, psi_deg))
    model.fix(ground, "u")
    model.fix(ground, "w")
    for node, share in zip(base, (1 / 6, 4 / 6, 1 / 6)):
        model.add_load(node, "u", share * H_REF)
    for node, share in zip([block[3], block[6], block[2]], (1 / 6, 4 / 6, 1 / 6)):
        model.add_dead_load(node, "w", -share * DEAD)
    return model, block


def test_sliding_block_dissipates_c_times_slip_exactly():
    """On the sliding plateau every contact point slips at tau = c and the block moves rigidly: the last
    increment dissipates c L du exactly (du the block's horizontal slip), stores nothing, and its kinematic
    multiplier is the limit c L / H_REF = 2. An increment before sliding (the first, all points stuck)
    dissipates nothing. Tolerance 1e-8: the equilibrium tolerance force_tol = 1e-10 and round-off."""
    model, block = _sliding_block()
    res = run(model, [5.0], Settings(control="work", force_tol=1e-10, symmetric_tangent=True))
    assert res.status == LIMIT_LOAD
    assert res.limit_load_factor == pytest.approx(C_CONTACT * L_BLOCK / H_REF, rel=1e-8)
    u_dof = model.dof(block, "u")
    k = res.n_steps
    slip = res.u[k][u_dof] - res.u[k - 1][u_dof]
    assert np.ptp(slip) < 1e-9 * abs(slip).max()  # a rigid slide
    energy = increment_energy(model, res.u[k - 1], res.u[k], res.states[k - 1], res.states[k], res.f_dead)
    exact = C_CONTACT * L_BLOCK * slip[0]
    assert energy.dissipated == pytest.approx(exact, rel=1e-8)
    assert abs(energy.stored) < 1e-8 * exact and energy.unsplit == 0.0
    assert res.limit_mechanism == pytest.approx(1.0, abs=1e-8)
    assert res.limit_stored_share == pytest.approx(0.0, abs=1e-8)
    assert res.limit_suspect == ""
    first = increment_energy(model, res.u[0], res.u[1], res.states[0], res.states[1], res.f_dead)
    assert abs(first.dissipated) < 1e-10 * first.work  # all stuck: elastic


def test_perfectly_plastic_spring_is_a_mechanism_and_a_tanh_asymptote_is_not():
    """Two plateaus of the controlled path with the same limit lambda = 2 (F = 1 kN, reference 0.5 kN):
    an elastic-perfectly plastic spring yields at F_y and its plateau dissipates everything (lambda_k =
    lambda_peak to round-off), while F_u tanh(k0 d / F_u) is an elastic (history-free) law whose asymptote
    stores all the work: lambda_k = 0, the plateau is no mechanism and the limit is flagged."""
    out = {}
    for kind in (ELASTOPLASTIC, TANH):
        model, _, nodes = spring_chain([kind], [1e6, 1e3, 0.0])
        model.add_load(nodes[-1], "u", 500.0)
        out[kind] = run(model, [5.0], Settings(control="work", force_tol=1e-10))
        assert out[kind].status == LIMIT_LOAD
    plastic, tanh = out[ELASTOPLASTIC], out[TANH]
    assert plastic.limit_mechanism == pytest.approx(1.0, abs=1e-9) and plastic.limit_suspect == ""
    assert tanh.limit_mechanism == pytest.approx(0.0, abs=1e-9)
    assert tanh.limit_stored_share == pytest.approx(1.0, abs=1e-9)
    assert "no collapse mechanism" in tanh.limit_suspect


def test_chapter10_associated_footing_certificate_within_tolerance_of_its_peak():
    """Chapter 10's rough associated footing (phi = psi = 20 deg, c = 10 kPa) on h = 0.0625 m: the path ends
    on its plateau within 3 % of Prandtl (issue 31, footing_assoc_peak; Prandtl is the closed form, not this
    code), and the last increment's kinematic multiplier lies within MECHANISM_TOL of that peak (measured:
    0.9946). The user's psi = 0 twin gets no certificate, only the stored share (issue 31, item 5)."""
    from ssi.lab.bearing_capacity import chapter10_footing, footing_pressure, prandtl

    settings = Settings(control="work", backend="superlu", symmetric_tangent=True, first_step=0.05,
                        max_step=0.05)  # fmt: skip
    scene = chapter10_footing(phi_deg=20.0, psi_deg=20.0, h_fine=0.0625, settle=0.06)
    res = run(scene.model, [1.0], settings)
    assert res.status == LIMIT_LOAD
    _, q = footing_pressure(scene, res)
    assert abs(q.max() / prandtl(10e3, 20.0)[0] - 1.0) < 0.03
    assert 1.0 - MECHANISM_TOL <= res.limit_mechanism <= 1.0 + MECHANISM_TOL
    assert "no collapse mechanism" not in res.limit_suspect


def test_non_associated_flow_reports_the_stored_share_and_no_certificate():
    """The block on a non-associated Coulomb contact (phi = 30 deg, psi = 0) slides at (c L + N tan phi) /
    H_REF: tau . d_slip is the energy it dissipates, but not the associated dissipation of anything, so no
    multiplier is certified (issue 31, item 5) and the check flags nothing; the stored share of the rigid
    slide is still reported (0 to the equilibrium tolerance)."""
    model, _ = _sliding_block(phi_deg=30.0, psi_deg=0.0)
    res = run(model, [10.0], Settings(control="work", force_tol=1e-10))
    assert res.status == LIMIT_LOAD
    exact = (C_CONTACT * L_BLOCK + DEAD * np.tan(np.radians(30.0))) / H_REF
    assert res.limit_load_factor == pytest.approx(exact, rel=1e-8)
    assert res.limit_mechanism is None and res.limit_suspect == ""
    assert res.limit_stored_share == pytest.approx(0.0, abs=1e-8)


def test_a_stall_read_as_a_limit_is_flagged(monkeypatch):
    """A plateau rule loosened on purpose (rise < 5 % over 3 steps and a tenth of the control) stops
    chapter 10's associated footing (h = 0.25 m) on its rising path, 0.7 % below its load at the end of the
    6 cm push: its last increment stores 6 % of the load's work elastically (measured), beyond
    MECHANISM_TOL, and the limit is reported suspect with that reason."""
    import ssi.solver.path as path
    from ssi.lab.bearing_capacity import chapter10_footing

    loose = replace(path.POLICY, plateau_rise=0.05, plateau_steps=3, plateau_control=0.1)
    monkeypatch.setattr(path, "POLICY", loose)
    settings = Settings(control="work", backend="superlu", symmetric_tangent=True, first_step=0.05,
                        max_step=0.05)  # fmt: skip
    scene = chapter10_footing(phi_deg=20.0, psi_deg=20.0, h_fine=0.25, settle=0.06)
    res = run(scene.model, [1.0], settings)
    assert res.status == LIMIT_LOAD
    assert res.limit_mechanism < 1.0 - MECHANISM_TOL
    assert "no collapse mechanism" in res.limit_suspect


def test_certificate_is_written_to_the_result_file_and_read_back(tmp_path):
    """The certificate (lambda_k / lambda_peak, stored share) of a scene's limit is written with the solver's
    attrs and read back (random zoo scene 8, seed 1, in Davis mode: a limit at lambda = 0.268 in 0.3 s); a
    limit without a certificate writes nan, read back as None."""
    from ssi.io.results import read_result, write_result
    from ssi.lab.zoo import random_scenes

    _, scene = random_scenes(9, seed=1)[8]
    out = scene.build().solve(settings=Settings(control="work", flow="davis"))
    res = out.solver_result
    assert res.status == LIMIT_LOAD and res.limit_mechanism is not None
    write_result(tmp_path / "r.h5", out)
    back = read_result(tmp_path / "r.h5").solver_result
    assert back.limit_mechanism == res.limit_mechanism
    assert back.limit_stored_share == res.limit_stored_share
    res.limit_mechanism = None
    write_result(tmp_path / "none.h5", out)
    assert read_result(tmp_path / "none.h5").solver_result.limit_mechanism is None


def test_a_group_whose_energy_is_not_split_gets_no_certificate():
    """tests/test_solver_path.py's softening spring (a subclass of Spring with a total law of its own) passes
    a peak: its work cannot be split into stored and dissipated parts here, so the limit gets no
    certificate (None), says why in its evidence, and is not flagged by the check."""
    from test_solver_path import _softening_model  # pytest puts tests/ on the path (no package)

    model, _ = _softening_model()
    res = run(model, [2.0], Settings(control="work", force_tol=1e-10, energy_tol=1e-14))
    assert res.status == LIMIT_LOAD
    assert res.limit_mechanism is None and res.limit_stored_share is None
    assert "no mechanism certificate" in res.limit_evidence and "not split" in res.limit_evidence
    assert res.limit_suspect == ""


def _one_element_increment(k_water):
    """The energy of a second increment of a uniform compression with shear (grad u scaled 1 -> 1.7) of one
    elastic Q8 element (E = 10 MPa, nu = 0.3) with pore water K_w/n = ``k_water`` [Pa] (0: drained)."""
    model = Model()
    xy = np.array([(0, 0), (1, 0), (1, 1), (0, 1), (0.5, 0), (1, 0.5), (0.5, 1), (0, 0.5)], float)
    nodes = model.add_nodes(xy, 2)
    kinds, params = material_table([(ELASTIC, elastic_params(1e7, 0.3))])
    group = SoilQ8(xy[None], model.element_dofs(nodes[None]), 0, kinds, params, k_water=k_water)
    model.add_group(group)

    def states_after(u_new, u_old, states):
        u_el, du_el = u_new[group.edofs], (u_new - u_old)[group.edofs]
        return [group.evaluate(u_el, du_el, states[0], 0)[2]]

    grad = np.array([[-1e-4, 3e-5], [0.0, -2e-4]])  # [[du/dx, du/dz], [dw/dx, dw/dz]]
    u1 = np.zeros(model.n_dof)
    u1[model.dof(nodes, "u")], u1[model.dof(nodes, "w")] = (xy @ grad.T).T
    u2 = 1.7 * u1
    states1 = states_after(u1, np.zeros(model.n_dof), [group.initial_state()])
    states2 = states_after(u2, u1, states1)
    return increment_energy(model, u1, u2, states1, states2, np.zeros(model.n_dof))


def test_undrained_elastic_soil_stores_all_of_its_work():
    """Elastic soil, drained and undrained (K_w/n = 2 GPa): nothing dissipates, the skeleton's
    sigma' : C^-1 d_sigma' and the pore water's -p d_eps_v (both elastic) store all of the work, to
    round-off. The pore water takes most of the undrained work here, so leaving it out would read as
    dissipation."""
    drained, undrained = _one_element_increment(0.0), _one_element_increment(2e9)
    assert undrained.work > 10.0 * drained.work > 0.0
    for energy in (drained, undrained):
        assert abs(energy.dissipated) < 1e-12 * energy.work
        assert energy.stored == pytest.approx(energy.work, rel=1e-12)
