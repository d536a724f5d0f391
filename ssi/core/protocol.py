"""The element-group protocol: what the model and the solver expect from every element type.

The bottom of the package's layering: materials, elements, the model and the solver all import it, and it
imports nothing of ``ssi``.

A scene is a set of *element groups* (soil Q8, plate strip, interface). A group holds all elements of one
type in flat, element-major, C-contiguous arrays and evaluates them in one numba kernel call.

Array layout (the one place it is written down)
------------------------------------------------
=================  ==========================  ==================================================
name               shape                        meaning
=================  ==========================  ==================================================
``edofs``          (n_el, n_edof) int64         global DOF numbers of each element, node by node,
                                                each node's DOFs in order (u, w) or (u, w, alpha)
``coords``         (n_el, n_node_el, 2) float   nodal (x, z) of each element, z upwards
``u_el``           (n_el, n_edof) float         total displacement gathered from the global vector
``du_el``          (n_el, n_edof) float         increment since the last converged (committed) state
``state``          (n_el, n_ip, n_var) float    integration-point history; the plate strip adds a
                                                layer axis: (n_el, n_ip, n_layer, n_var)
``f_el``           (n_el, n_edof) float         element internal force vectors
``k_el``           (n_el, n_edof, n_edof) float element stiffness matrices
=================  ==========================  ==================================================

Signs: x horizontal, z vertical upwards, w positive up, stresses positive in tension.

Incremental laws (soil, interface) update stresses from ``du_el`` and the committed state; total laws
(plate strip) compute strains from ``u_el`` and use the state only for history (max strains, cracks).
``evaluate`` never mutates ``state_old``: the solver alone commits ``state_new`` after convergence.
"""

from typing import Protocol

import numpy as np

# Tangent flags: the last argument of every ``evaluate`` and of every material point kernel. They say which
# matrix to return, not which law to use: law kinds (``soil_laws.ELASTIC``, ``layer_laws.CONCRETE``, ...) are
# another vocabulary, and the names differ so that one cannot be passed for the other by accident.
K0_MATRIX = 0  # return the initial elastic stiffness K0 (modified Newton-Raphson, BFGS, linear solves)
CONSISTENT = 1  # return the algorithmic (consistent) tangent (full Newton)
FORCES_ONLY = -1  # internal forces only; k_el may be None. Only groups whose attribute ``forces_only`` is
# True receive it (the others get K0_MATRIX and their k_el is ignored)
TANGENT_FLAGS = (K0_MATRIX, CONSISTENT, FORCES_ONLY)


class ElementGroup(Protocol):
    name: str
    edofs: np.ndarray

    def initial_state(self) -> np.ndarray:
        """Committed state before the first step (zeros, or geostatic stress for soil)."""

    def evaluate(
        self, u_el: np.ndarray, du_el: np.ndarray, state_old: np.ndarray, tangent: int
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Return ``(f_el, k_el, state_new)``; ``tangent`` is K0_MATRIX or CONSISTENT (or FORCES_ONLY)."""

    def elastic_stiffness(self) -> np.ndarray:
        """``k_el`` of the undamaged, elastic elements (K0)."""

    def body_force(self) -> np.ndarray | None:
        """Equivalent nodal forces of body loads (self-weight), shape like ``f_el``, or None."""

    def describe(self) -> dict:
        """Plain attributes (numbers, strings, lists) that document the group in result files."""
