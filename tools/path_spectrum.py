"""Why a random zoo scene's controlled path stops: the spectrum of its tangent (issue 31). Off-line.

    python tools/path_spectrum.py 22,31,66,80 [--flow davis] [--every 1]

For each scene (``random_scenes(100, seed=1)``) the controlled path (``Settings(control="work")``) is solved
with every committed state kept; then, at the committed steps (every ``--every``-th and the last):

* the sign of det K_t (K_t: the algorithmic tangent of the step, evaluated at its converged u from the
  previous committed state) and of the bordered determinant det K_t * (f . K_t^-1 f), and f . K_t^-1 f itself
  (the elastic-to-current ratio of d s / d lambda: a fold of the work control makes it change sign through
  infinity while det K_t keeps its sign; a bifurcation (K_t phi = 0 with f . psi = 0) changes det K_t and the
  bordered determinant together while f . K_t^-1 f stays finite);
* at the last committed state: the eigenvalues of K_t nearest zero and every real negative one, each with
  f . phi / |f| and f . psi / |f| (right and left eigenvectors, unit norm), the share of |phi|^2 on each
  group's DOFs, the three largest DOFs of phi, and the elements whose phi_e . K_e . phi_e is most negative
  with their points' codes;
* the smallest eigenvalue of K0 (the scale against which "small" is read).

Dense linear algebra (scipy.linalg.eig, numpy slogdet): meant for the zoo's 700-2 000 DOFs, a few minutes a
scene at ``--every 1``.
"""

import argparse

import numpy as np
import scipy.linalg as sla

from ssi.core.model import System
from ssi.core.protocol import CONSISTENT
from ssi.lab.zoo import random_scenes
from ssi.solver import NonConvergence, Settings
from ssi.solver.davis import davis_mode


def tangent(system, u, du, states):
    """The algorithmic tangent over the free DOFs (dense) and the element matrices."""
    _, k_list, _ = system.evaluate(u, du, states, CONSISTENT)
    return system.pattern.matrix(system.pattern.assemble(k_list)).toarray(), k_list


def group_share(model, system, vec):
    """Share of |vec|^2 on the DOFs each group touches (a DOF shared by groups counts for each)."""
    full = np.zeros(model.n_dof)
    full[system.free_dofs] = vec
    total = float(vec @ vec)
    return {
        g.name: round(float(full[np.unique(g.edofs)] @ full[np.unique(g.edofs)]) / total, 4)
        for g in model.groups
    }


def describe_mode(model, system, f, mu, phi, psi, k_list, states):
    phi = np.real(phi) / np.linalg.norm(np.real(phi))
    psi = np.real(psi) / np.linalg.norm(np.real(psi))
    nf = np.linalg.norm(f)
    top = np.argsort(-np.abs(phi))[:3]
    where = system.describe_dofs(top, 3).replace("unsupported DOFs: ", "")
    print(
        f"   mu {mu.real:+.4e}{mu.imag:+.1e}j  f.phi/|f| {float(f @ phi) / nf:+.3e}  "
        f"f.psi/|f| {float(f @ psi) / nf:+.3e}  share {group_share(model, system, phi)}"
    )
    print(f"      largest at {where}")
    full = np.zeros(model.n_dof)
    full[system.free_dofs] = phi
    for gi, g in enumerate(model.groups):
        ke = np.asarray(k_list[gi])
        if ke.ndim != 3:
            continue
        pe = full[g.edofs]
        energy = np.einsum("ei,eij,ej->e", pe, ke, pe)
        worst = np.argsort(energy)[:3]
        codes = g.point_codes(states[gi])
        info = "" if codes is None else [np.asarray(codes)[e].ravel().tolist() for e in worst]
        print(
            f"      {g.name}: phi.K.phi {energy.sum():+.3e}; most negative elements {worst.tolist()} "
            f"{np.round(energy[worst], 1).tolist()} point codes {info}"
        )


def diagnose(name, scene, flow, every):
    built = scene.build()
    model = built.model
    try:
        res = built.solve(settings=Settings(control="work", flow=flow, keep_states=True)).solver_result
        print(name, flow, "ended:", res.status)
    except NonConvergence as err:
        res = err.result
        print(name, flow, "NonConvergence:", str(err)[:300])
    with davis_mode(model, flow == "davis"):
        system = System(model)
        free = system.free
        f = res.f_ref[free]
        n = len(res.u) - 1
        print(f"  free DOFs {int(free.sum())}, committed steps {n}, last lambda {res.load_factor[-1]:.6g}")
        steps = list(range(1, n + 1, every))
        if steps[-1] != n:
            steps.append(n)
        before = None
        for k in steps:
            K, _ = tangent(system, res.u[k], res.u[k] - res.u[k - 1], res.states[k - 1])
            sign = np.linalg.slogdet(K)[0]
            fkf = float(f @ sla.lu_solve(sla.lu_factor(K), f))
            row = (sign, sign * np.sign(fkf))
            s = float(f @ (res.u[k][free] - res.u_origin[free]))
            if k in (steps[0], n) or row != before:
                mark = "  <- sign change" if before is not None and row != before else ""
                print(
                    f"  step {k:4d} lambda {res.load_factor[k]:.6f} s {s:.4e} sign det K {row[0]:+.0f} "
                    f"bordered {row[1]:+.0f} f.K^-1 f {fkf:.3e}{mark}"
                )
            before = row
        K, k_list = tangent(system, res.u[n], res.u[n] - res.u[n - 1], res.states[n - 1])
        w, vl, vr = sla.eig(K, left=True, right=True)
        scale = np.abs(w).max()
        print(f"  last committed state: |eigenvalue| max {scale:.3e}; nearest zero:")
        for j in np.argsort(np.abs(w))[:3]:
            describe_mode(model, system, f, w[j], vr[:, j], vl[:, j], k_list, res.states[n])
        negative = np.flatnonzero((w.real < 0) & (np.abs(w.imag) < 1e-9 * scale))
        print(f"  real negative eigenvalues: {negative.size}")
        for j in negative[np.argsort(w.real[negative])][:3]:
            describe_mode(model, system, f, w[j], vr[:, j], vl[:, j], k_list, res.states[n])
        k0 = system.pattern.matrix(system.pattern.assemble_elastic(model.groups)).toarray()
        print(f"  K0: smallest eigenvalue {np.linalg.eigvalsh(0.5 * (k0 + k0.T))[0]:.3e}")
        for gi, g in enumerate(model.groups):
            now = g.point_codes(res.states[n][gi])
            if now is None:
                continue
            now = np.asarray(now).ravel()
            was = np.asarray(g.point_codes(res.states[n - 1][gi])).ravel()
            counts = {nm: int((now == c).sum()) for c, nm in enumerate(g.point_code_names)}
            print(f"  {g.name}: point codes {counts}, changed in the last step {int((now != was).sum())}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scenes", help="comma-separated indices of random_scenes(100, seed=1)")
    ap.add_argument("--flow", default="user", choices=("user", "davis"))
    ap.add_argument("--every", type=int, default=1, help="det K sign every n-th committed step")
    args = ap.parse_args(argv)
    scenes = random_scenes(100, seed=1)
    for i in (int(v) for v in args.scenes.split(",")):
        diagnose(*scenes[i], args.flow, args.every)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
