"""The tunables of the controlled path (:mod:`ssi.solver.path`) in one frozen object, ``PathPolicy``, and its
default instance ``PATH_POLICY``.

``Settings`` holds what a user chooses (tolerances, step sizes, the method, the back end); ``PathPolicy``
holds how the path decides (when a load has peaked, when a factor is stale, how far a line search goes). The
values were measured on the random zoo, chapters 10, 11, 13 and 19 and the bench footing; what was measured
and not kept is in ``docs/solver/decisions.md`` under the entry named in each field's line. A study that
varies a rule passes ``run_path(..., policy=replace(PATH_POLICY, plateau_rise=0.05))`` or sets ``path.POLICY``
for a block.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..core.validate import check_choice, check_int, check_real

SECANT_RULES = ("never", "poor", "always")


@dataclass(frozen=True)
class PathPolicy:
    """How the controlled path decides; every field [-] unless a unit is given. Defaults: ``PATH_POLICY``."""

    plateau_rise: float = 2e-3
    """A load rising less than this fraction over a continuation is on a plateau; a load below (1 - this) x
    its maximum has fallen (0.2 %: decisions.md#plateau)."""
    plateau_steps: int = 10
    """... the continuation is at least this many steps [steps] (decisions.md#plateau)."""
    plateau_control: float = 0.5
    """... and this fraction of the control value where the plateau began; both, not either: 10 small steps of
    a crawl made chapter 11's cracking strip a false limit (decisions.md#plateau)."""
    fall_steps: int = 3
    """A load below its maximum for this many successive steps has passed a peak [steps]; one or two lower
    steps are a cracking dip the path may climb out of."""
    poor_contraction: float = 0.8
    """|r_k| / |r_k-1| above this is a poor contraction (decisions.md#refactorisation)."""
    poor_run: int = 3
    """... in this many successive iterations, and the tangent is refactorised [iterations]
    (decisions.md#refactorisation)."""
    soft_mode: float = 1e-3
    """The failure report names a mode without stiffness where K_t's Rayleigh quotient is below this fraction
    of K0's (chapter 19's floating strip: 2.7e-5)."""
    singular_shift: float = 1e-6
    """A singular symmetric consistent tangent is factorised as K_t + this x diag(K0): errs by 1e-6 of K0 on
    the other modes (decisions.md#singular-shift)."""
    growth: tuple[float, float] = (0.5, 2.0)
    """Bounds of the step factor (N_target / N)^(1/2): a step at most halves or doubles."""
    line_search_min: float = 1.0 / 64.0
    """Smallest step fraction of the backtracking line search on a tangent factor
    (decisions.md#line-search)."""
    g_growth: float = 10.0
    """On a cracking strip's unsymmetric factor, Matthies & Strang's root is not taken if it raises |r| this
    many times; the backtracking trial of least |r| instead [-] (decisions.md#g-growth)."""
    secant_rule: str = "poor"
    """When the corrector factorises SECANT_SOFTENING in place of CONSISTENT: "never", "poor" (a
    refactorisation asked for by a poor contraction) or "always" (decisions.md#secant-rule)."""
    small_strain: float = 0.1
    """A limit whose loaded displacement exceeds this x the loaded width is suspect (beyond small strain)."""
    overshoot_trials: int = 8
    """Trials of the regula falsi below the Matthies & Strang search's smallest step
    (decisions.md#overshoot)."""
    overshoot_min: float = 1e-3
    """... and the smallest step fraction it tries (decisions.md#overshoot)."""
    relax_halvings: int = 3
    """Where the corrector stalls, the relaxation tries the load increments d, d / 2, ... (this + 1 in all;
    decisions.md#relax)."""
    relax_beta: float = 0.95
    """Momentum of the relaxation's heavy ball: 0.8 settles too fast to leave the saddle (random 36 stops at
    its stall), 1 without restarts never settles (decisions.md#relax)."""
    relax_max_iter: int = 4000
    """Iterations of one relaxation at a prescribed load factor [iterations] (decisions.md#relax)."""
    relax_window: int = 1000
    """Its stagnation window [iterations]: the stable modes reached contract slowly (the smallest eigenvalue
    of K_t x = mu K0 x at random 36's relaxed state: 1.2e-3, ~1900 iterations a decade)."""
    kept_steps: int = 24
    """Committed steps kept for the half-size redo of the steps around a peak [steps]."""
    redo_steps: int = 3
    """Steps before (and after) the peak that the redo covers [steps]; the limit's uncertainty is the larger
    of the redo's change of the peak and the parabola's excess through the peak and its neighbours."""

    def __post_init__(self):
        check_real("PathPolicy.plateau_rise", self.plateau_rise, 0.0, 1.0, lo_open=True, hi_open=True)
        check_int("PathPolicy.plateau_steps", self.plateau_steps, 1)
        check_real("PathPolicy.plateau_control", self.plateau_control, 0.0)
        check_int("PathPolicy.fall_steps", self.fall_steps, 1)
        check_real("PathPolicy.poor_contraction", self.poor_contraction, 0.0, 1.0, lo_open=True)
        check_int("PathPolicy.poor_run", self.poor_run, 1)
        check_real("PathPolicy.soft_mode", self.soft_mode, 0.0, 1.0, lo_open=True)
        check_real("PathPolicy.singular_shift", self.singular_shift, 0.0, 1.0, lo_open=True)
        low, high = self.growth
        check_real("PathPolicy.growth[0]", low, 0.0, 1.0, lo_open=True)
        check_real("PathPolicy.growth[1]", high, 1.0, math.inf)
        check_real("PathPolicy.line_search_min", self.line_search_min, 0.0, 1.0, lo_open=True)
        check_real("PathPolicy.g_growth", self.g_growth, 1.0, math.inf, allow_inf=True)
        check_choice("PathPolicy.secant_rule", self.secant_rule, SECANT_RULES)
        check_real("PathPolicy.small_strain", self.small_strain, 0.0, lo_open=True)
        check_int("PathPolicy.overshoot_trials", self.overshoot_trials, 0)
        check_real("PathPolicy.overshoot_min", self.overshoot_min, 0.0, 0.05, lo_open=True)
        check_int("PathPolicy.relax_halvings", self.relax_halvings, 0)
        check_real("PathPolicy.relax_beta", self.relax_beta, 0.0, 1.0, lo_open=True)
        check_int("PathPolicy.relax_max_iter", self.relax_max_iter, 1)
        check_int("PathPolicy.relax_window", self.relax_window, 1)
        check_int("PathPolicy.kept_steps", self.kept_steps, 2)
        check_int("PathPolicy.redo_steps", self.redo_steps, 1)


PATH_POLICY = PathPolicy()
"""The default policy: the values the path was measured with."""
