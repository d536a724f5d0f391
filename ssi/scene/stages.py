"""The pieces of a staged analysis: the load levels of one phase, the run of one phase, the record of each,
the phases' rows joined into one result, and the error a failing phase raises.
"""

import numpy as np

from ..core.model import Model
from ..core.solution import Result
from ..solver import NonConvergence, run
from .view import SceneResult


def _load_levels(n_steps):
    """Target load factors of one phase: [1] (automatic increments) for None, else n equal levels."""
    if n_steps is None:
        return [1.0]
    if isinstance(n_steps, (int, np.integer)) and not isinstance(n_steps, bool) and n_steps >= 1:
        return np.linspace(0.0, 1.0, int(n_steps) + 1)[1:]
    raise ValueError(f"n_steps must be None (automatic) or an integer >= 1, got {n_steps!r}")


def _run_phase(model, load_factors, settings, start=None, loads=None):
    """The one place a phase is stepped: ``ssi.solver.run`` along ``load_factors`` from ``start`` (the last
    converged state of the previous phase) with F_ext = lambda f_ref + f_dead (``loads``)."""
    return run(model, load_factors, settings, start=start, loads=loads)


class PhaseNonConvergence(NonConvergence):
    """A phase of a phased solve did not converge. ``scene_result`` is a :class:`SceneResult` of every
    completed phase plus the failing phase's converged steps (its record's ``result`` has status "stopped";
    ``ssi.io.results.write_result`` writes it with ``stop=report``); ``result`` is the failing phase's partial
    solver result (as for any :class:`~ssi.solver.NonConvergence`); ``report`` is the solver's report with
    ``phase`` (the failing phase's name) and ``completed_phases`` ("name (steps first-last)") added."""

    def __init__(self, report: dict, result: Result, scene_result: "SceneResult") -> None:
        super().__init__(report, result)
        self.scene_result = scene_result
        solver = ", ".join(f"{k}={v}" for k, v in report.items() if k not in ("phase", "completed_phases"))
        done = ", ".join(report["completed_phases"]) or "none"
        text = f"phase {report['phase']!r} did not converge: {solver}; completed phases: {done}"
        self.args = (text + " (all in .scene_result)",)


def _phase_failure(built, err, name, records, view=SceneResult):
    """The PhaseNonConvergence of phase ``name`` from the solver's NonConvergence ``err``, with the completed
    phases' ``records``; ``view`` the result class of ``built`` (a scene's or a site's)."""
    partial = err.result
    records = records + [_phase_record(name, records, partial)]
    done = [f"{r['name']} (steps {r['first']}-{r['last']})" for r in records[:-1]]
    report = {"phase": name, "completed_phases": done, **err.report}
    result_view = view(built, join_phases(built.model, records), phases=records)
    return PhaseNonConvergence(report, partial, result_view)


def _phase_record(name, records, result):
    """The record of a phase solved after ``records``: its rows follow theirs (its row 0 is their last)."""
    first = records[-1]["last"] + 1
    return {"name": name, "first": first, "last": first + result.n_steps - 1, "result": result}


def join_phases(model: Model, records: list[dict]) -> Result:
    """The one :class:`~ssi.core.solution.Result` of a phased solve from its phases' ``records`` (``name``,
    ``first``, ``last``, ``result``; the geostatic phase first): on the phase time (the geostatic phase's
    first and last rows at 0, phase i's rows at i - 1 + its load factor), each phase's rows after its first
    (its first is the previous phase's last); the per-row records come along, the counts and times are
    summed, the status and limit (shifted onto the phase time) are the last phase's. Its ``f_ref`` and
    ``f_dead`` are None: each phase has its own loads (``records[i]["result"]``)."""
    geo = records[0]["result"]
    rows = {
        "load_factor": [0.0, 0.0],
        **{key: [getattr(geo, key)[0], getattr(geo, key)[-1]] for key in Result.ROWS if key != "load_factor"},
    }
    for i, record in enumerate(records[1:]):
        res = record["result"]
        rows["load_factor"] += [i + v for v in res.load_factor[1:]]
        for key in Result.ROWS[1:]:  # states: every step's, or the last only, as the phases kept them
            rows[key] += getattr(res, key)[1:]
    last, i_last = records[-1]["result"], len(records) - 2

    def phase_time(value):  # a load factor of the last phase on the phase time
        return None if value is None else i_last + value

    return Result(
        model=model,
        **rows,
        cuts=sum(r["result"].cuts for r in records),
        relaxed_steps=sum(r["result"].relaxed_steps for r in records),
        relaxed_iterations=sum(r["result"].relaxed_iterations for r in records),
        relaxed_note=next((r["result"].relaxed_note for r in records if r["result"].relaxed_note), ""),
        wall_time=sum(r["result"].wall_time for r in records),
        factorizations=sum(r["result"].factorizations for r in records),
        status=last.status,
        limit_load_factor=phase_time(last.limit_load_factor),
        limit_evidence=last.limit_evidence,
        limit_uncertainty=last.limit_uncertainty,
        limit_suspect=last.limit_suspect,
        limit_mechanism=last.limit_mechanism,
        limit_stored_share=last.limit_stored_share,
        u_origin=geo.u_origin,
        f_int_origin=geo.f_int_origin,
    )


def _hold(model, dofs, start, increment):
    """Constrain ``dofs`` to start + lambda * increment during a phase (the model stores a DOF's fixed value
    and its prescribed reference apart; both are set here)."""
    model.hold_dofs(dofs, start, increment)


class PhaseLoads:
    """The loads of a phased solve as it goes, for a scene's phases and a site's alike (one place, so the two
    cannot drift apart): each phase's load effect (its force vector [N/m] and its held motions {dof: [m]}),
    the factor of every phase so far, and where each phase's held motions started. :meth:`begin` opens a
    phase and gives its end state, :meth:`end` closes it."""

    def __init__(self, n: int) -> None:
        self.n = n  # number of DOFs of the model
        self.effects: dict = {}  # phase name -> (force (n,) [N/m], {dof: held increment [m]})
        self.factors: dict = {}  # phase name -> its loads' factor now
        self.held_from: dict = {}  # phase name -> {dof: displacement [m] at that phase's first state}
        self.f_prev = np.zeros(n)  # the force of all loads at the end of the phase before [N/m]

    def begin(self, phase, force: np.ndarray, held: dict, u: np.ndarray):
        """Open ``phase`` (a :class:`~ssi.scene.parts.Phase`) whose loads make ``force`` and ``held`` from
        the state ``u`` (n,) [m]: its loads at factor 1, earlier phases' at its ``factors``. Returns (f_end
        (n,) [N/m] every phase's loads at their factors, dofs (k,) the prescribed DOFs, goal (k,) [m] their
        targets at the phase's end)."""
        self.effects[phase.name] = (force, held)
        self.factors[phase.name] = 1.0
        self.factors.update(phase.factors)
        for d in held:
            self.held_from.setdefault(phase.name, {})[d] = float(u[d])
        f_end = sum((self.factors[k] * self.effects[k][0] for k in self.effects), np.zeros(self.n))
        target = {}
        for k, start in self.held_from.items():
            for d, u0 in start.items():
                target[d] = target.get(d, u0) + self.factors[k] * self.effects[k][1][d]
        dofs = np.array(sorted(target), np.int64)
        return f_end, dofs, np.array([target[d] for d in dofs])

    def end(self, model, dofs, goal, f_end, records, name, res) -> bool:
        """Close phase ``name`` solved to ``res``: its prescribed DOFs held at their ``goal``, its end force
        the next phase's start, its record appended to ``records``. Returns True if the analysis ends here
        (the phase reached a limit load)."""
        _hold(model, dofs, goal, np.zeros(len(dofs)))
        self.f_prev = f_end
        records.append(_phase_record(name, records, res))
        return bool(res.collapsed)


def _held(parts):
    """The prescribed motions of a phase's load effects, summed per DOF."""
    held = {}
    for _, p in parts:
        for d, v in p.items():
            held[d] = held.get(d, 0.0) + v
    return held


def solve_site_phases(built, n_steps, settings):
    """A :class:`~ssi.scene.site.Site`'s phased solve (``built`` a BuiltSite): the geostatic phase (the
    initial stress, in equilibrium with the soil's weight: a check, its rows at phase time 0), then ``loads``
    (if any) as a first phase named "loads" and each of ``site.phases`` in turn, as a scene's
    (:meth:`~ssi.scene.built.BuiltScene.solve`): a phase adds its loads at full value at its end, rescales
    earlier phases' loads by its ``factors`` (0 removes them), its prescribed motions (a Push) held from
    the phase's first state. The weights (soil, strips' ``self_weight``) are dead loads in every phase, as
    in a single-phase site. A phase that reaches a limit load ends the analysis. Returns a SiteResult whose
    ``phases`` are the records (:func:`join_phases`)."""
    from .site_view import SiteResult

    site, model = built.site, built.model
    n = model.n_dof
    f_dead = model.load_vectors()[1]
    saved = model.constraint_state()
    model.fix_prescribed()  # the phases set every prescribed motion themselves
    try:
        res = _run_phase(model, [1.0], settings, loads=(np.zeros(n), f_dead))
        records = [{"name": "geostatic", "first": 0, "last": 1, "result": res}]
        book = PhaseLoads(n)
        for ph in site.load_phases():
            parts = [ld.effect(built) for ld in ph.loads]
            f_end, dofs, goal = book.begin(
                ph, sum((p[0] for p in parts), np.zeros(n)), _held(parts), res.u[-1]
            )
            now = res.u[-1][dofs]
            _hold(model, dofs, now, goal - now)
            f_prev = book.f_prev
            try:
                res = _run_phase(
                    model, _load_levels(ph.n_steps or n_steps), settings, start=res,
                    loads=(f_end - f_prev, f_dead + f_prev),
                )  # fmt: skip
            except NonConvergence as err:
                raise _phase_failure(built, err, ph.name, records, view=SiteResult) from err
            if book.end(model, dofs, goal, f_end, records, ph.name, res):
                break
    finally:
        model.restore_constraints(saved)
    return SiteResult(built, join_phases(model, records), phases=records)
