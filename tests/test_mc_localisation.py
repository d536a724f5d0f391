"""mc_ellipticity (loss of ellipticity of perfectly plastic Mohr–Coulomb flow) against independent
references: the determinant of the acoustic tensor built from the full fourth-order tangent (no rank-one
algebra), Coulomb's band for associated flow, and the Coulomb–Roscoe bracket of the band's normal."""

import math

import numpy as np
import pytest

from ssi.materials.mc_localisation import mc_ellipticity


def _brute_force(phi, psi, nu, theta):
    """det Q_ep(n) / det Q_e(n) from D_ep = D - (D:g)(f:D) / (f:D:g) as 3x3x3x3 tensors, n in the (e1, e3)
    plane at theta from e1 -- the definition itself, evaluated without the module's closed form."""
    lam = nu / ((1 + nu) * (1 - 2 * nu))
    mu = 1 / (2 * (1 + nu))
    eye = np.eye(3)
    d = lam * np.einsum("ij,kl->ijkl", eye, eye) + mu * (
        np.einsum("ik,jl->ijkl", eye, eye) + np.einsum("il,jk->ijkl", eye, eye)
    )
    k = (1 + math.sin(phi)) / (1 - math.sin(phi))
    m = (1 + math.sin(psi)) / (1 - math.sin(psi))
    f, g = np.diag([k, 0.0, -1.0]), np.diag([m, 0.0, -1.0])  # e1 largest, e2 out of plane, e3 smallest
    dg, fd = np.einsum("ijkl,kl->ij", d, g), np.einsum("ij,ijkl->kl", f, d)
    dep = d - np.einsum("ij,kl->ijkl", dg, fd) / np.einsum("ij,ij", f, dg)
    n = np.array([math.cos(theta), 0.0, math.sin(theta)])
    plane = np.ix_([0, 2], [0, 2])
    q_ep = np.einsum("j,ijkl,l->ik", n, dep, n)[plane]
    q_e = np.einsum("j,ijkl,l->ik", n, d, n)[plane]
    return np.linalg.det(q_ep) / np.linalg.det(q_e)


@pytest.mark.parametrize("phi_deg, psi_deg, nu", [(30, 0, 0.3), (20, 0, 0.3), (35, 5, 0.25), (30, 15, 0.45)])
def test_non_associated_flow_has_lost_ellipticity(phi_deg, psi_deg, nu):
    phi, psi = math.radians(phi_deg), math.radians(psi_deg)
    ratio, theta = mc_ellipticity(phi, psi, nu)
    # the same number from the tensor definition (1e-10: round-off of two 2x2 determinants of O(1) entries)
    assert ratio == pytest.approx(_brute_force(phi, psi, nu, theta), abs=1e-10)
    # a minimum: a finer brute-force scan over all normals finds nothing lower
    scan = min(_brute_force(phi, psi, nu, t) for t in np.linspace(0, math.pi, 2001))
    assert ratio <= scan + 1e-12
    assert ratio < -1e-3  # clearly negative: lost ellipticity
    # the band's normal between Coulomb's (45 - phi/2) and Roscoe's (45 - psi/2) angle from e1 (the band
    # itself at those angles from the most compressive axis): Vardoulakis 1980, Vermeer & de Borst 1984
    folded = min(theta, math.pi - theta)
    assert math.radians(45) - phi / 2 < folded < math.radians(45) - psi / 2


@pytest.mark.parametrize("phi_deg, nu", [(20, 0.3), (30, 0.2), (40, 0.45)])
def test_associated_flow_is_on_the_boundary_at_coulombs_band(phi_deg, nu):
    phi = math.radians(phi_deg)
    ratio, theta = mc_ellipticity(phi, phi, nu)
    assert abs(ratio) < 1e-10  # exactly zero in exact arithmetic: h_crit = 0 for associated flow
    folded = min(theta, math.pi - theta)
    assert folded == pytest.approx(math.radians(45) - phi / 2, abs=1e-4)  # Coulomb's plane (golden search)


def test_bad_angles_name_the_parameter():
    with pytest.raises(ValueError, match="psi"):
        mc_ellipticity(0.3, 0.4, 0.3)
    with pytest.raises(ValueError, match="nu"):
        mc_ellipticity(0.5, 0.0, 0.5)


def test_failure_report_names_the_ill_posed_soil():
    """ill_posed_soil reads the plastic points of a pushed footing: psi = 0 soil is named with its ratio,
    the same push on associated soil is not (its rate problem is on the boundary of ellipticity)."""
    from ssi.lab.bearing_capacity import chapter10_footing, push_footing
    from ssi.solver.diagnostics import ill_posed_soil

    texts = {}
    for psi in (0.0, 20.0):
        scene = chapter10_footing(psi_deg=psi, h_fine=0.5, settle=0.03)
        out = push_footing(scene, n_steps=3)
        states = out["result"].states[-1]
        assert scene.soil.point_codes(states[scene.model.groups.index(scene.soil)]).sum() > 0  # yielding
        texts[psi] = ill_posed_soil(scene.model, states)
    ratio, _ = mc_ellipticity(math.radians(20.0), 0.0, 0.3)
    assert f"min det Q_ep / det Q_e = {ratio:.3f}" in texts[0.0] and "phi = 20 deg, psi = 0 deg" in texts[0.0]
    assert "Davis mode" in texts[0.0]
    assert texts[20.0] == ""


def test_ill_posed_soil_reads_each_points_material():
    """A group with a material per integration point (SoilQ8Points, the site's dipping layers): the plastic
    points are counted under their own rows -- here one element whose upper points are psi < phi sand and
    whose lower points are associated clay, every point plastic."""
    from types import SimpleNamespace

    from ssi.core.model import Model
    from ssi.elements.soil_q8_points import SoilQ8Points
    from ssi.materials.soil_laws import SoilLayer, material_table
    from ssi.solver.diagnostics import ill_posed_soil

    model = Model()
    xy = np.array([[0, 0], [2, 0], [2, 1], [0, 1], [1, 0], [2, 0.5], [1, 1], [0, 0.5]], float)
    conn = np.array([model.add_nodes(xy, ndof=2)])
    kinds, params = material_table(
        [
            SoilLayer(1.0, E=2e7, nu=0.3, c=5e3, phi_deg=30.0, psi_deg=0.0).law(),
            SoilLayer(1.0, E=2e7, nu=0.3, c=5e3, phi_deg=20.0, psi_deg=20.0).law(),
        ]
    )
    point_mat = np.array([[1, 1, 0, 0]])  # rows per Gauss point
    group = SoilQ8Points(model.coords[conn], model.element_dofs(conn), point_mat, kinds, params)
    state = group.initial_state()
    group.history(state, "branch")[...] = 1.0  # every point returned to the main plane
    assert group.point_codes(state).sum() == 4
    text = ill_posed_soil(SimpleNamespace(groups=[group]), [state])
    assert text.startswith(f"2 plastic points of {group.name} material 0 (phi = 30 deg, psi = 0 deg")
    assert "material 1" not in text  # the associated points are not named
