"""Controlled path following (``Settings(control="work")``): a limit only where the path peaks.

Each step prescribes an increment ds of a control that keeps rising through a limit point, and the load
factor lambda is an unknown of the step:

* force loads: the work of the reference load, s = f_ref . (u - u_0) (indirect displacement control); the
  load measure P whose peak is the limit is lambda;
* prescribed displacements and no force load: s = lambda (displacement control, monotone by itself); P is
  the reaction along the prescribed displacements.

One corrector: Newton on a lagged factorisation of the consistent tangent, refactorised only when the
observed contraction |r_k| / |r_k-1| stays above ``POOR_CONTRACTION`` for ``POOR_RUN`` iterations (a new
factor that does not solve its own matrix to ``TANGENT_SOLVE_TOL`` is not used), L-BFGS updates on that
factor, and a line search; no retry ladder. A symmetric tangent (associated or Davis-mode
soil, ``Settings.symmetric_tangent``) starts the path, and each step after a failed one, on K0 and searches
along Matthies & Strang's G, the slope of the increment's potential; an unsymmetric one (slipping contact,
non-associated soil) factorises the tangent of the committed state there instead and backtracks on the
residual norm, along G only where no step lowers it (see ``_line_search``). With work control each
iteration solves the bordered system by two solves with that operator H ~ K^-1: a = H r, b = H f_ref,
d lambda = -(f_ref . a) / (f_ref . b), du = a + d lambda b, which keeps f_ref . du = 0 after a predictor
that meets the constraint exactly (the previous step scaled, or the tangent b at the first step). A step to
a prescribed lambda without a previous step starts from the committed tangent's linear response to it,
prescribed displacements included (``_prescribed_predictor``).

State table (one row per transition; a "step" is one control increment ds)::

    state  | event                                    | action                              | next
    -------+------------------------------------------+-------------------------------------+-------
    START  | no reference load, no prescribed         | one load-controlled step to the     | end
           |   displacement (dead load only)          |   last target (NonConvergence if it |
           |                                          |   fails: lambda scales nothing)     |
    START  | residual above the tolerance             | load-controlled step at lambda_0    | FIRST
    START  | balanced                                 | --                                  | FIRST
    FIRST  | --                                       | load-controlled step to             | WATCH
           |                                          |   lambda_0 + ds / (f_ref K0^-1 f_ref)|
    STEP   | secant predictor passes the target       | load-controlled step to the target  | FINAL
    STEP   | converged, lambda below the target       | commit; ds <- ds clip(sqrt(N*/N),   | WATCH
           |                                          |   1/2, 2) within [ds_min, ds_max]   |
    STEP   | converged, lambda passes the target      | redo as one load-controlled step    | FINAL
           |                                          |   to the target                     |
    START  | every law associated (``associated``)   | run as with symmetric_tangent=True  | (same)
    any    | a symmetric tangent's factor does not    | iterate on K_t + SINGULAR_SHIFT     | (same)
           |   solve its own matrix (singular K_t)    |   diag(K0) (_regularised)           |
    any    | symmetric: the line search overshoots    | regula falsi on G below t = 0.05    | (same)
           |   (G(t) < 0, |r| grew)                   |   (_overshoot)                      |
    any    | not converged                            | ds <- ds / 2; next step from K0     | STEP
    any    | not converged, ds < ds_min               | RELAX: damped dynamics on K0 at a   | WATCH
           |                                          |   prescribed lambda (_relax,        |
           |                                          |   _dynamic); ds <- ds_min           |
    RELAX  | no load increment converges              | NonConvergence (diagnosis: groups,  | end
           |                                          |   points changing state, lambda, s) |
    FINAL  | converged                                | commit (ds kept)                    | WATCH,
           |                                          |                                     | next
           |                                          |                                     | target
    WATCH  | P below (1 - PLATEAU_RISE) P_max, for    | the steps around the peak redone    | LIMIT
           |   FALL_STEPS steps or a continuation     |   at half size: uncertainty;        |
           |   as below                               |   checks: limit_suspect             |
    WATCH  | P within PLATEAU_RISE of P_max since the | as above                            | LIMIT
           |   control was s_p, and s - s_p >=        |                                     |
           |   s_p / 2 over >= PLATEAU_STEPS steps    |                                     |
    WATCH  | (either above) after a relaxed step      | damped dynamics to (1 + 2           | STEP
           |                                          |   PLATEAU_RISE) x the peak (_above):|
           |                                          |   converged -> committed, no limit  |
    WATCH  | the peak is a relaxed state              | NonConvergence, never a limit       | end
    WATCH  | otherwise                                | --                                  | STEP

ds_max is ``max_step`` of the elastic work at the largest target, or of the work done so far if larger
(a softened path's work grows faster than the elastic one). FIRST exists because from the start state a
contact that carries no load yet lets a work step follow a mechanism at lambda = 0 (a weightless strip
lifting off).

A failure to converge is never read as a limit. A limit is reported with ``limit_uncertainty``, the
mechanism certificate of its increment (``limit_mechanism``, ``limit_stored_share``:
:mod:`ssi.solver.mechanism`) and, when a check fails, ``limit_suspect`` with the reason
(:func:`ssi.limit.flag_suspect` adds the limit-analysis bracket's verdict).

Where the corrector stalls at the smallest step (issue 45): past a bifurcation of the non-associated soil
the equilibrium it sits on is a saddle (the tangent has a negative eigenvalue), and the step is found at a
prescribed load factor by damped dynamics on K0 (:mod:`ssi.solver.relax`), which leave the saddle and settle
on a stable equilibrium, accepted by the same tests as any step; the result then says the state is one of
several (``Result.relaxed_note``). A peak at such a state is never a limit. What was measured:
docs/solver/decisions.md (#relax, #no-limit-from-a-relaxed-state).

Where the path stopped before that fallback: non-associated soil at the edge of its plastic zone. In 10 of the
random zoo's 12 stopped scenes (seed 1), at the bench footing's failed steps and at chapter 13's graded copy
(whose round-off copies stop at lambda ~ 0.902), the residual hovers at 1-13 times ``force_tol`` while soil
points flip between elastic and plastic: the tangent there is nearly singular (x.K_t.x / x.K0.x from -2.5e-3
to 3e-3) and along an exact Newton direction |r| falls only up to t ~ 1e-3 - 1e-2, where plastic points unload
elastically. Measured and not kept (issue 31; zoo outcomes completed / limit / NonConvergence from 57 / 31 /
12): full Newton over the whole path (6 of the 12 solved, two others stopped earlier); a rewind of 23 steps
with full Newton after a failure at the smallest step (60 / 33 / 7, the zoo 1.35-1.6x slower, chapter 10's
finest psi = 0 push 3.7x: a retry after a failure, which this module does not do); a Levenberg- Marquardt
shift of 6e-3 x the soil's K0 in its tangent (6 solved; scene 86 lost, five limits down by 0.46-8 %); 1e-3 of
the elastic matrix at apex points (one solved, one lost, limits -3.3 % and -8.1 %); the shift of
``_regularised`` on the soil's DOFs (none solved); the elastic tangent at near-neutral plastic points (the
footing's copies 5 of 6 at threshold 0.1, stopped at 0.3); ``force_tol`` 1e-4 (4 of the 12 solved, the others
stopping elsewhere), 1e-3 (7 of 12 end, scene 21 at a false early peak 0.344 where full Newton's plateau is
0.499) and 1e-6 (2 of 12, the others earlier); on chapter 13's copy a control on the strip's end zone and the
bordered solve on the tangent's factor (both stop at ~0.902). In Davis mode the same scenes complete or peak.
Also measured and not kept (speed10): ``min_step`` 1e-5 and 1e-6 on the path in place of 1e-4. The bench
footing's ten round-off copies (settlement x (1 + eps), |eps| <= 2e-12) then complete 9 and 10 of 10 (with
1e-4: 6, the others stopping at lambda = 0.655-0.752; in the copy traced, 4 soil points flipping and the
smallest steps' residuals at 1.4-1.8 x ``force_tol``), with the key's own time unchanged; the random zoo 57 /
31 / 12 -> 57 / 35 / 8 and 57 / 36 / 7 (scenes 21, 22, 50, 82 and, with 1e-6, 54 now at a limit; the 31 limits
unchanged, no scene lost), but three of the new limits are false collapses by the limit-analysis bracket -- 21
at 0.291, 50 at 0.812 and 82 at 0.730 lie below 0.97 x their Davis lower bounds (0.314, 0.907, 1.510;
``reference_data/zoo_brackets_random.csv``), only 22 (0.225, 2.8 % above 1.03 x its associated upper bound)
and 54 (0.839, in its bracket) pass -- and the zoo took 1.33x the time with 1e-5 (run beside main's, same
load: scene 22 crawls along its plateau for 403 steps, 4 s -> 76 s; scene 0 takes steps below 1e-4, 16 s -> 68
s). Also not kept, a status hysteresis of the soil points (branch active10, commit 983c2b1, not merged: no
product code carries it): a point keeps its status of the previous iterate (elastic, or its return branch; at
a step's first iterate, of the committed state) while that moves its nodal forces by at most band = force_tol
x F, F the residual's force scale (the stress error so bounded per point). The zoo 57 / 31 / 12 again: scenes
22 (limit 0.2247, 382 steps), 50, 82 solved, 0 and 37 (completed) and 30 (limit) lost, 83's limit -8.0 %; the
bench footing stopped at lambda 0.393; the converged steps' plain residual (no hysteresis) up to 1.9 x
force_tol (scenes 0, 50, 82, 83). Keeping only elastic statuses, only plastic ones, or bands of 0.1 and 10 x:
1, 2, 3, 3 of the 12 solved (with the 4 scenes lost above: 16 tried), each a different few, all but the band
of 10 x losing scene 30 or 0. The band of 10 x on the whole zoo: 60 / 31 / 9, none lost, limits moved <= 0.30
%, the footing completes (q_u -0.36 %), the Davis-mode zoo 61 / 39 / 0 as before (limits <= 0.34 %) -- but it
is a looser tolerance in disguise, found by a sweep, not an argument: its converged steps' plain residual is
4-18 x force_tol (median 4.3-11 on scenes 0, 30, 46, 50, 82), as with force_tol 1e-4 above. With the band
tightened within a step instead (10 x, then / 10 at each convergence whose plain residual misses force_tol,
down to 0; commit 897c702) and a step accepted only where the plain law meets force_tol: 2 of the 12 (46, 82),
scene 30 lost, 83's limit -8.0 %. Freezing every status from iteration 10 and releasing the inconsistent
points each time the frozen system converged (primal-dual active set, up to 8 releases): 1 of the 12, 13 of
the 16 scenes tried ended earlier; the same from iteration 20 with the hysteresis: 57 / 30 / 13 (82 solved, 25
and 73 lost). Why (active10's status-flip tool on main's last steps of the 12): only 13-68 % of their status
changes would be kept by a band of force_tol x F (the median band needed 0.4-28 x it); the others are points
unloading by f ~ 1e-3 - 1e-2 of their stress scale along a long Newton step on the nearly singular tangent
(|r| growing 10-1 000 times), which a constitutive tolerance tied to the force tolerance cannot hold.

Why no corrector can be counted on there: every soil of the random zoo flows with psi < phi (the top layer psi
= 0 under phi = 0-38 deg, the lower psi = 5 under 35), and perfectly plastic Mohr-Coulomb flow with psi < phi
has lost ellipticity at every yielding point (the acoustic tensor's determinant is negative for a fan of band
normals: min det Q_ep / det Q_e = -0.018 to -0.054 in the 12 stopped scenes; zero for associated flow;
Rudnicki & Rice 1975, Vermeer & de Borst 1984; :mod:`ssi.materials.mc_localisation`). The rate problem at the
plastic front then has no unique solution, and a discrete one near the last state need not exist: the nearly
singular, indefinite tangents and the points unloading along every Newton step above are its symptoms. All 12
stopped scenes are such fronts (100-401 of the top layer's points plastic in the failed iterate), and their
Davis-mode copies (associated, on the boundary of ellipticity) all end. A ``NonConvergence`` there names the
materials and their ratios (report key ``ill_posed``, :func:`.diagnostics.ill_posed_soil`).
"""

from __future__ import annotations

import math
import time
from collections import deque
from dataclasses import replace

import numpy as np
import scipy.sparse as sp

from ..core.assembly import scatter_vector
from ..core.linsolve import Factorization
from ..core.model import Model
from ..core.protocol import CONSISTENT, SECANT_SOFTENING
from ..core.solution import LIMIT_LOAD, STOPPED, Result
from ..elements.interface import Interface6
from ..elements.plate import PlateStrip
from ..elements.soil_q8 import SoilQ8
from ..elements.spring import Spring
from ..materials.layer_laws import ELASTIC
from ..materials.soil_laws import MOHR_COULOMB, MOHR_COULOMB_EXPLICIT
from .diagnostics import _failure_report, ill_posed_soil
from .increment import (
    TANGENT_SOLVE_TOL,
    _converged,
    _energy_scale,
    _force_scale,
    _Lbfgs,
    _norm,
    _stagnates,
    cracking_strip,
)
from .mechanism import check_mechanism, flow_is_associated, increment_energy
from .progress import SolverProgress, solver_progress
from .record import _record, _start
from .relax import relax
from .settings import NonConvergence, Settings

PLATEAU_RISE = 2e-3  # a load rising less than 0.2 % over the continuation below is on a plateau
PLATEAU_STEPS = 10  # ... continuation of at least this many steps ...
PLATEAU_CONTROL = 0.5  # ... and of this fraction of the control value where the plateau began (both: with
# "or", 10 small steps of a crawl made chapter 11's cracking strip at h = 1/8 a false limit at 0.969)
FALL_STEPS = 3  # a load below its maximum for this many successive steps has passed a peak (one or two
# lower steps are a cracking dip the path may climb out of)
POOR_CONTRACTION = 0.8  # |r_k| / |r_k-1| above this ...
POOR_RUN = 3  # ... in this many successive iterations: the tangent is refactorised. (Measured on the random
# zoo, seed 1, whose tangents are unsymmetric: starting each step on K0 and waiting 8 poor iterations left
# 29 of 100 scenes stopped, most where the contact slips or opens -- K0's iterations there crawl until the
# stagnation test ends them; the tangent of the committed state at a step's start, 2 poor iterations and
# the line search of _line_search: 18, in 120 s against 218 s back to back. On chapter 06's associated
# footing the tangent start cost 26 steps and 33 factorisations against 13 and 11 from K0: symmetric
# tangents keep the K0 start. Then 0.9 / 2 -> 0.8 / 3, issue 31: chapter 11 at h = 0.125 m, 10 targets,
# factorisations 153 -> 61, failed steps 7 -> 3, iterations 1085 -> 815, residual evaluations 3725 ->
# 2317, CPU 9.9 -> 6.4 s; the 100 random zoo scenes (seed 1) completed / limit / NonConvergence 52 / 30 / 18
# -> 54 / 30 / 16 (now solved: 12, 30, 48, 73, 97; lost: 25, 50, 82), 5 500 tangent factorisations
# against 6 400 on scenes 20-99 in the same CPU time, one limit moved by > 0.5 % (scene 62: +3.7 %). The
# neighbours are not smooth: 0.9 / 3 61 factorisations and 5 failed steps on chapter 11, 0.85 / 3 49 and
# 1, 0.7 / 3 250 and 20, 0.8 / 2 and 0.8 / 4 NonConvergence -- the outcome of a hard step is sensitive to
# when its tangent is refreshed, so these numbers order the rules, they do not make one robust)
SOFT_MODE = 1e-3  # _soft_mode: K_t's Rayleigh quotient below this fraction of K0's: a mode without stiffness
# (chapter 19's floating strip: 2.7e-5 after three inverse iterations)
SINGULAR_SHIFT = 1e-6  # a singular consistent tangent is factorised as K_t + this x diag(K0) (_regularised)
GROWTH = (0.5, 2.0)  # bounds of the step factor (N_target / N)^(1/2)
LINE_SEARCH_MIN = 1.0 / 64.0  # line search on a tangent factor: smallest step fraction tried. Measured
# (issue 31, speed10; the bench footing, psi = 0, h = 0.125 m / chapter 11 at h = 0.125 m): t = 1 accepted
# at the first evaluation in 39 % / 66 % of the searches, 2.7 / 2.1 evaluations a search, 10 % / 8 % going
# down to 1/64 or to the fallback on G (7-10 evaluations). The acceptance |r(t)| < |r_0| is the cheapest
# monotone test (Armijo's sufficient decrease is stricter); the non-monotone test |r(t)| < the largest |r|
# of the step's last m iterations completed 0 of 5 round-off copies of the footing with m = 2 and 2 of 5
# with m = 5 (this rule, m = 1: 4 of 5), and a tangent refactorised at the iterate where no t lowers |r|
# (before the fallback on G) stopped all of 10 copies at lambda = 0.392
G_GROWTH = 10.0  # on an unsymmetric tangent's factor of a model with a cracking strip (cracking_strip), a
# step to G's root that raises |r| this many times is not taken, the backtracking trial of least |r| instead
# (see _line_search: the strip's cracked layer points flip between softening and unloading, and the root's
# long steps made |r| grow 10-300 times). Only there: applied to every model it also changed soil-only
# scenes, whose failures are not the strip's -- the 100 random zoo scenes, seed 1 (elastic strips), completed
# / limit / NonConvergence 57 / 31 / 12 without it, 60 / 30 / 10 with 10 (30 lost), 59 / 31 / 10 with 30 and
# random 46 a "limit" 0.69 % below 0.97 x its certified Davis floor (a false collapse); chapter 10's psi = 0
# footing (rigid) with 20- and 40-step budgets stopped at lambda = 0.16 with 10 on h = 0.125 m and at 2.4 cm
# on h = 0.0625 m. On chapter 11 at h = 0.125 m (SECANT_RULE "poor"): 53 factorisations and 0 failed steps
# with 10, 171 and 6 without the rule.
SECANT_RULE = "poor"  # when the corrector factorises SECANT_SOFTENING (ssi.core.protocol: the consistent


# tangent with the secant sig / e at the plate's concrete points loading on their cracked tension envelope) in
# place of CONSISTENT (_tangent_flag): "never", "poor" (a refactorisation asked for by a poor contraction; the
# factor is then kept, lagged, like any other) or "always". With G_GROWTH = 10, "poor": chapter 11 at h =
# 0.125 m 2.40 s CPU, 53 factorisations, 0 failed steps. Measured (issue 31, secant8, with G_GROWTH = 30;
# CPU s, same process; chapter 11, 10 targets, the run and its four copies with the column load x (1 +-
# 1e-13), (1 +- 1e-12); chapter 13's graded h/4 copy, default Settings):
#   rule    h = 0.125 m: complete; failed steps; CPU        | h = 0.25 m: failed; steps; CPU | ch13 graded
#   never   3 of 5; 6, 6, 13, 12, 6 (NC 0.871, 0.870); 6-7 | 1 each; 18-22; 0.74-1.01      | NC 0.9013, 26 s
#   poor    5 of 5; 0, 7, 4, 0, 4; 1.9-7.6                  | 1 each; 32-34; 1.48-1.61      | NC 0.9010, 55 s
#   always  5 of 5; 0, 6, 3, 0, 6; 1.9-10.2                 | 1 each; 51-52; 2.16-2.38      | NC 0.9021, 47 s
# "poor" completes every copy of the fine strip (2 of 5 without a failed step, in ~2 s) but costs 1.8x the
# CPU at h = 0.25 m (same failed step) and 2.1x on the graded copy (same stop). It is the default: the
# issue's bench key (chapter 11 at h = 0.125 m) is the case it is for, and a scene without cracking concrete
# gets the same factorisations bit for bit (its groups' tangents do not depend on the flag). Also measured and
# rejected at h = 0.125 m (with G_GROWTH = 10): a consistent refactorisation at the next step's start after a
# secant one (1-5 failed steps each copy), the secant only from the second poor refactorisation of a step
# (1-12 failed, one NonConvergence), and the secant everywhere after the path's first failed step (3 copies:
# 103-125 steps, 11-16 s)
def _carrying_strip_x(model, dofs, x):
    """The x of the nodes of every element group carrying the loaded ``dofs`` whose elements have nodal
    ``coords`` and ``edofs`` (a plate strip under a column load); ``x`` itself when there is none."""
    out = []
    for g in model.groups:
        edofs, coords = getattr(g, "edofs", None), getattr(g, "coords", None)
        if edofs is None or coords is None or np.ndim(coords) != 3:
            continue
        if np.isin(np.asarray(edofs), dofs).any():
            out.append(np.asarray(coords)[..., 0].ravel())
    return np.concatenate(out) if out else x


SMALL_STRAIN = 0.1  # loaded displacement / loaded width beyond which a limit is suspect (not small strain)
OVERSHOOT_TRIALS = 8  # _overshoot: trials below the Matthies & Strang search's smallest step ...
OVERSHOOT_MIN = 1e-3  # ... and the smallest step fraction it tries
RELAX_HALVINGS = 3  # _relax: load increments tried where the corrector stalls: dlam, dlam / 2, ...
# (RELAX_HALVINGS + 1 in all; decisions.md#relax)
KEPT_STEPS = 24  # committed steps kept for the half-size redo of the steps around a peak
REDO_STEPS = 3  # steps before (and after) the peak that the redo covers; the uncertainty is the larger
# of the redo's change of the peak and the excess of the parabola through the peak and its neighbours


def run_path(
    model: Model, targets: np.ndarray, settings: Settings, start: Result | None, loads: tuple | None
) -> Result:
    """The controlled path through the rising ``targets`` (load factors); see the module docstring. Called by
    :func:`ssi.solver.run` when ``settings.control == "work"``."""
    if np.any(np.diff(np.concatenate([[0.0], targets])) <= 0.0):
        raise ValueError(f"control='work' needs rising positive load_factors, got {targets.tolist()}")
    t0 = time.perf_counter()
    if not settings.symmetric_tangent and associated(model):
        settings = replace(settings, symmetric_tangent=True)
    path = _Follower(model, settings, start, loads, scale=float(targets[-1]))
    try:
        with solver_progress(settings.progress, total=path.scale) as path.bar:
            if path.dead_only:
                path.balance(float(targets[-1]))
            else:
                path.equilibrate()
                for target in targets:
                    if path.follow(float(target)):
                        break
    finally:
        path.result.wall_time = time.perf_counter() - t0
    return path.result


def associated(model: Model) -> bool:
    """True if every law of the model has a symmetric consistent tangent: Mohr-Coulomb soil with psi = phi
    (elastic and von Mises soil as well), Coulomb interfaces with psi = phi, plates of elastic layers only,
    springs; any other group makes it False. The path then runs as with ``Settings.symmetric_tangent``
    (each step starts on K0, the line search follows the potential's slope G, a singular tangent is
    factorised shifted, see ``_regularised``), as in Davis mode: the increment is a convex problem.

    Measured (issue 31): chapter 19's embedded strip pushed sideways (Tresca clay, Tresca base, smooth side
    walls: all associated) stopped at lambda = 0 when run as unsymmetric: the step started on the tangent of
    the pushed predictor (base slipping, back wall open), whose directions of 0.8 m for a push of 2.5 mm the
    residual-norm backtracking accepted; on K0 with G and ``_overshoot`` it completes (h = 0.25 m: 22 steps,
    10 factorisations, H = 85.957 kN/m as on the load-controlled path to 5 digits). Not seen by this test:
    an interface point that re-closes within a step has an unsymmetric chained tangent (interface_law,
    step 1), which the symmetric factorisation then treats as symmetric -- as Davis mode does."""
    for g in model.groups:
        if isinstance(g, SoilQ8):
            mc = np.isin(g.kinds, (MOHR_COULOMB, MOHR_COULOMB_EXPLICIT))
            if any(m and p[3] != p[4] for p, m in zip(g.params, mc)):
                return False
        elif isinstance(g, Interface6):
            if np.any(np.asarray(g.params)[:, 3] != np.asarray(g.params)[:, 4]):
                return False
        elif isinstance(g, PlateStrip):
            if np.any(g.section.kind != ELASTIC):
                return False
        elif not isinstance(g, Spring):
            return False
    return True


class _Follower:
    """The committed path (u, states, lambda, control s) and the step rule of one controlled run."""

    def __init__(self, model, settings, start, loads, scale):
        self.model, self.settings = model, settings
        # the root's growth limit is for a cracking strip's kinks only (G_GROWTH)
        self.g_growth = G_GROWTH if cracking_strip(model) else np.inf
        self.system, self.f_ref, self.f_dead, self.states, self.u, self.result, k0 = _start(
            model, settings, start, loads
        )
        self.k0 = self.fac = k0  # K0 (SPD): the operator only until the first step factorises its tangent
        free = self.system.free
        self.f = self.f_ref[free]
        self.work = bool(np.any(self.f))  # work control; else displacement control on lambda
        ref = np.zeros(model.n_dof)
        ref[self.system.cons_dofs] = self.system.cons_ref
        # no reference load and no prescribed displacement (a phase of dead load only, e.g. a phased scene's
        # geostatic phase): lambda scales nothing, and the path is one balancing step (see balance)
        self.dead_only = not self.work and not np.any(ref)
        self.ref = ref
        self.lam = 0.0
        self.s = float(self.f @ (self.u[free] - self.result.u_origin[free])) if self.work else 0.0
        self.scale = scale
        self.bar = SolverProgress(None, 1.0)
        self.w1 = float(self.f @ k0.solve(self.f)) if self.work else 1.0  # elastic d s / d lambda
        unit = self.w1 * scale  # the control of lambda = scale on the elastic path
        self.started = False  # the first step is load-controlled (see follow)
        self.ds = settings.first_step * unit  # elastically: the work of the first load step
        self.ds_min, self.ds_max = settings.min_step * unit, settings.max_step * unit
        self.dlam_cap = settings.max_step * scale  # the largest load-factor correction of one iteration
        self.prev = None  # (du, dlam, ds) of the last committed step: the secant predictor
        self._k0_diag = None  # diag(K0) over the free DOFs, for a singular tangent (see _regularised)
        self.kept = deque(maxlen=KEPT_STEPS)  # (k, u, states, lam, s, P)
        self.relaxed = {}  # step -> the corrector's failure that a relaxed step (_relax) replaced
        self.loads = [self._load_measure(self.u, self.result.f_int[0], 0.0)]
        self.controls = [self.s]
        self.kept.append((0, self.u, self.states, 0.0, self.s, self.loads[0]))

    # ----------------------------------------------------------------------------------------------------
    def equilibrate(self):
        """Bring the start state into equilibrium at its own load factor first, under load control, when it
        is not (e.g. dead load added to a geostatic state): the controlled steps then carry only the
        reference load (measured: 8 of the random zoo's scenes failed at lambda ~ 0 while one step had to
        balance both). Recorded as a step only if it moved; raises NonConvergence if it fails."""
        r = (self.lam * self.f_ref + self.f_dead - self.result.f_int[-1])[self.system.free]
        reference = _norm(self.f) * self.scale if self.work else _norm(self.result.f_int[-1])
        if _norm(r) <= self.settings.force_tol * reference:  # balanced (to the tolerance of the first
            return  # step's load; the geostatic round-off is not to be iterated on: zoo scenes 2, 3, 9)
        out = self._step(self.u, self.states, self.lam, None, self.lam)
        if out is None:
            self._fail()
        if out["iterations"] > 1:
            self._commit(out)
        self.prev = None  # the balancing move is no predictor for the controlled steps

    def balance(self, target):
        """Nothing scales with lambda (``dead_only``): one load-controlled step to ``target`` balances the
        dead load, recorded as step 1 (a phased scene's geostatic phase has exactly that row); raises
        NonConvergence if it fails -- a smaller lambda would not change the load, so there is nothing to
        halve."""
        out = self._step(self.u, self.states, self.lam, None, target)
        if out is None:
            self._fail()
        self._commit(out, adapt=False)

    def follow(self, target) -> bool:
        """Advance to ``target``; True if the path ended at a limit."""
        while self.lam < target * (1.0 - 1e-12):
            if not self.started:  # from the start state, whose contact may carry no load yet, a work step
                # can follow a mechanism at lambda = 0 (a weightless strip lifting off: zoo scene 24)
                lam_next = min(target, self.lam + self.ds / self.w1)
                out = self._step(self.u, self.states, self.lam, None, lam_next)
                self.started, final = out is not None, False
            elif self._predicted_lam(self.ds) > target:  # the secant predictor passes the target: the
                out = self._step(self.u, self.states, self.lam, None, target)  # step ends on it instead
                final = True
            else:
                out = self._step(self.u, self.states, self.lam, self.ds)
                final = out is not None and out["lam"] > target
                if final:
                    out = self._step(self.u, self.states, self.lam, None, target)
            if out is None:
                self.result.cuts += 1
                self.ds *= 0.5
                if self.ds < self.ds_min * (1.0 - 1e-9):
                    out = self._relax(target)  # the corrector stalled: a stable equilibrium at a fixed lambda
                    if out is None:
                        self._fail()
                    self.started = True
                    self._commit(out)
                    self.relaxed[self.result.n_steps] = self.last_failure
                    self.ds = self.ds_min  # the controlled steps start again from the smallest
                    if self._limit():
                        return True
                continue
            self._commit(out, adapt=not final)  # a step cut short by the target says nothing of the size
            if self._limit():
                return True
        return False

    def _predicted_lam(self, ds):
        """The load factor the secant predictor reaches with the control step ``ds`` (current lambda if
        there is no previous step to scale)."""
        if self.prev is None:
            return self.lam
        return self.lam + ds / self.prev[2] * self.prev[1]

    def _fail(self):
        out = self.last_failure
        report = _failure_report(self.model, self.system.free, out, self.lam, out.get("lam", self.lam))
        report.update(control_value=self.s, control_step=self.ds, control="work" if self.work else "lambda")
        soft = self._soft_mode(out)
        if soft:
            report.update(soft_mode=soft)
        self.result.status = STOPPED
        raise NonConvergence(report, self.result)

    def _soft_mode(self, out) -> str:
        """The failed step's last iterate: if its consistent tangent has a mode without stiffness (Rayleigh
        quotient below ``SOFT_MODE`` of K0's along it, three inverse iterations on K_t + SINGULAR_SHIFT
        diag(K0)), which group carries it and whether the load does work on it, for the NonConvergence report
        (key ``soft_mode``) -- e.g. chapter 19's unloaded weightless strip whose cohesionless contact opened:
        a mechanism at lambda = 0 that no load drives, whose position the corrector cannot fix (residual
        stagnating at 7.5e-4; the mode: Rayleigh quotient 2.7e-5, on the strip's u DOFs, |f.x| / |f| |x| =
        8e-4). '' otherwise."""
        u = out.get("u")
        if u is None:
            return ""
        try:
            _, k_list, _ = self.system.evaluate(u, u - self.u, self.states, CONSISTENT)
            pattern = self.system.pattern
            kt = pattern.matrix(pattern.assemble(k_list))
            k0 = pattern.matrix(pattern.assemble_elastic(self.model.groups))
            d = k0.diagonal()
            shifted = kt + SINGULAR_SHIFT * _diag(d)
            fac = Factorization(shifted, symmetric=False, backend=self.settings.backend)
            x = np.ones(kt.shape[0])
            for _ in range(3):
                x = fac.solve(d * x)
                x /= np.abs(x).max()
        except (FloatingPointError, RuntimeError, ValueError):
            return ""
        quotient = abs(float(x @ (kt @ x))) / float(x @ (k0 @ x))
        if not quotient < SOFT_MODE:
            return ""
        full = np.zeros(self.model.n_dof)
        full[self.system.free_dofs] = x
        total = float(x @ x)
        share = {}
        for g in self.model.groups:
            on = full[np.unique(g.edofs)]
            share[g.name] = float(on @ on) / total
        ranked = sorted(share.items(), key=lambda item: -item[1])
        carriers = ", ".join(f"{name} {100 * v:.0f} %" for name, v in ranked if v >= 0.5)
        top = np.argsort(-np.abs(x))[:4]
        where = self.system.describe_dofs(top, 4).replace("unsupported DOFs: ", "")
        work = abs(float(self.f @ x)) / (_norm(self.f) * _norm(x)) if self.work else 0.0
        driven = (
            f"the reference load does almost no work on it (|f.x| / |f| |x| = {work:.1e})"
            if work < 1e-2
            else f"|f.x| / |f| |x| = {work:.2g}"
        )
        return (
            f"the tangent has a mode without stiffness (x.K_t.x / x.K0.x = {quotient:.1e}), "
            f"on the DOFs of {carriers} ({where}); {driven}: a body or region that "
            f"nothing holds at lambda = {self.lam:.4g} (e.g. an unloaded weightless strip whose contact "
            "opened)"
        )

    def _commit(self, out, adapt=True):
        du = out["u"][self.system.free] - self.u[self.system.free]
        ds = out["s"] - self.s
        self.prev = (du, out["lam"] - self.lam, ds) if ds > 0.0 else None
        self.u, self.states, self.lam, self.s = out["u"], out["states"], out["lam"], out["s"]
        _record(
            self.result, self.lam, self.u, out["f_int"], self.states, out["iterations"], out["residuals"],
            out["energies"], self.settings,
        )  # fmt: skip
        self.result.stiffness.append(np.nan)
        self.loads.append(self._load_measure(self.u, out["f_int"], self.lam))
        self.controls.append(self.s)
        self.kept.append((self.result.n_steps, self.u, self.states, self.lam, self.s, self.loads[-1]))
        self.bar.update(self.result.n_steps, self.lam, out["iterations"], out["residuals"][-1])
        if not adapt:
            return
        n = max(out["iterations"], 1)
        grow = min(max(math.sqrt(self.settings.desired_iterations / n), GROWTH[0]), GROWTH[1])
        # the largest step: max_step of the elastic work at the largest target, or of the work done so far
        # where the path has softened (else a soft path crawls: 427 steps on chapter 11's scene at h = 1/8)
        ds_max = max(self.ds_max, self.settings.max_step * abs(self.s - self.controls[0]))
        self.ds = min(max(grow * max(ds, self.ds_min), self.ds_min), ds_max)

    def _load_measure(self, u, f_int, lam):
        if self.work:
            return float(lam)
        return float((f_int - self.result.f_int_origin) @ self.ref)

    # ----------------------------------------------------------------------------------------------------
    def _limit(self) -> bool:
        """The WATCH rows of the state table; on a limit, the half-size redo and the checks."""
        p = np.asarray(self.loads)
        k_max = int(np.argmax(p))
        n = len(p) - 1
        if p[k_max] <= 0.0 or k_max == 0:
            return False
        on = np.flatnonzero(p >= p[k_max] / (1.0 + PLATEAU_RISE))[0]  # where the plateau began
        s = np.asarray(self.controls) - self.controls[0]
        continued = s[on] > 0.0 and s[-1] - s[on] >= PLATEAU_CONTROL * s[on] and n - on >= PLATEAU_STEPS
        below = p[-1] < (1.0 - PLATEAU_RISE) * p[k_max]
        fell = below and (n - k_max >= FALL_STEPS or continued)
        plateau = continued and not below
        if not (fell or plateau):
            return False
        if self.relaxed and self._above(float(p[k_max])):
            return False  # an equilibrium above the "peak": the path had left its branch, no limit
        if k_max in self.relaxed:  # the peak is a relaxed state: a fall from it is no evidence of a collapse
            self.last_failure = self.relaxed[k_max]  # (one of several states of the ill-posed soil): the
            self._fail()  # stop of the corrector that could not go on there
        res = self.result
        res.status, res.limit_load_factor = LIMIT_LOAD, float(res.load_factor[k_max])
        what = "peak passed" if fell else f"plateau over {n - on} steps"
        measure = f"load factor {p[k_max]:.6g}" if self.work else "of the reaction on the prescribed motion,"
        res.limit_evidence = f"controlled path: {what}, {measure} at step {k_max}"
        reasons = []
        redo = self._redo(k_max)
        vertex = self._vertex_excess(k_max) if fell else 0.0  # a plateau's corner is no smooth peak
        res.limit_uncertainty = None if redo is None else max(redo, vertex)
        if res.limit_uncertainty is None:
            reasons.append("the half-size redo of the steps around the peak did not converge")
        reasons.extend(self._certify(k_max, fell))
        strain = self._loaded_strain(k_max)
        if strain is not None and strain[0] > SMALL_STRAIN * strain[1]:
            reasons.append(
                f"loaded displacement {strain[0]:.3g} m > {SMALL_STRAIN:g} x the loaded width "
                f"{strain[1]:.3g} m: beyond small strain"
            )
        res.limit_suspect = "; ".join(reasons)
        self.bar.note(res.message)
        return True

    def _certify(self, k_max, fell) -> list[str]:
        """The mechanism certificate of the limit (ssi.solver.mechanism), recorded on the result; its failure
        as a reason (a list of at most one). Its increment: on a plateau the last one; where the path fell
        past a peak the one that reached the peak (past it the increments unload and release stored energy:
        in user flow, random zoo scene 30's last increment stored -88 % of its load work, measured), or the
        last one if that is no longer kept."""
        rows = {row[0]: row for row in self.kept}
        end = k_max if fell and k_max - 1 in rows else self.kept[-1][0]
        (_, u_a, states_a, *_), (_, u_b, states_b, _, _, load_b) = rows[end - 1], rows[end]
        energy = increment_energy(self.model, u_a, u_b, states_a, states_b, self.f_dead)
        davis = self.settings.flow == "davis"
        check = check_mechanism(energy, load_b, self.loads[k_max], flow_is_associated(self.model, davis))
        self.result.limit_mechanism, self.result.limit_stored_share = check.ratio, check.stored
        if check.note:  # why no certificate was given (non-associated flow, a cracking strip's work)
            self.result.limit_evidence += f"; no mechanism certificate: {check.note}"
        return [check.reason] if check.reason else []

    def _redo(self, k_max):
        """Relative change of the peak load when the kept steps from REDO_STEPS before the peak to
        REDO_STEPS after it are redone with each control increment split in two (None: a redo failed)."""
        kept = [row for row in self.kept if k_max - REDO_STEPS <= row[0] <= k_max + REDO_STEPS]
        if len(kept) < 2:
            return None
        _, u, states, lam, s, _ = kept[0]
        self.fac = self.k0  # the last step's factor belongs past the peak: the redo starts afresh
        peak = kept[0][5]
        for before, row in zip(kept, kept[1:]):
            # predictor of the half steps: the kept step itself (the secant predictor scales it)
            self.prev = (
                row[1][self.system.free] - before[1][self.system.free],
                row[3] - before[3],
                row[4] - s,
            )
            for c in (0.5 * (s + row[4]), row[4]):  # the control at the half and the end of the kept step
                out = self._step(u, states, lam, c - s) if self.work else self._step(u, states, lam, None, c)
                if out is None:
                    return None
                self.prev = (out["u"][self.system.free] - u[self.system.free], out["lam"] - lam, out["s"] - s)
                u, states, lam, s = out["u"], out["states"], out["lam"], out["s"]
                peak = max(peak, self._load_measure(u, out["f_int"], lam))
        p_max = max(row[5] for row in kept)
        return abs(peak - p_max) / abs(p_max)

    def _vertex_excess(self, k):
        """Relative excess of the vertex of the parabola through the load measure at the steps k - 1, k,
        k + 1 (over the control) above the largest step value: how far the discrete maximum may lie below the
        path's (0 without neighbours on both sides)."""
        if not 0 < k < len(self.loads) - 1:
            return 0.0
        x, y = np.asarray(self.controls[k - 1 : k + 2]), np.asarray(self.loads[k - 1 : k + 2])
        a, b, c = np.polyfit(x - x[1], y, 2)
        if not a < 0.0:
            return 0.0
        return float((c - b * b / (4.0 * a) - y[1]) / abs(y[1]))

    def _loaded_strain(self, k):
        """(largest loaded displacement [m], x-extent of the loaded nodes [m]) at step k, or None. Of a half
        model (``Model.info["mirror_x"]``, the x of its mirror axis) whose loaded nodes reach the axis, the
        extent of the whole loaded region, both halves."""
        dofs = np.flatnonzero(self.f_ref if self.work else self.ref)
        start = np.concatenate([[0], np.cumsum(self.model.node_ndof)])
        nodes = np.unique(np.searchsorted(start, dofs, side="right") - 1)
        if not nodes.size:
            return None
        x = self.model.coords[nodes, 0]
        width = float(np.ptp(x))
        mirror = self.model.info.get("mirror_x")
        if width <= 0.0:  # a point load (one column): the width of the strip it stands on
            x = _carrying_strip_x(self.model, dofs, x)
            width = float(np.ptp(x))
        if mirror is not None and abs(x.min() - mirror) <= 1e-9 * (1.0 + np.abs(x).max()):
            width = 2.0 * float(np.abs(x - mirror).max())
        if width <= 0.0:
            return None
        return float(np.abs(self.result.u[k][dofs] - self.result.u_origin[dofs]).max()), width

    # ----------------------------------------------------------------------------------------------------
    def _relax(self, target):
        """A step the corrector could not take (the control step halved below ``min_step``): an equilibrium
        at a prescribed load factor found by damped dynamics on K0 (``_dynamic``). The load increment: the
        last committed step's (or the elastic one of ``min_step``), halved up to ``RELAX_HALVINGS`` times;
        None if none converges (``last_failure`` then the corrector's own, for the diagnosis)."""
        failure = self.last_failure
        first = self.prev[1] if self.prev is not None and self.prev[1] > 0.0 else 0.0
        first = max(first, self.ds_min / self.w1)
        self.fac = self.k0  # the stalled step's factor is suspect: the next controlled step refactorises
        for k in range(RELAX_HALVINGS + 1):
            lam_to = min(target, self.lam + first * 0.5**k)
            out = self._dynamic(self.u, self.states, self.lam, lam_to)
            if out is not None:
                self.bar.note(f"relaxed step to lambda={lam_to:.6g} in {out['iterations']} iterations")
                self.last_failure = failure  # the corrector's failure, recorded against the relaxed step
                return out
        self.last_failure = failure
        return None

    def _above(self, peak) -> bool:
        """Where a path that took a relaxed step falls or levels off: is there an equilibrium above its peak?
        Damped dynamics (``_dynamic``) from the current state at (1 + 2 ``PLATEAU_RISE``) x the peak load
        factor; converged -> committed (True). Why: a relaxed step finds one of several states of the
        ill-posed soil, from which the controlled steps may follow a descending branch that is no collapse
        (docs/solver/decisions.md#no-limit-from-a-relaxed-state)."""
        lam_to = min(peak * (1.0 + 2.0 * PLATEAU_RISE), self.scale)
        if not lam_to > self.lam:
            return False
        failure = self.last_failure
        out = self._dynamic(self.u, self.states, self.lam, lam_to)
        self.fac = self.k0
        if out is None:
            self.last_failure = failure
            return False
        self._commit(out)
        self.relaxed[self.result.n_steps] = failure
        return True

    def _dynamic(self, u_n, states_n, lam_n, lam):
        """:func:`ssi.solver.relax.relax` from the committed state at the load factor ``lam``: the residual
        of the material update from the committed state over the whole increment (as in any step), K0 the
        mass, accepted by ``_converged`` with the force and energy references of a K0 step. Returns the
        step (dict, as ``_step``'s) or None (kept in ``last_failure``); counts the relaxation on the
        result."""
        st, sy = self.settings, self.system
        free = sy.free
        u = u_n.copy()
        if self.prev is not None:  # the secant predictor of a step to a prescribed lambda (see _step)
            du_p, dlam_p, _ = self.prev
            u[free] += (max((lam - lam_n) / dlam_p, 0.0) if dlam_p != 0.0 else 0.0) * du_p
        else:
            u = self._prescribed_predictor(u_n, states_n, lam)
        sy.apply_constraints(u, lam)
        f_ext = lam * self.f_ref + self.f_dead
        energies, trials = [], deque([None, None], maxlen=2)  # the last two iterates' states (diagnosis)

        def full(u_f):
            v = u.copy()
            v[free] = u_f
            return v

        def residual(u_f):
            ev = self._evaluate(full(u_f), u_n, states_n, lam)
            if ev is None:
                return None
            f_int, trial, r = ev
            trials.append(trial)
            rel = _norm(r[free]) / _force_scale(st, lam, self.f_ref, f_ext, f_int, self.result)
            return r[free], rel, (f_int, trial, r)

        energy0 = []

        def converged(rel, energy, it, u_f, data):
            if not energy0:
                energy0.append(energy)
            energies.append(energy / _energy_scale(energy0[0], full(u_f), data[0], self.result, st))
            return _converged(rel, energies[-1], it, st) or rel <= 1e-14 * st.force_tol

        run = relax(u[free], residual, self.k0.solve, converged)
        self.result.relaxed_iterations += run.iterations
        out = {"converged": run.converged, "residuals": run.residuals, "energies": energies}
        out.update(iterations=run.iterations, lam=lam, u=full(run.u), trial_prev=trials[0])
        if run.data is not None:
            f_int, trial, r = run.data
            out.update(residual=r, trial=trial, f_int=f_int, states=trial)
        if not run.converged:
            out.update(reason=run.reason)
            self.last_failure = out
            return None
        self.result.relaxed_steps += 1
        out["s"] = float(self.f @ (out["u"][free] - self.result.u_origin[free])) if self.work else lam
        note = ill_posed_soil(self.model, out["states"])
        if note and not self.result.relaxed_note:
            self.result.relaxed_note = note
        return out

    def _step(self, u_n, states_n, lam_n, ds, lam_target=None):
        """One step from a committed state: work control (``ds``) or, with ``lam_target`` (or displacement
        control), the load factor prescribed. Returns the converged step (dict) or None (kept in
        ``last_failure``)."""
        st, sy = self.settings, self.system
        free = sy.free
        fixed_lam = lam_target is not None or not self.work
        if fixed_lam and lam_target is None:  # displacement control: the control is lambda itself
            lam_target = lam_n + ds
        u = u_n.copy()
        if self.prev is not None:  # secant predictor: the last step scaled (meets the constraint exactly)
            du_p, dlam_p, ds_p = self.prev
            if fixed_lam:
                ratio = max((lam_target - lam_n) / dlam_p, 0.0) if dlam_p != 0.0 else 0.0
            else:
                ratio = ds / ds_p
            lam = lam_target if fixed_lam else lam_n + ratio * dlam_p
            u[free] += ratio * du_p
        elif fixed_lam:
            lam = lam_target
            u = self._prescribed_predictor(u_n, states_n, lam)
        else:  # tangent predictor: du = dlam H f_ref with f_ref . du = ds
            b = self.fac.solve(self.f)
            lam = lam_n + ds / float(self.f @ b)
            u[free] += (lam - lam_n) * b
        sy.apply_constraints(u, lam)
        bfgs = _Lbfgs(self.fac, st.bfgs_memory)
        residuals, energies = [], []
        out = {"converged": False, "residuals": residuals, "energies": energies, "iterations": 0, "lam": lam}
        ev = self._evaluate(u, u_n, states_n, lam)
        energy0 = trial_prev = None  # trial_prev: the last iterate's states, for the failure's diagnosis
        poor = 0
        for it in range(1, st.max_iter + 1):
            if ev is None:
                out.update(reason="material update failed", iterations=it)
                break
            f_int, trial, r = ev
            r_f = r[free]
            f_ext = lam * self.f_ref + self.f_dead
            rel = _norm(r_f) / _force_scale(st, lam, self.f_ref, f_ext, f_int, self.result)
            residuals.append(rel)
            out.update(iterations=it, residual=r, u=u, trial=trial, trial_prev=trial_prev, lam=lam)
            trial_prev = trial
            if not np.isfinite(rel):
                out.update(reason="residual is not finite")
                break
            if it > 1 and rel > st.divergence_ratio * max(residuals[0], st.force_tol):
                out.update(reason=f"residual grew by more than {st.divergence_ratio:g}")
                break
            if _stagnates(residuals):
                out.update(reason="residual stagnates (no decrease over the last 15 iterations)")
                break
            poor = poor + 1 if it > 1 and rel > POOR_CONTRACTION * residuals[-2] else 0
            # with an unsymmetric tangent a step that starts on K0 (the first, or the one after a failure)
            # factorises the consistent tangent of the committed state first (see POOR_RUN)
            stale = poor >= POOR_RUN or (it == 1 and self.fac is self.k0 and not st.symmetric_tangent)
            if stale and self._refactor(u, u_n, states_n, self._tangent_flag(poor >= POOR_RUN)):
                bfgs, poor = _Lbfgs(self.fac, st.bfgs_memory), 0
            a = bfgs.direction(r_f)
            dlam = 0.0
            if not fixed_lam:
                b = bfgs.direction(self.f)
                dlam = -float(self.f @ a) / float(self.f @ b)
                if not abs(dlam) <= self.dlam_cap:  # f . b ~ 0: the factor is nearly singular along f_ref
                    out.update(reason=f"load-factor correction {dlam:.3g} beyond the largest step")
                    break
                a = a + dlam * b
            if not np.all(np.isfinite(a)):
                out.update(reason="the correction is not finite (singular tangent factor)")
                break
            energy = abs(float(a @ r_f))
            energy0 = energy if energy0 is None else energy0
            energies.append(energy / _energy_scale(energy0, u, f_int, self.result, st))
            # no "energy == 0" shortcut: with work control du may vanish while lambda still moves
            if _converged(rel, energies[-1], it, st) or rel <= 1e-14 * st.force_tol:
                s = float(self.f @ (u[free] - self.result.u_origin[free])) if self.work else lam
                out.update(converged=True, f_int=f_int, states=trial, s=s)
                return out
            u, lam, ev_new, step = self._line_search(u, u_n, states_n, lam, a, dlam, r_f)
            if ev_new is not None:
                bfgs.update(step * a, ev_new[0][free] - f_int[free])
            ev = ev_new
        else:
            out.update(reason=f"no convergence in {st.max_iter} iterations")
        out.setdefault("reason", "unknown")
        self.last_failure = out
        self.fac = self.k0  # a failed step's factor is suspect: the next factorises its own tangent
        self.bar.note(f"step halved at lambda={lam_n:.6g}: {out['reason']}")
        return None

    def _prescribed_predictor(self, u_n, states_n, lam):
        """The tangent predictor of a step to the load factor ``lam`` without a previous step to scale: the
        committed state's linear response to the change of load and of the prescribed displacements,
        u = u_n + H (r_n + (lam - lam_n) f_ref - K_t,fc du_c) over the free DOFs (H the current factor),
        the prescribed DOFs at ``lam``.

        Why: the prescribed DOFs alone moved (the free ones left at u_n) make a first iterate that tears the
        elements beside them. Measured (issue 31) on the bench footing (psi = 0, h = 0.125 m, pushed 8 cm in
        12 targets): its first step, 6.7 mm of rigid footing beside unmoved soil, put 968 of the weightless
        soil's integration points on the Mohr-Coulomb apex and 1 172 plastic; its tangent was singular (24
        of 26 refactorisations rejected) and the step failed four times (halved to 0.42 mm) before the
        iterations, 21 of them, reached a state with no plastic point at all. With this predictor the first
        step converges in 22 iterations: the push completes with 24 failed steps instead of 29 and 361
        factorisations instead of 450 (q_u / Prandtl 0.99577 against 0.99516), CPU 5.37 s against 6.84 s
        (best of 3, back to back: 0.785); with five perturbed copies (settlement x (1 + 1e-12), (1 - 1e-12),
        (1 + 1e-13); 11 and 13 targets) 4 of the 6 complete against 3 of 6. The random zoo and chapter 11
        (force loads) are unchanged bit for bit."""
        sy, free = self.system, self.system.free
        u = sy.apply_constraints(u_n.copy(), lam)
        delta = u - u_n
        if not np.any(delta):  # nothing prescribed moves: the first iteration is this predictor already
            return u
        try:
            f_int, k_list, _ = sy.evaluate(u_n, np.zeros_like(u_n), states_n, CONSISTENT)
        except FloatingPointError:
            return u
        f_lin = f_int.copy()
        for g, k_el in zip(self.model.groups, k_list):
            scatter_vector(g.edofs, np.einsum("eij,ej->ei", k_el, delta[g.edofs]), f_lin)
        du = self.fac.solve((lam * self.f_ref + self.f_dead - f_lin)[free])
        if np.all(np.isfinite(du)):
            u[free] += du
        return u

    def _evaluate(self, u, u_n, states_n, lam):
        try:
            f_int, _, trial = self.system.evaluate(u, u - u_n, states_n, None)
        except FloatingPointError:
            return None
        return f_int, trial, lam * self.f_ref + self.f_dead - f_int

    def _tangent_flag(self, poor: bool) -> int:
        """The tangent flag of a factorisation (``SECANT_RULE``); ``poor``: asked for by a poor contraction
        (POOR_RUN)."""
        if SECANT_RULE == "always" or SECANT_RULE == "poor" and poor:
            return SECANT_SOFTENING
        return CONSISTENT

    def _refactor(self, u, u_n, states_n, tangent=CONSISTENT) -> bool:
        """Factorise the tangent ``tangent`` at ``u`` (False, the old factor kept, if it cannot be)."""
        try:
            _, k_list, _ = self.system.evaluate(u, u - u_n, states_n, tangent)
        except FloatingPointError:
            return False
        probe = None
        try:
            kt = self.system.pattern.matrix(self.system.pattern.assemble(k_list))
            probe = np.ones(kt.shape[0])  # a singular factor shows here, not in the next direction
            fac = Factorization(
                kt, symmetric=self.settings.symmetric_tangent, backend=self.settings.backend, lagged=True
            )
            error = _norm(kt @ fac.solve(probe) - probe)
            self.result.factorizations += 1
        except (FloatingPointError, RuntimeError):
            if probe is None:
                return False
            error = np.inf
        if not error <= TANGENT_SOLVE_TOL * _norm(probe) and self.settings.symmetric_tangent:
            fac, error = self._regularised(k_list, probe)  # a singular symmetric tangent: its shifted copy
        # a factor that does not solve its own matrix is not used (the old one is kept): e.g. a strip whose
        # contact points all slip (psi_i = 0: no tangential stiffness) or open has a singular tangent along
        # its horizontal translation, and SuperLU returns finite garbage (zoo scenes 1, 12, 24, 48, 58, 97
        # stopped at lambda = 0 on such directions; all complete with the check)
        if not error <= TANGENT_SOLVE_TOL * _norm(probe):
            return False
        self.fac = fac
        return True

    def _regularised(self, k_list, probe):
        """(factor, solve error) of K_t + ``SINGULAR_SHIFT`` diag(K0), the operator where a symmetric
        consistent tangent is singular; (None, inf) if it cannot be factorised.

        Measured (tools/path_spectrum.py, issue 31): Davis-mode zoo scenes 62 and 66 stopped on a plateau
        (f . K_t^-1 f 2 800 and 1 200 times its elastic value) where K_t had an eigenvalue 2e-13 and 5e-14 of
        its largest, its mode on one soil-surface node beside the footing (cohesionless top layer, contact
        points open there): a node without stiffness, not a fold or a bifurcation of the path. The old factor
        kept, the iterations stagnated; the shifted copy, a quasi-Newton operator that errs by 1e-6 of K0 on
        the other modes, carries both to their peak (limits 0.3142 and 0.5078). Only for symmetric tangents:
        with the user's non-associated laws the singular direction is a strip sliding on slipping contact
        (psi_i = 0), a real mechanism, and the shifted operator sent scene 24 sideways at lambda = 0 (kept
        factor: completed). The 100 random zoo scenes (seed 1) in Davis mode: completed / limit /
        NonConvergence 61 / 36 / 3 -> 61 / 38 / 1, none lost; of the 36 limits 33 moved by <= 0.31 %, three
        by more, all upward where the path no longer stalls on its slowly rising plateau (scenes 42 +0.53 %,
        3 +0.68 %, 78 +0.77 %; a shift of 1e-9 moved them further, +1.2 % on 42 and 78)."""
        pattern = self.system.pattern
        if self._k0_diag is None:  # K0's diagonal as values of the tangent's pattern (its ordering is kept)
            k0 = pattern.matrix(pattern.assemble_elastic(self.model.groups))
            rows = np.repeat(np.arange(k0.shape[0]), np.diff(k0.indptr))
            self._k0_diag = np.where(rows == k0.indices, k0.data, 0.0)
        kt = pattern.matrix(pattern.assemble(k_list) + SINGULAR_SHIFT * self._k0_diag)
        try:
            fac = Factorization(
                kt, symmetric=self.settings.symmetric_tangent, backend=self.settings.backend, lagged=True
            )
            error = _norm(kt @ fac.solve(probe) - probe)
        except (FloatingPointError, RuntimeError):
            return None, np.inf
        self.result.factorizations += 1
        return fac, error

    def _line_search(self, u, u_n, states_n, lam, du, dlam, r_f):
        """Step t along (du, dlam). On a factor of an unsymmetric consistent tangent: t = 1, 1/2, ... down
        to ``LINE_SEARCH_MIN``, the first whose residual norm is below the current one -- a Newton direction
        lowers |r|^2 whatever the tangent's symmetry. Otherwise (a symmetric tangent,
        ``Settings.symmetric_tangent``, or K0), and when no such t exists: Matthies & Strang's
        G(t) = du . r(u + t du, lambda + t dlam) ~ 0, t = 1 if |G(1)| <= |G(0)| / 2, else up to three
        secant / regula-falsi trials in [0.05, 4].

        Why both: G is the slope of a potential only for associated laws; with the slipping (psi = 0)
        contact and the non-associated soil of the random zoo it took steps whose residual grew, and the
        iterations cycled between slip, stick and open states. The norm rule alone stalls where chapter
        11's RC strip cracks (h = 0.125 m: NonConvergence at lambda = 0.394, |r| at 4.5e-4 with no t down
        to 1/64 lowering it, no soil or contact point changing state); the strip's direction is taken
        along G there.

        Measured where the controlled run failed at 3a5ff09, G's root always taken (chapter 11 at h = 0.125 m,
        10 targets; the run and four copies with the column load x (1 + eps), eps = +-1e-13, +-1e-12: 3 of the
        5 complete, with 2-6 failed steps, and the others stop in NonConvergence at lambda = 0.9407 and 0.8678
        -- bench key ch11_h0125_controlled_roundoff): the failed steps are corrector failures at kinks of the
        residual, not steps too long. (a) Where the strip first cracks (lambda ~ 0.39, 78 layer points at mid-
        strip) the iterations pass only by the root's extrapolation (t up to 4): with t <= 1 all 5 runs stop
        there, and so does the unperturbed run taking the trial of least |r| in place of the root. (b) At
        lambda = 0.9407 the iterations settle into an exact cycle of 8 in which 10 cracked layer points switch
        between loading on the softening envelope and secant unloading, |r| between 7e1 and 1.6e3 N (relative
        ~1e-4), a t = 4 step part of the cycle. (c) After such a step |r| grew 10-300 times, up to 400 soil
        points changing state, the step ending at the load-factor correction cap.

        Hence ``G_GROWTH``: the root is taken only if it raises |r| less than 10 times (see the constant for
        why not 30). As measured by crack8 against no rule: chapter 11 at h = 0.25
        m (and its four copies): 1 failed step -> 0 (tests/test_path_kinks.py); at h = 0.125 m 3 -> 4 of the 5
        complete (2-7 failed steps; the -1e-12 copy stops at 0.8704); chapter 13's graded h/4 copy
        (controlled) stops at lambda = 0.903 instead of 0.735, 46 soil points switching between elastic and
        plastic; the 100 random zoo scenes (seed 1) completed / limit / NonConvergence 57 / 31 / 12 -> 60 / 30
        / 10: scenes 46, 50, 82 now complete, scene 30 (a peak at 0.9449 before) stops at 0.9425 just below
        it, the 30 common limits move by <= 0.071 %. A growth of 3 stops chapter 11 at h = 0.125 m where it
        first cracks (5 of 5); 30 leaves chapter 11 as at 3a5ff09 (3 of 5 complete) and ends zoo scenes 30,
        46, 50, 82 at a limit 0.9468, a limit 0.9850, completed, completed; 100 stops scenes 30, 46 and 82.
        Also measured and rejected (crack8): t <= 1 for the root (0 of 5 complete), refactorising after each
        step taken along G (2 of 5, 9 and 12 failed steps), the tangent of the rejected full step (0 of 5:
        lambda = 0.414), the plate's K0 in the tangent (the unperturbed run: NonConvergence at 0.437). A
        secant modulus in place of the concrete's negative tangent on its softening envelope (tried in the
        law, not kept: the law is not this module's) with growths 3 and 10 here: 5 of 5 complete at h = 0.125
        m, 4 and 3 of them without a failed step in ~2 s; the failed steps left are soil points switching
        between elastic and plastic. That secant is now the tangent flag SECANT_SOFTENING, which the
        corrector asks for by ``SECANT_RULE`` (measured there; not the default)."""
        free = self.system.free
        g0 = float(du @ r_f)
        r0 = _norm(r_f)

        def trial(t):
            v = u.copy()
            v[free] += t * du
            lt = lam + t * dlam
            self.system.apply_constraints(v, lt)
            ev = self._evaluate(v, u_n, states_n, lt)
            return v, lt, ev, (np.inf if ev is None else float(du @ ev[2][free]))

        def norm(cand):
            return np.inf if cand[2] is None else _norm(cand[2][2][free])

        t = 1.0
        best = trial(t)
        if not self.settings.line_search:
            return best[0], best[1], best[2], t
        if self.fac is not self.k0 and not self.settings.symmetric_tangent:
            tried = [(norm(best), t, best)]
            while not norm(best) < r0 and t > LINE_SEARCH_MIN:
                t *= 0.5
                best = trial(t)
                tried.append((norm(best), t, best))
            if norm(best) < r0:
                return best[0], best[1], best[2], t
            # no step lowers |r|: Matthies & Strang's root, unless it raises |r| G_GROWTH times or more
            root, t_root, _, _ = self._g_root(tried[0][2], 1.0, g0, trial)
            if norm(root) < self.g_growth * r0:
                return root[0], root[1], root[2], t_root
            _, t, best = min(tried, key=lambda row: row[0])  # the trial of least |r| instead
            return best[0], best[1], best[2], t
        best, t, t_lo, g_lo = self._g_root(best, t, g0, trial)
        if self.settings.symmetric_tangent and norm(best) > r0 and (best[2] is None or best[3] < 0.0):
            t, best = _overshoot(trial, norm, r0, g0, t_lo, g_lo, t, best)
        return best[0], best[1], best[2], t

    @staticmethod
    def _g_root(best, t, g0, trial):
        """Matthies & Strang's root of G = du . r from the trial ``best`` at ``t`` (a ``trial`` tuple (u,
        lambda, evaluation, G)): up to three secant / regula-falsi trials in [0.05, 4]; (trial, t, t_lo,
        g_lo), the last two the bracket's lower end, where G > 0 (``_overshoot`` narrows it)."""
        t_lo, g_lo = 0.0, g0
        for _ in range(3 if g0 > 0.0 else 0):
            g = best[3]
            if best[2] is not None and abs(g) <= 0.5 * g0:
                break
            if best[2] is None or not np.isfinite(g):
                t_new = 0.5 * (t_lo + t)
            elif g < 0.0:
                t_new = t - g * (t - t_lo) / (g - g_lo)
            else:
                t_lo, g_lo = t, g
                t_new = 2.0 * t
            t_new = min(max(t_new, 0.05), 4.0)
            if t_new == t:
                break
            t, best = t_new, trial(t_new)
        return best, t, t_lo, g_lo


def _overshoot(trial, norm, r0, g0, t_lo, g_lo, t, best):
    """(t, trial) below Matthies & Strang's smallest step 0.05 where their search overshot: G(t) < 0 (the
    potential's minimum along the direction lies below t) or the update failed, and the residual grew.

    Why: a direction through a nearly singular tangent is long -- on chapter 19's pushed strip (Tresca soil,
    smooth side walls whose kn is 1e3 times the soil's stiffness) 0.7 m for a push of 2.5 mm, the soil beside
    an opening wall having no stiffness left -- and t = 0.05 of it drives the wall nodes centimetres into
    their contact: the residual grew 1e2-1e5 times in a step and the path stopped at lambda = 0. Regula falsi
    on G over the bracket [t_lo (G > 0), t (G < 0 or failed)], bisection where the update failed, for up to
    ``OVERSHOOT_TRIALS`` trials down to ``OVERSHOOT_MIN``, until |G| <= G(0) / 2; else the largest trial
    with G > 0 (the potential, convex along the line, falls all the way to it), or, without one, the trial
    of the smallest residual (the corrector's divergence and stagnation tests then judge the step).
    Stopping at the first trial whose residual fell below the current one instead crept by t ~ 0.003 where
    the potential has a kink (a contact changing state along the line) and stopped Davis-mode zoo scene 74
    at lambda = 0.

    Only for symmetric tangents (``Settings.symmetric_tangent``, Davis mode, ``associated`` models): there G
    is the slope of the increment's convex potential and its root brackets the potential's minimum. Without
    that gate the user-flow random zoo (seed 1; no scene associated) changed where the K0 steps' search
    overshot: of its first 31 scenes, 30's limit 0.9477 became a NonConvergence at lambda = 0.943 and the
    limits of 3, 8, 11, 13, 17 moved by up to 0.12 %."""
    t_hi, hi = t, best
    smallest = (norm(best), t, best)
    below = None  # the largest trial with G > 0
    for _ in range(OVERSHOOT_TRIALS):
        g_hi = hi[3]
        if hi[2] is None or not np.isfinite(g_hi):
            t_new = 0.5 * (t_lo + t_hi)
        else:
            t_new = t_hi - g_hi * (t_hi - t_lo) / (g_hi - g_lo)
        # strictly inside the bracket, away from its ends (regula falsi stalls at one end otherwise)
        t_new = min(max(t_new, t_lo + 0.05 * (t_hi - t_lo), OVERSHOOT_MIN), t_lo + 0.95 * (t_hi - t_lo))
        if not t_lo < t_new < t_hi:
            break
        cand = trial(t_new)
        if norm(cand) < smallest[0]:
            smallest = (norm(cand), t_new, cand)
        if cand[2] is not None and abs(cand[3]) <= 0.5 * g0:
            return t_new, cand
        if cand[2] is not None and cand[3] > 0.0:
            t_lo, g_lo, below = t_new, cand[3], (t_new, cand)
        else:
            t_hi, hi = t_new, cand
    return below if below is not None else smallest[1:]


def _diag(d):
    return sp.diags(d, format="csc")
