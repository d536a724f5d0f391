"""Davis mode (``Settings(flow="davis")``): for the duration of a run, every Mohr-Coulomb soil material and
every Coulomb interface is made associated with the beta-reduced strength of Davis (1968),
c* = beta c, tan phi* = beta tan phi, psi* = phi*, beta = :func:`ssi.materials.soil_laws.davis_beta`.
Each increment is then a convex problem with a symmetric tangent; its limit bounds the capacity of the
non-associated material (the limit analysis uses the same reduction). Each group gives its Davis copy
(``ElementGroup.davis_params``); the rows are :func:`ssi.materials.soil_laws.davis_soil_row` and
:func:`ssi.materials.interface_law.davis_interface_row`.
"""

from contextlib import contextmanager

from ..materials.interface_law import davis_interface_row
from ..materials.soil_laws import davis_soil_row

__all__ = ["davis_interface_row", "davis_mode", "davis_soil_row"]


@contextmanager
def davis_mode(model, on: bool):
    """Within the block, the model's groups that have a Davis copy (``davis_params``: soil and interface)
    carry it as their parameters (when ``on``); their own parameter arrays are put back on exit, also after
    an error."""
    saved = []
    if on:
        for g in model.groups:
            rows = g.davis_params()
            if rows is None:
                continue
            saved.append((g, g.params))
            g.params = rows
    try:
        yield
    finally:
        for g, params in saved:
            g.params = params
