"""The limit watch of the controlled path (:mod:`.path`): the WATCH rows of its state table (a peak passed, a
plateau), the half-size redo of the steps around the peak and the checks of a limit (mechanism certificate,
small strain). A mixin of ``path._Follower``: it reads the follower's ``model``, ``settings``, ``policy``,
``system``, ``result``, ``loads``, ``controls``, ``kept``, ``relaxed``, ``f_ref``, ``f_dead``, ``ref``,
``work``, ``bar`` and its ``_step``, ``_fail``, ``_above`` and ``_load_measure``. Why the rules are as they
are: ``docs/solver/decisions.md`` (#plateau, #no-limit-from-a-relaxed-state).
"""

from __future__ import annotations

import numpy as np

from ..core.solution import LIMIT_LOAD
from .mechanism import check_mechanism, flow_is_associated, increment_energy


class _LimitWatch:
    """Where the load measure peaked or levelled off, the limit and its checks (see the module docstring)."""

    def _limit(self) -> bool:
        """The WATCH rows of the state table; on a limit, the half-size redo and the checks."""
        p = np.asarray(self.loads)
        k_max = int(np.argmax(p))
        n = len(p) - 1
        if p[k_max] <= 0.0 or k_max == 0:
            return False
        on = np.flatnonzero(p >= p[k_max] / (1.0 + self.policy.plateau_rise))[0]  # where the plateau began
        s = np.asarray(self.controls) - self.controls[0]
        continued = (
            s[on] > 0.0
            and s[-1] - s[on] >= self.policy.plateau_control * s[on]
            and n - on >= self.policy.plateau_steps
        )
        below = p[-1] < (1.0 - self.policy.plateau_rise) * p[k_max]
        fell = below and (n - k_max >= self.policy.fall_steps or continued)
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
        if strain is not None and strain[0] > self.policy.small_strain * strain[1]:
            reasons.append(
                f"loaded displacement {strain[0]:.3g} m > {self.policy.small_strain:g} x the loaded width "
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
        """Relative change of the peak load when the kept steps from ``policy.redo_steps`` before the peak
        to as many after it are redone with each control increment split in two (None: a redo failed)."""
        kept = [
            row
            for row in self.kept
            if k_max - self.policy.redo_steps <= row[0] <= k_max + self.policy.redo_steps
        ]
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
