"""The solver's options (``Settings``) and the error a failed increment raises (``NonConvergence``)."""

from dataclasses import dataclass

from ..core.linsolve import BACKENDS
from ..core.solution import Result
from ..core.validate import check_bool, check_choice, check_int, check_real

METHODS = ("bfgs", "modified", "full")


STEPPINGS = ("auto", "fixed")


REFERENCES = ("structural", "total")


CONTROLS = ("load", "work")  # see Settings.control and ssi/solver/path.py


FLOWS = ("user", "davis")  # see Settings.flow


# load control, per method: default iteration cap of an increment and the iteration count automatic stepping
# aims at
_MAX_ITER = {"bfgs": 100, "modified": 300, "full": 30}


_DESIRED_ITER = {"bfgs": 20, "modified": 60, "full": 8}


# control="work" (path.py): iteration cap and target of its one corrector (lagged consistent tangent with
# L-BFGS), those of the L-BFGS method: the zoo's contact scenes take 70-90 K0-based iterations per step.
# The target 20 measured against 6-30 (issue 31, speed10; bench footing footing_mc_psi0_h0125_s: psi = 0,
# h = 0.125 m, 12 targets; one process, CPU; copies with the settlement x (1 + eps), eps = 0, +-1e-13,
# +-1e-12): 20 completes 4 of 5 copies in 5.3-6.3 s; 12 2 of 5 (7.8-8.0 s: ~13 iterations a step, but 2.4x
# the steps), 16 0 of 5, 24 1 of 5; 6, 8, 10, 25, 30 (eps = 0) ended before the last target with q_u 80-93 %
# of the completed runs'. With min_step 1e-6, where every copy completes, 12 took 1.2-1.5x the CPU of 20:
# fewer iterations per step buy no time where the failed steps are soil points flipping at the plastic
# front (see path.py's docstring)
_MAX_ITER_PATH, _DESIRED_ITER_PATH = 100, 20


@dataclass
class Settings:
    """Solver options. The defaults follow the controlled path (``control="work"``), which solves ordinary
    nonlinear scenes and finds a limit load where the path peaks; :meth:`paper` gives the paper's algorithm.

    ``control``: ``"work"`` -- controlled path following (:mod:`ssi.solver.path`): each step prescribes the
    work of the reference load f_ref . (u - u_0) (with prescribed displacements and no force load, the load
    factor itself, i.e. displacement control), so the path passes limit points; one corrector (a lagged
    consistent tangent with L-BFGS updates and a line search), a continuous step-size rule, a limit only
    where the path peaks or stays on a plateau, and a failure to converge is :class:`NonConvergence`, never
    a limit. Its targets must rise. ``"load"`` -- load control: the load factor is prescribed increment by
    increment and solved with ``method`` in ``stepping``; an increment that cannot converge after its step
    cuts is :class:`NonConvergence` (with the path's current stiffness in its report), never a limit load:
    load control cannot pass a peak, so where it stops says nothing about the capacity. Use it for the
    paper's algorithm, for unloading (falling targets) and to compare methods.

    The rule when ``control`` is left at None: naming a load-control algorithm -- a ``method``, or
    ``stepping="fixed"`` -- asks for load control (``Settings(method="modified")`` is the modified
    Newton-Raphson method on load steps, as written); otherwise the controlled path. ``method`` and
    ``stepping="fixed"`` with ``control="work"`` are an error: the controlled path has one corrector and its
    own step-size rule.

    ``method`` (load control; None: ``"bfgs"``): ``"bfgs"`` -- quasi-Newton (L-BFGS) updates of the one K0
    factorisation with a line search; ``"modified"`` -- the paper's modified Newton-Raphson (K0 for every
    iteration); ``"full"`` -- Newton with the consistent tangent, refactorised every iteration.

    ``stepping`` (load control): ``"auto"`` (default) -- each target load factor is approached in increments
    that start at ``first_step``, grow or shrink with the iteration count (aiming at ``desired_iterations``)
    and are halved on failure down to ``min_step``; ``"fixed"`` -- each target is one increment, halved at
    most ``max_cuts`` times on failure (the paper's equal increments). Load steps are fractions of the largest
    target load factor; the controlled path's control steps start at ``first_step`` and stay within
    [``min_step``, ``max_step``] as fractions of the control at the largest target on the elastic path
    (see path.py). Tolerances are relative (dimensionless).

    ``max_iter`` and ``desired_iterations`` default to 100 and 20 on the controlled path, and per method on
    load control (bfgs 100 and 20, modified 300 and 60, full 30 and 8).

    ``flow``: ``"user"`` (default) -- each law's own dilation angle; ``"davis"`` -- Davis mode for capacity:
    every Mohr-Coulomb soil and Coulomb interface is solved associated with beta-reduced strength
    (c* = beta c, tan phi* = beta tan phi, psi* = phi*, beta = cos psi cos phi / (1 - sin psi sin phi)):
    a convex problem per increment with a symmetric tangent and a unique limit, so ``symmetric_tangent`` is
    True there whatever it is set to (measured on the 100 random zoo scenes, seed 1, controlled path: 94
    solved with the unsymmetric rules, 97 with the symmetric ones, in 0.89 of the time; the 33 limits both
    reached moved by at most 0.22 %).
    """

    method: str | None = None  # load control's method; None: "bfgs" (see above)
    stepping: str = "auto"
    force_tol: float = 1e-5  # |r| <= force_tol * (structural load; see convergence_reference)
    energy_tol: float = 1e-8  # |du . r| <= energy_tol * max(|du_0 . r_0|, work of the structural load)
    convergence_reference: str = "structural"  # "total": the old measure, force relative to
    # max(|F_ext|, |F_int|) and energy relative to |u . F_int|, geostatic forces included
    max_iter: int | None = None  # per increment; None: see above
    first_step: float = 0.1  # first increment (of the load factor, or of the controlled path's control)
    max_step: float = 0.25  # largest increment
    min_step: float = 1e-4  # smallest increment tried before the step is NonConvergence
    desired_iterations: int | None = None  # the iteration count the step size aims at; None: see above
    max_cuts: int = 6  # fixed stepping: halvings of a failing increment
    divergence_ratio: float = 1e6  # residual growth over the first iteration taken as divergence
    backend: str = "auto"
    symmetric_tangent: bool = False  # set True when every law's tangent is symmetric (associated flow);
    # always True in Davis mode (flow="davis")
    verbose: bool = False  # log every converged step at INFO level (logger "ssi.solver")
    progress: bool | None = None  # progress bar: None = only when stderr is a terminal and no test runs
    keep_states: bool = True  # keep the committed state of every step (False: only the last)
    line_search: bool | None = None  # None: on for bfgs and the controlled path, off for full Newton (on, it
    # stopped chapter 11's finest mesh at 95 % of its load); never for modified Newton
    line_search_min: float = 1.0 / 64.0  # full Newton: smallest step fraction the line search tries
    bfgs_memory: int = 30  # L-BFGS pairs kept within an increment
    control: str | None = None  # "work" (controlled path following) or "load"; None: see the rule above
    flow: str = "user"  # "user" or "davis" (see above)

    def __post_init__(self):
        if self.method is not None:
            check_choice("Settings.method", self.method, METHODS)
        check_choice("Settings.stepping", self.stepping, STEPPINGS)
        check_choice("Settings.convergence_reference", self.convergence_reference, REFERENCES)
        if self.control is None:  # naming a load-control algorithm asks for load control
            self.control = "load" if self.method is not None or self.stepping == "fixed" else "work"
        check_choice("Settings.control", self.control, CONTROLS)
        check_choice("Settings.flow", self.flow, FLOWS)
        path = self.control == "work"
        if path and (self.method is not None or self.stepping != "auto"):
            name, value = ("method", self.method) if self.method is not None else ("stepping", self.stepping)
            raise ValueError(
                f"Settings.{name}={value!r} is a load-control option: the controlled path (control='work') "
                "has one corrector and its own step-size rule; use control='load' for it"
            )
        if not path and self.method is None:
            self.method = "bfgs"
        if self.max_iter is None:
            self.max_iter = _MAX_ITER_PATH if path else _MAX_ITER[self.method]
        if self.desired_iterations is None:
            self.desired_iterations = _DESIRED_ITER_PATH if path else _DESIRED_ITER[self.method]
        if self.line_search is None:
            self.line_search = path or self.method == "bfgs"
        check_real("Settings.force_tol", self.force_tol, lo=0.0, hi=1.0, lo_open=True, hi_open=True)
        check_real("Settings.energy_tol", self.energy_tol, lo=0.0, hi=1.0, lo_open=True, hi_open=True)
        check_int("Settings.max_iter", self.max_iter, lo=1)
        check_int("Settings.max_cuts", self.max_cuts, lo=0)
        check_int("Settings.desired_iterations", self.desired_iterations, lo=1)
        check_int("Settings.bfgs_memory", self.bfgs_memory, lo=0)
        check_real("Settings.max_step", self.max_step, lo=0.0, hi=1.0, lo_open=True)
        check_real("Settings.first_step", self.first_step, lo=0.0, hi=self.max_step, lo_open=True)
        check_real("Settings.min_step", self.min_step, lo=0.0, hi=self.first_step, lo_open=True)
        check_real("Settings.divergence_ratio", self.divergence_ratio, lo=1.0, lo_open=True)
        check_choice("Settings.backend", self.backend, BACKENDS)
        for name in ("symmetric_tangent", "verbose", "keep_states", "line_search"):
            check_bool(f"Settings.{name}", getattr(self, name))
        if self.progress is not None:
            check_bool("Settings.progress", self.progress)
        check_real("Settings.line_search_min", self.line_search_min, lo=0.0, hi=1.0, lo_open=True)

    @classmethod
    def paper(cls, **overrides: object) -> "Settings":
        """The paper's algorithm (§8): modified Newton--Raphson on K0 in the given, equal load increments
        (load control).

        (The paper's explicit D_ep stress integration is a property of the soil law: ``scheme="explicit"``
        on a ``SoilLayer`` or in ``mohr_coulomb_params``.)"""
        return cls(**{"method": "modified", "stepping": "fixed", "control": "load", **overrides})


class NonConvergence(RuntimeError):
    """An increment failed after all step cuts; ``report`` says what, where and at which load."""

    def __init__(self, report: dict, result: "Result") -> None:
        self.report = report
        self.result = result  # the converged steps before the failure, for inspection only
        text = ", ".join(f"{k}={v}" for k, v in report.items())
        super().__init__(f"increment did not converge: {text}")
