"""Fingerprints of solved scenes: a sha1 of the final displacement vector ``u`` of each, to show that a change
which must not touch arithmetic (a move of files, a rename, a split of a module) leaves every result bit for
bit the same.

    python tools/result_hashes.py > before.txt
    ... change the code ...
    python tools/result_hashes.py > after.txt && diff before.txt after.txt

The scenes: chapter 11's foundation beam (``chapter11_foundation(0.5)``, the chapter's fast-mode mesh) solved
with the default ``Settings()`` and with full Newton in ten steps (the chapter's comparison), and the zoo
scenes 0, 3, 20, 21, 37, 50, 66 and 91 of ``random_scenes(100, seed=1)`` (chapter 06's full-mode zoo) with the
default settings. A scene that stops (``NonConvergence``) is hashed at its last converged state, so a change
in where it stops shows too. Each line: name, solver status, number of DOFs, sha1 of the float64 bytes of u.
"""

import hashlib
import sys

import numpy as np

import ssi  # noqa: F401  (first: keys numba's cache before numba is imported)
from ssi.lab.examples import chapter11_foundation
from ssi.lab.zoo import random_scenes
from ssi.solver import NonConvergence, Settings

ZOO = (0, 3, 20, 21, 37, 50, 66, 91)


def fingerprint(u: np.ndarray) -> str:
    """sha1 of the bytes of ``u`` as a C-contiguous float64 array."""
    return hashlib.sha1(np.ascontiguousarray(u, dtype=np.float64).tobytes()).hexdigest()


def solve_and_hash(name: str, scene, **solve_args) -> str:
    """One line: name, status, n_dof and the fingerprint of the last converged u."""
    built = scene.build()
    try:
        out = built.solve(**solve_args)
        status, u = out.status, out.u[-1]
    except NonConvergence as err:
        status, u = "failed", err.result.u[-1]
    return f"{name:24s} {status:20s} {built.model.n_dof:6d} {fingerprint(u)}"


def main() -> int:
    print(solve_and_hash("chapter11 default", chapter11_foundation(0.5)), flush=True)
    full = Settings(method="full")
    print(
        solve_and_hash("chapter11 full n=10", chapter11_foundation(0.5), n_steps=10, settings=full),
        flush=True,
    )
    zoo = random_scenes(100, seed=1)
    for i in ZOO:
        print(solve_and_hash(f"zoo {i}", zoo[i][1]), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
