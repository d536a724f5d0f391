"""Davis mode (``Settings(flow="davis")``): for the duration of a run, every Mohr-Coulomb soil material and
every Coulomb interface is made associated with the beta-reduced strength of Davis (1968),
c* = beta c, tan phi* = beta tan phi, psi* = phi*, beta = :func:`ssi.materials.soil_laws.davis_beta`.
Each increment is then a convex problem with a symmetric tangent; its limit bounds the capacity of the
non-associated material (the limit analysis uses the same reduction).
"""

import math
from contextlib import contextmanager

import numpy as np

from ..elements.interface import Interface6
from ..elements.soil_q8 import SoilQ8
from ..materials.soil_laws import MOHR_COULOMB, MOHR_COULOMB_EXPLICIT, davis_beta


def davis_soil_row(row: np.ndarray) -> np.ndarray:
    """A Mohr-Coulomb parameter row [E, nu, c, phi, psi, ...] (angles in rad) made associated with Davis'
    reduced c*, phi* (psi* = phi*)."""
    out = row.copy()
    beta = davis_beta(math.degrees(row[3]), math.degrees(row[4]))
    out[2] = beta * row[2]
    out[3] = out[4] = math.atan(beta * math.tan(row[3]))
    return out


def davis_interface_row(row: np.ndarray) -> np.ndarray:
    """An interface parameter row [kt, kn, c, tan_phi, tan_psi, sig_t] made associated with Davis' reduced
    c*, tan phi* (tan psi* = tan phi*; the tension cut-off, at most the apex c / tan phi, is unchanged)."""
    out = row.copy()
    beta = davis_beta(math.degrees(math.atan(row[3])), math.degrees(math.atan(row[4])))
    out[2] = beta * row[2]
    out[3] = out[4] = beta * row[3]
    return out


@contextmanager
def davis_mode(model, on: bool):
    """Within the block, the model's soil and interface groups carry Davis' associated parameters (when
    ``on``); their own parameters are put back on exit, also after an error."""
    saved = []
    if on:
        for g in model.groups:
            if isinstance(g, SoilQ8):
                mc = np.isin(g.kinds, (MOHR_COULOMB, MOHR_COULOMB_EXPLICIT))
                rows = [davis_soil_row(p) if m else p.copy() for p, m in zip(g.params, mc)]
            elif isinstance(g, Interface6):
                rows = [davis_interface_row(p) for p in g.params]
            else:
                continue
            saved.append((g, g.params))
            g.params = np.ascontiguousarray(np.array(rows, np.float64))
    try:
        yield
    finally:
        for g, params in saved:
            g.params = params
