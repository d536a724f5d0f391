"""The element-group protocol: what the model and the solver expect from every element type.

Near the bottom of the package's layering: materials, elements, the model and the solver all import it, and it
imports only :mod:`ssi.core.assembly` (the default K0 assembly of a group).

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

Capabilities (declared, never probed)
-------------------------------------
Every group inherits :class:`ElementGroup`, which declares what the model, the solver, the scene and the
result files may ask of a group, each with a default that means "this group has no such thing". A group
overrides what it has; nobody asks ``hasattr(group, ...)``:

=============================  ======================================================================
``forces_only``                accepts the FORCES_ONLY flag (else it gets K0_MATRIX and k_el is ignored)
``secant_softening``           accepts the SECANT_SOFTENING flag (else it gets CONSISTENT)
``viscous``, ``viscosity``     takes a Duvaut--Lions viscosity tau = dt / eta per increment [-], which
                               a group with ``viscous`` is built with (the solver sets none)
``history_fields``             name -> index on the last axis of ``state`` (read with :meth:`history`)
``point_codes(state)``         a state code per integration point (e.g. stick/slip/open), named by
                               ``point_code_names``, or None
``integration_points()``       (n_el, n_ip, 2) physical (x, z) of the integration points [m], or None
``ip_weights()``               (n_el, n_ip) weight times Jacobian of each point [m], or None
``assemble_elastic_stiffness``  add K0 into CSR values (default: scatter :meth:`elastic_stiffness`)
=============================  ======================================================================
"""

from collections.abc import Mapping

import numpy as np

from .assembly import scatter_matrix

# Tangent flags: the last argument of every ``evaluate`` and of every material point kernel. They say which
# matrix to return, not which law to use: law kinds (``soil_laws.ELASTIC``, ``layer_laws.CONCRETE``, ...) are
# another vocabulary, and the names differ so that one cannot be passed for the other by accident.
K0_MATRIX = 0  # return the initial elastic stiffness K0 (modified Newton-Raphson, BFGS, linear solves)
CONSISTENT = 1  # return the algorithmic (consistent) tangent (full Newton)
FORCES_ONLY = -1  # internal forces only; k_el may be None. Only groups whose attribute ``forces_only`` is
# True receive it (the others get K0_MATRIX and their k_el is ignored)
SECANT_SOFTENING = 2  # the consistent tangent, except at points loading on a softening envelope (the
# concrete's cracked tension branch), which return their secant modulus sig / e: a positive modulus where the
# exact one is negative, so that a corrector iterating on it does not cycle between softening and secant
# unloading (issue 31). Only groups whose attribute ``secant_softening`` is True receive it (the others get
# CONSISTENT); the internal forces are those of every other flag
TANGENT_FLAGS = (K0_MATRIX, CONSISTENT, FORCES_ONLY, SECANT_SOFTENING)


class ElementGroup:
    """Base class of every element group: the required methods and the optional capabilities, declared.

    A subclass sets ``name`` and ``edofs`` and implements :meth:`initial_state`, :meth:`evaluate` and
    :meth:`elastic_stiffness`; it overrides a capability (class attribute or method below) only where it
    has it. The defaults say "none": no viscosity, no named state slots, no point codes, no integration
    points, K0 assembled by scattering the element matrices.
    """

    name: str = "group"
    edofs: np.ndarray

    #: accepts ``FORCES_ONLY`` (internal forces without matrices)
    forces_only: bool = False
    #: accepts ``SECANT_SOFTENING`` (the secant modulus at softening points; else it gets ``CONSISTENT``)
    secant_softening: bool = False
    #: takes a Duvaut--Lions viscosity (set when the group is built; the solver sets none)
    viscous: bool = False
    #: the viscosity in force, tau = dt / eta per increment [-]; 0: rate independent
    viscosity: float = 0.0
    #: name -> index on the last axis of ``state`` (several names may share an index where the meaning of a
    #: slot depends on the point's law, as in the plate's layers)
    history_fields: Mapping[str, int] = {}
    #: names of the codes :meth:`point_codes` returns (code i is ``point_code_names[i]``)
    point_code_names: tuple[str, ...] = ()

    # ---- required --------------------------------------------------------------------------------------
    def initial_state(self) -> np.ndarray:
        """Committed state before the first step (zeros, or geostatic stress for soil)."""
        raise NotImplementedError(f"{type(self).__name__} must implement initial_state()")

    def evaluate(
        self, u_el: np.ndarray, du_el: np.ndarray, state_old: np.ndarray, tangent: int
    ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray]:
        """Return ``(f_el, k_el, state_new)``; ``tangent`` is K0_MATRIX or CONSISTENT (or FORCES_ONLY)."""
        raise NotImplementedError(f"{type(self).__name__} must implement evaluate()")

    def elastic_stiffness(self) -> np.ndarray:
        """``k_el`` of the undamaged, elastic elements (K0)."""
        raise NotImplementedError(f"{type(self).__name__} must implement elastic_stiffness()")

    # ---- optional, with defaults -----------------------------------------------------------------------
    def body_force(self) -> np.ndarray | None:
        """Equivalent nodal forces of body loads (self-weight) [N/m], shape like ``f_el``, or None."""
        return None

    def describe(self) -> dict:
        """Plain attributes (numbers, strings, lists) that document the group in result files."""
        return {"name": self.name}

    def history(self, state: np.ndarray, field: str) -> np.ndarray:
        """The slot ``field`` of ``state`` (a view, shape ``state.shape[:-1]``), by its name in
        ``history_fields``."""
        try:
            index = self.history_fields[field]
        except KeyError:
            raise KeyError(
                f"{self.name}: no state field {field!r}; its fields are {sorted(self.history_fields)}"
            ) from None
        return state[..., index]

    def point_codes(self, state: np.ndarray) -> np.ndarray | None:
        """An integer state code per integration point (names in ``point_code_names``), or None."""
        return None

    def integration_points(self) -> np.ndarray | None:
        """(n_el, n_ip, 2) physical (x, z) of the integration points [m], or None."""
        return None

    def ip_weights(self) -> np.ndarray | None:
        """(n_el, n_ip) quadrature weight times Jacobian of each integration point [m], or None."""
        return None

    # ---- what the solver asks of a group's laws (the defaults: a group the solver knows nothing of) -------
    def associated_flow(self, tol: float = 0.0) -> bool:
        """True unless a law of the group flows off the normal of its yield surface by more than ``tol``
        (|psi - phi| [rad] of a soil row, |tan psi - tan phi| of a contact row); True for a group without a
        flow rule."""
        return True

    def symmetric_tangent(self) -> bool:
        """True if every law of the group has a symmetric consistent tangent; False where not known (a group
        the solver knows nothing of is not assumed symmetric)."""
        return False

    def softens(self) -> bool:
        """True if a law of the group can soften (a plate strip's cracking RC layers): the corrector's rules
        for a cracking strip then apply."""
        return False

    def davis_params(self) -> np.ndarray | None:
        """A new parameter array with Davis' associated, beta-reduced strength (c* = beta c,
        tan phi* = beta tan phi, psi* = phi*) for the group's Mohr-Coulomb and Coulomb rows, the others
        copied; ``params`` itself is not touched. None: the group has no such rows."""
        return None

    def stored_energy(
        self, u_el: np.ndarray, du_el: np.ndarray, state_old: np.ndarray, state_new: np.ndarray, work: float
    ) -> float | None:
        """The elastic energy [J/m] the group stores over the converged increment ``du_el`` from ``state_old``
        to ``state_new`` (``u_el`` at its end; ``work`` the group's work on it [J/m]); None where the group
        cannot split its work into stored and dissipated parts."""
        return None

    def nonassociated_yielding(
        self, state: np.ndarray, tol: float
    ) -> list[tuple[int, int, float, float, float]]:
        """(material row, plastic points in ``state``, nu, phi [rad], psi [rad]) of each Mohr-Coulomb row with
        phi - psi > ``tol`` that has plastic points (the rows whose rate problem has lost ellipticity); []
        for a group without such rows."""
        return []

    def assemble_elastic_stiffness(self, smap: np.ndarray, data: np.ndarray) -> np.ndarray:
        """Add K0 into the CSR values ``data`` through this group's scatter map ``smap`` and return ``data``.
        The default scatters :meth:`elastic_stiffness`; a group overrides it to assemble without keeping
        the element matrices."""
        scatter_matrix(smap, self.elastic_stiffness(), data)
        return data
