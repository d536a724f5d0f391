"""The result of an analysis: its converged steps, linear (:meth:`ssi.core.model.Model.solve_linear`, rows
[initial, solved]) or incremental (:func:`ssi.solver.run`, one row per converged step), with the solver's
diagnostics. :class:`ssi.scene.SceneResult` is a view of one; ``ssi.io.results`` writes and reads it.

Below the model and the solver: it imports neither (``model`` is only read through ``Model.dof``).
"""

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

if TYPE_CHECKING:  # for annotations only: the model imports this module
    from .model import Model

COMPLETED = "completed"
LIMIT_LOAD = "limit load reached"
STOPPED = "stopped"  # the status of the partial result a NonConvergence carries


@dataclass
class Result:
    """Converged steps of an analysis. Row 0 is the initial state (lambda = 0, or where ``start`` ended).

    ``status`` is ``"completed"`` (every target reached) or ``"limit load reached"``: the path stopped rising
    at ``limit_load_factor`` (the last converged step); its steps up to there are all converged. The partial
    result that a :class:`~ssi.solver.NonConvergence` carries says ``"stopped"``.
    ``stiffness`` holds the current stiffness parameter of each step (1 for the first, -> 0 at a limit).
    ``states`` holds every step's committed states, or only the last (``Settings.keep_states=False``).
    ``f_ref``, ``f_dead``: the loads it was solved with (F_ext = lambda f_ref + f_dead), which
    :meth:`reactions` subtracts; None where one set of loads does not describe the rows (a phased scene's
    joined result, whose phases each keep their own).
    """

    model: "Model"
    load_factor: list = field(default_factory=list)
    u: list = field(default_factory=list)
    f_int: list = field(default_factory=list)
    states: list = field(default_factory=list)
    iterations: list = field(default_factory=list)
    residuals: list = field(default_factory=list)  # per step: relative force norm of every iteration
    energies: list = field(default_factory=list)  # per step: relative energy norm of every iteration
    stiffness: list = field(default_factory=list)  # per step: current stiffness parameter (step 0: nan)
    step_viscosity: list = field(default_factory=list)  # per step: the Duvaut-Lions tau it was solved with
    # (0: a state of the rate-independent law; > 0: a viscous state, which carries overstress)
    cuts: int = 0
    relaxed_steps: int = 0  # controlled path: steps found by damped dynamics where the corrector stalled
    relaxed_iterations: int = 0  # ... and the iterations of every relaxation, converged or not
    relaxed_note: str = ""  # where a relaxed state has yielding non-associated soil: why it is one of several
    wall_time: float = 0.0
    factorizations: int = 0
    status: str = COMPLETED
    limit_load_factor: float | None = None
    limit_evidence: str = ""  # controlled path: why the path is taken to have peaked (peak or plateau)
    limit_uncertainty: float | None = None  # controlled path (Settings(control="work")): relative change
    # of the peak load when the last steps before it are redone at half size (its numerical uncertainty)
    limit_suspect: str = ""  # controlled path: why the limit is not to be read as a capacity ("" if no check
    # failed: beyond small strain, below/above a limit-analysis bracket, uncertainty not measured)
    limit_mechanism: float | None = None  # controlled path: the mechanism certificate, lambda_k / lambda_peak
    # of the limit's increment (the last on a plateau, the one reaching a passed peak) under associated
    # dissipation (ssi.solver.mechanism; -> 1 at a collapse); None where it is no certificate
    # (non-associated flow, an RC strip's unsplit work, not measured)
    limit_stored_share: float | None = None  # controlled path: the share of the load's work on the limit's
    # increment that the laws stored elastically (0 for a mechanism; also reported for non-associated flow,
    # where it certifies nothing); None where not split (an RC strip)
    u_origin: np.ndarray | None = None  # displacement and internal force of the state the structural
    f_int_origin: np.ndarray | None = None  # loads are measured from (the geostatic state)
    f_ref: np.ndarray | None = None  # (n_dof,) reference load [N/m], scaled by the load factor
    f_dead: np.ndarray | None = None  # (n_dof,) dead load [N/m], constant

    # the per-step lists (one entry per row); a phased scene's join copies these
    ROWS = (
        "load_factor",
        "u",
        "f_int",
        "states",
        "iterations",
        "residuals",
        "energies",
        "stiffness",
        "step_viscosity",
    )

    @classmethod
    def of_linear_solve(
        cls,
        model: "Model",
        u: list,
        f_int: list,
        states: list,
        f_ref: np.ndarray | None,
        f_dead: np.ndarray | None,
        wall_time: float = 0.0,
    ) -> "Result":
        """The record of one direct linear solve: rows [initial, solved] at load factors 0 and 1 (``u``,
        ``f_int``, ``states`` the two rows), one factorisation, iterations [0, 1], no residual history."""
        return cls(
            model=model,
            load_factor=[0.0, 1.0],
            u=list(u),
            f_int=list(f_int),
            states=list(states),
            iterations=[0, 1],
            residuals=[[], []],
            energies=[[], []],
            stiffness=[np.nan, 1.0],
            step_viscosity=[0.0, 0.0],
            wall_time=wall_time,
            factorizations=1,
            u_origin=u[0],
            f_int_origin=f_int[0],
            f_ref=f_ref,
            f_dead=f_dead,
        )

    @property
    def n_steps(self) -> int:
        return len(self.load_factor) - 1

    @property
    def collapsed(self) -> bool:
        return self.status == LIMIT_LOAD

    def rate_independent_steps(self) -> np.ndarray:
        """Indices of the steps that are equilibrium states of the rate-independent law: all of them, except
        the steps solved with a Duvaut-Lions viscosity in force (``step_viscosity > 0``: groups built with
        ``viscosity > 0``; the solver sets none). Read extreme values of a path (the largest load reached)
        over these only: a viscous state's overstress carries load the material cannot (measured: chapter
        10's psi = 0 push, 1.62 x Prandtl on a viscous stretch against 0.993 relaxed)."""
        return np.flatnonzero(np.asarray(self.step_viscosity) == 0.0)

    def displacement(self, ids: ArrayLike, comp: str | int) -> np.ndarray:
        """(n_steps + 1, n_ids) history of a displacement component [m] (rad for "alpha")."""
        return np.array(self.u)[:, self.model.dof(ids, comp)]

    def reaction(self, ids: ArrayLike, comp: str | int) -> np.ndarray:
        """(n_steps + 1,) summed internal force (= support reaction where no load acts on those DOFs) over
        ``ids`` in ``comp`` [N/m] (N m/m for "alpha"). With loads on them, see :meth:`support_reaction`."""
        d = self.model.dof(ids, comp)
        return np.array(self.f_int)[:, d].sum(axis=1)

    def reactions(self, k: int = -1) -> np.ndarray:
        """(n_dof,) support reactions [N/m] at step ``k``: the internal force minus the applied load,
        F_int - (lambda f_ref + f_dead); zero on the free DOFs up to the equilibrium residual."""
        self._check_loads("reactions")
        return self.f_int[k] - (self.load_factor[k] * self.f_ref + self.f_dead)

    def support_reaction(self, ids: ArrayLike, comp: str | int) -> np.ndarray:
        """(n_steps + 1,) summed support reaction over ``ids`` in ``comp`` [N/m] (N m/m for "alpha"): the
        internal force minus the applied load there (:meth:`reactions`, summed; e.g. a rigid footing's base
        node that a ground surcharge also loads)."""
        self._check_loads("support_reaction")
        d = self.model.dof(ids, comp)
        applied = np.asarray(self.load_factor) * self.f_ref[d].sum() + self.f_dead[d].sum()
        return self.reaction(ids, comp) - applied

    def _check_loads(self, name: str) -> None:
        if self.f_ref is None or self.f_dead is None:
            raise ValueError(
                f"{name}: this result does not record the loads it was solved with (f_ref, f_dead); of a "
                "phased scene read each phase's result (out.phases[i]['result'])"
            )

    @property
    def final_state(self) -> list[np.ndarray]:
        return self.states[-1]

    @property
    def message(self) -> str:
        if self.status == STOPPED:
            return f"stopped: no convergence beyond lambda = {self.load_factor[-1]:.6g} (see NonConvergence)"
        if self.collapsed:  # only the controlled path finds a limit (ssi/solver/path.py)
            unc = "not measured" if self.limit_uncertainty is None else f"{self.limit_uncertainty:.2e}"
            text = f"limit load reached at lambda = {self.limit_load_factor:.6g} ({self.limit_evidence}; "
            text += f"relative uncertainty {unc}"
            if self.limit_mechanism is not None:
                text += f"; mechanism certificate lambda_k / lambda_peak = {self.limit_mechanism:.4f}"
            text += ")"
            return text + (f"; suspect: {self.limit_suspect}" if self.limit_suspect else "") + self._relaxed()
        return f"completed: lambda = {self.load_factor[-1]:.6g} in {self.n_steps} steps" + self._relaxed()

    def _relaxed(self) -> str:
        """What the message adds where the controlled path took relaxed steps ('' where it took none)."""
        if not self.relaxed_steps:
            return ""
        text = f"; {self.relaxed_steps} relaxed steps ({self.relaxed_iterations} iterations)"
        if self.relaxed_note:
            text += f"; the state is one of several: {self.relaxed_note}"
        return text
