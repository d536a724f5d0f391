"""The load a foundation carries and its capacity, read off a solved scene: the part of
:class:`~ssi.scene.view.SceneResult` that follows the load path (column load, the foundation's load of a
push-over, equilibrium rows, the capacity and how it was found, the load-settlement curve), and the warning
a capacity's error estimate gives."""

from __future__ import annotations

import numpy as np

from .parts import load_history

# a push-over's path counts as on its plateau when its last increment's stiffness dP/ds is below this share
# of its first increment's: a formed mechanism has (nearly) zero stiffness. 2 % is a choice, not a measured
# constant; capacity() says which criterion it applied, and the tests check a push that reaches its plateau
PLATEAU_STIFFNESS_SHARE = 0.02
# a capacity whose estimated discretisation error (ssi.scene.estimate) exceeds this share of it carries a
# warning: issue 34's threshold, a choice (not a measured constant) that capacity()'s warning states
CAPACITY_ERROR_LIMIT = 0.05


class LoadPathView:
    """Mixin of :class:`~ssi.scene.view.SceneResult` (its ``built``, ``solver_result`` and the step
    accessors): the load path and the capacity."""

    # ---- the load a foundation carries and its capacity (issue 34) ----------------------------------------
    @property
    def is_push_over(self) -> bool:
        """The scene is driven by a prescribed :class:`Settlement` or :class:`Push` (in ``scene.loads`` or a
        phase): its load is the reaction the soil gives, not a given force."""
        return any(ld.drives for ld in self._all_loads())

    @property
    def is_horizontal_push(self) -> bool:
        """The scene is driven by a :class:`Push`: its load is the horizontal reaction, its displacement the
        foundation's horizontal one."""
        return any(ld.drives == "horizontal" for ld in self._all_loads())

    def _push_direction(self) -> float:
        """+1 or -1: the sign of the first Push's u (the direction a horizontal push-over reports in)."""
        return 1.0 if next(ld for ld in self._all_loads() if ld.drives == "horizontal").u >= 0.0 else -1.0

    def _all_loads(self) -> list:
        return list(self.built.scene.loads) + [ld for ph in self.built.scene.phases for ld in ph.loads]

    def column_load(self) -> np.ndarray:
        """(n_steps + 1,) total column force sum N [N/m] applied at every row: lambda * sum N of a
        single-phase scene; of a phased scene the columns of every phase so far, each scaled by its phase
        factor, the running phase's ramped by its load factor (zero in the geostatic phase)."""
        lam = np.asarray(self.load_factor, np.float64)

        def total(loads):
            return float(sum(n for ld in loads for _, n in ld.columns()))

        if not self.phases:
            return lam * total(self.built.scene.loads)
        return load_history(self.built.scene.load_phases(), self.phases, len(lam), total)

    def foundation_load(self) -> np.ndarray:
        """(n_steps + 1,) vertical load [N/m] the foundation carries at every row (downwards positive, per
        metre of strip; of a symmetric scene the whole foundation's). Of a push-over (:attr:`is_push_over`)
        the soil's reaction: a RigidFooting's base reaction, or the contact resultant of a plate strip
        (:meth:`BuiltScene.contact_force`); of a load-controlled scene the applied column load
        (:meth:`column_load`). Of a horizontal push-over (:attr:`is_horizontal_push`) the horizontal force
        [N/m] at the pushed nodes (:meth:`BuiltScene.push_force`) in the direction of the first Push's u
        (> 0: resisting the push). Rows that are not
        rate-independent equilibria are included: see :meth:`load_settlement`'s ``equilibrium`` mask."""
        if not self.is_push_over:
            return self.column_load()
        if self.is_horizontal_push:
            return self._push_direction() * self.built.push_force(self)
        if self.built.footing_nodes is None:
            return self.built.contact_force(self)
        if not self.phases:
            return self.built.contact_force(self)
        # a phased push of a RigidFooting: each phase's own reaction record (its loads are its own)
        whole = 2.0 if self.built.scene.symmetric else 1.0
        out = np.zeros(len(self.load_factor))
        for record in self.phases:
            reaction = -whole * record["result"].support_reaction(self.built.footing_nodes, "w")
            first = max(record["first"] - 1, 0) if record is not self.phases[0] else 0
            out[first : first + len(reaction)] = reaction
        return out

    def equilibrium_rows(self) -> np.ndarray:
        """(n_steps + 1,) bool: rows that are equilibrium states of the rate-independent laws (False: a
        viscous state, solved with a group's own Duvaut-Lions viscosity, which carries overstress the material
        cannot; see
        :meth:`ssi.core.solution.Result.rate_independent_steps`)."""
        mask = np.zeros(len(self.load_factor), bool)
        visc = np.asarray(self.solver_result.step_viscosity, np.float64)
        if len(visc) == len(mask):
            mask[:] = visc == 0.0
        else:  # a record without per-row viscosity: every row counts, as it did when written
            mask[:] = True
        return mask

    def capacity(self) -> dict:
        """The largest load the foundation carried and how it was found (only rate-independent equilibrium
        rows count). Keys: ``load`` [N/m] (:meth:`foundation_load` at ``step``), ``settlement`` [m] there,
        ``step``, ``is_limit`` (True when the path shows a limit: a peak, a plateau or a limit the solver
        found; False: the largest load carried, no limit found), ``how`` (a sentence), ``viscous_rows``
        (rows left out), ``estimate`` (the capacity's estimated discretisation error,
        :attr:`capacity_error`, or None when not estimated) and
        ``warning`` (a sentence when that estimated error exceeds ``CAPACITY_ERROR_LIMIT`` of the load or
        could not be extrapolated, else None).

        How: a run the solver stopped (a NonConvergence's partial result): the largest load it carried, no
        limit. A run whose controlled path peaked (the solver's limit load, ``status == "limit load
        reached"``): that load, how the solver found it. A scene under column loads that completed: its full
        load, no limit found. A push-over that completed: the peak of the
        path if the load falls after it by more than 1 %; a plateau if the last increment's stiffness dP/ds is
        below ``PLATEAU_STIFFNESS_SHARE`` of the first's; else the largest carried load, no limit found."""
        path = self.load_settlement()
        load, settle, ok = path["load"], path["settlement"], path["equilibrium"]
        rows = np.flatnonzero(ok)
        i = int(rows[np.argmax(load[rows])])
        out = {
            "load": float(load[i]),
            "settlement": float(settle[i]),
            "step": i,
            "viscous_rows": int((~ok).sum()),
            "estimate": self.capacity_error,
            "warning": capacity_error_warning(self.capacity_error),
        }
        if self.status == "stopped":  # a NonConvergence's partial path: what it carried, no more
            return out | {
                "is_limit": False,
                "how": "largest load carried before the solver stopped (a solver failure, not a limit)",
            }
        if self.status == "limit load reached":  # only the controlled path finds one: its definition is the
            # one used (a push-over's own rules below are for paths that completed or were load-controlled)
            how = f"limit load detected by the solver ({self.solver_result.limit_evidence})"
            return out | {"is_limit": True, "how": how}
        if not self.is_push_over:
            return out | {"is_limit": False, "how": "largest carried load: the full load, no limit found"}
        after = load[rows[rows > i]]
        if after.size and after.min() < 0.99 * load[i]:
            return out | {
                "is_limit": True,
                "how": "peak of the load-settlement path: the load falls after it",
            }
        if len(rows) >= 3:
            ds = np.diff(settle[rows])
            dp = np.diff(load[rows])
            moving = np.abs(ds) > 1e-9 * np.abs(settle[rows]).max()  # beyond round-off of the displacement
            if self.is_horizontal_push and moving.any():
                # a push in a later phase: the rows before it do not move the strip sideways (ds: round-off);
                # the path's first stiffness is that of the push's first increment
                start = int(np.flatnonzero(moving)[0])
                ds, dp = ds[start:], dp[start:]
            first, last = dp[0] / ds[0] if ds[0] else np.inf, dp[-1] / ds[-1] if ds[-1] else np.inf
            if np.isfinite(first) and first > 0 and last < PLATEAU_STIFFNESS_SHARE * first:
                return out | {
                    "is_limit": True,
                    "how": (
                        f"plateau of the load-settlement path: last stiffness {last / first:.1%} of the first"
                    ),
                }
        return out | {"is_limit": False, "how": "largest carried load, no limit found: the load still rises"}

    def load_settlement(self) -> dict[str, np.ndarray]:
        """The load--settlement path over every converged step (also of a stopped run): ``load_factor``
        (n_steps + 1,) [-] (of a phased scene the phase time), ``column_load`` (n_steps + 1,) [N/m] (see
        :meth:`column_load`), ``load`` [N/m] the load the foundation carries (:meth:`foundation_load`: of a
        push-over the soil's reaction), ``settlement`` (n_steps + 1,) [m] the largest settlement at each step
        (positive down; of a horizontal push-over the pushed nodes' mean horizontal displacement in the push's
        direction) and ``equilibrium`` (n_steps + 1,) bool: the row is a rate-independent equilibrium
        (:meth:`equilibrium_rows`; False rows are never a result)."""
        lam = np.asarray(self.load_factor, np.float64)
        if self.is_horizontal_push:
            dofs = self.built.model.dof(self.built.pushed_nodes(), "u")
            settle = self._push_direction() * np.array([float(np.mean(u[dofs])) for u in self.u])
        else:
            settle = np.array([self.max_settlement(k)[1] for k in range(len(lam))])
        return {
            "load_factor": lam,
            "column_load": self.column_load(),
            "load": self.foundation_load(),
            "settlement": settle,
            "equilibrium": self.equilibrium_rows(),
        }


def capacity_error_warning(est: dict | None) -> str | None:
    """The warning a capacity carries when its estimated discretisation error ``est`` (see
    :attr:`SceneResult.capacity_error`) exceeds ``CAPACITY_ERROR_LIMIT`` or is not asymptotic; else None."""
    if est is None:
        return None
    rel = est["relative"]
    where = f"extrapolated {est['extrapolated'] / 1e3:.2f} kN/m"
    if rel > CAPACITY_ERROR_LIMIT:
        rough = "" if est["asymptotic"] else "; not in the asymptotic range, so the estimate itself is rough"
        return (
            f"the capacity's estimated discretisation error is {rel:.1%} (more than "
            f"{CAPACITY_ERROR_LIMIT:.0%}; {where}{rough}): refine the mesh before using it"
        )
    if not est["asymptotic"]:
        return (
            f"the capacity's error estimate ({rel:.1%}) is not reliable: the refined answers are not in the "
            "asymptotic range (no observed order in the accepted range)"
        )
    return None
