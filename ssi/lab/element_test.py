"""A laboratory test on one soil element: plane-strain biaxial compression with smooth platens.

One 8-node element (unit square, 1 m x 1 m) starts from a uniform effective stress ``sig0``; its bottom is
held vertically and its left side horizontally, its right side keeps its initial total stress (a dead load),
and its top is pushed down by ``delta``. The stress stays uniform, so the element is the material point and
the finite-element answer is exact: the element's law (drained or undrained "A" with the water penalty of
:meth:`ssi.scene.SoilLayer.k_water`) is tested as a whole, equilibrium included.
"""

import numpy as np

from ..core.mesh import structured_q8
from ..core.model import Model
from ..core.validate import check_array, check_int, check_real
from ..elements.soil_q8 import SoilQ8
from ..materials.soil_laws import material_table
from ..solver import Settings, run


def biaxial_compression(layer, sig0, delta=0.02, n_steps=40, settings=None) -> dict:
    """Biaxial compression of one element of ``layer`` (:class:`ssi.scene.SoilLayer`) from the effective
    stress ``sig0`` = [sxx, szz, txz, syy] [Pa] (tension positive, txz = 0) by a top displacement
    ``delta`` [m] in ``n_steps`` equal increments (``settings``: default full Newton).

    Returns a dict of per-step arrays (step 0 = the initial state): ``sig`` (n + 1, 4) effective stress
    [Pa], ``t`` = (sxx - szz) / 2 [Pa] (the in-plane deviator, > 0 in compression), ``s`` = -(sxx + szz) / 2
    [Pa] (in-plane mean effective stress, compression positive), ``excess_pore_pressure`` [Pa], ``eps_z`` the
    vertical strain [-], and ``result`` (:class:`ssi.solver.Result`)."""
    sig0 = check_array("sig0", sig0, ndim=1)
    if sig0.shape != (4,) or sig0[2] != 0.0:
        raise ValueError(f"sig0 must be [sxx, szz, 0, syy] (4 values, no shear), got {sig0.tolist()}")
    delta = check_real("delta", delta, lo=0.0, lo_open=True, hi=0.5, unit="m (of a 1 m element)")
    n_steps = check_int("n_steps", n_steps, lo=1)
    mesh = structured_q8([0.0, 1.0], [0.0, 1.0])
    model = Model()
    ids = model.add_nodes(mesh.xy, 2)
    kinds, params = material_table([layer.law()])
    soil = SoilQ8(
        mesh.xy[mesh.conn],
        model.element_dofs(ids[mesh.conn]),
        0,
        kinds,
        params,
        k_water=[layer.k_water()],
        initial_stress=np.broadcast_to(sig0, (1, 4, 4)).copy(),
    )
    model.add_group(soil)
    xy = mesh.xy
    right = np.flatnonzero(xy[:, 0] == 1.0)
    right = right[np.argsort(xy[right, 1])]
    model.fix(np.flatnonzero(xy[:, 1] == 0.0), "w")
    model.fix(np.flatnonzero(xy[:, 0] == 0.0), "u")
    model.prescribe(np.flatnonzero(xy[:, 1] == 1.0), "w", -delta)
    model.add_dead_load(right, "u", sig0[0] * np.array([1.0, 4.0, 1.0]) / 6.0)  # L/6, 4L/6, L/6 of sxx0
    res = run(model, np.linspace(0.0, 1.0, n_steps + 1)[1:], settings or Settings(method="full"))
    sig = np.array([soil.stress(st[0])[0, 0] for st in res.states])
    p_ex = np.array([soil.excess_pore_pressure(u[soil.edofs])[0, 0] for u in res.u])
    return {
        "sig": sig,
        "t": 0.5 * (sig[:, 0] - sig[:, 1]),
        "s": -0.5 * (sig[:, 0] + sig[:, 1]),
        "excess_pore_pressure": p_ex,
        "eps_z": -delta * np.asarray(res.load_factor),
        "result": res,
    }
