"""Benchmark of issue 15: throughput of ``ssi.studies.sweep`` on this machine.

Twenty-four scenes like chapter 14's (``ssi.lab.examples.chapter11_foundation`` on a coarse mesh: chapter 11's
section and its 400 kN/m per column -- until the shared factory this benchmark used the zoo's 7-layer RC strip
and 450 kN/m; the soft clay's E, c, tan phi varied) are solved serially in this process (the scene's own solve
time), then by a LocalCluster of 1 and of 2 worker processes (threads_per_worker=1). The cluster's start-up is
timed separately: it is paid once per sweep, not per scene. The numba cache is warm (a first scene is solved
before timing, and the workers load the same NUMBA_CACHE_DIR).

Prints ``key: value`` lines: ``sweep_scenes_per_min_1w``, ``sweep_scenes_per_min_2w`` (scenes per minute of
wall time from submission to the last result, cluster start excluded), ``sweep_overhead_per_task_s`` (1
worker: wall time per scene minus the serial solve time per scene), ``sweep_cluster_start_s`` and
``sweep_worker_memory_mb`` (largest resident memory of a worker after the sweep). Details go to stderr.
"""

import math
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from ssi.lab.examples import chapter11_foundation
from ssi.studies.sweep import _client, sweep

N_SCENES = 24


def foundation_on(E, c, tan_phi):
    """The chapter-11 foundation (400 kN/m per column), coarse, with the clay's E [Pa], c [Pa],
    tan(phi) [-]."""
    return chapter11_foundation(
        1.0, clay_E=E, clay_c=c, clay_phi_deg=math.degrees(math.atan(tan_phi)), h_coarse=4.0
    )


def parameters(offset):
    rng = np.random.default_rng(15 + offset)
    return [
        {"E": float(e), "c": float(c), "tan_phi": float(t)}
        for e, c, t in zip(
            rng.uniform(7e6, 14e6, N_SCENES),
            rng.uniform(14e3, 28e3, N_SCENES),
            rng.uniform(0.33, 0.40, N_SCENES),
        )
    ]


def worker_memory_mb(client):
    def rss():
        import resource

        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # kB on Linux

    return max(client.run(rss).values())


def main():
    foundation_on(10e6, 20e3, 0.364).build().solve()  # JIT cache warm in this process
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        serial = sweep(
            foundation_on, parameters(0), client="serial", out_dir=Path(tmp) / "serial", keep_files=False
        )
        serial_wall = time.perf_counter() - t0
        solve_per_scene = float(np.mean([r["wall_time"] for r in serial]))
        print(f"# serial: {serial_wall:.2f} s, solve {solve_per_scene:.3f} s per scene", file=sys.stderr)
        rates, memory = {}, {}
        for n in (1, 2):
            t0 = time.perf_counter()
            client, _ = _client(None, n)
            start = time.perf_counter() - t0
            sweep(
                foundation_on,
                parameters(100 + n)[:2],
                client=client,
                out_dir=Path(tmp) / f"warm{n}",
                keep_files=False,
            )  # each worker loads its numba cache
            t0 = time.perf_counter()
            rows = sweep(
                foundation_on, parameters(n), client=client, out_dir=Path(tmp) / f"w{n}", keep_files=False
            )
            wall = time.perf_counter() - t0
            memory[n] = worker_memory_mb(client)
            cluster = client.cluster
            client.close()
            cluster.close()
            failed = sum(r["status"] == "failed" for r in rows)
            rates[n] = (60.0 * N_SCENES / wall, wall, start, failed)
            print(
                f"# {n} worker(s): {wall:.2f} s for {N_SCENES} scenes, start {start:.2f} s, {failed} failed, "
                f"worker memory {memory[n]:.0f} MB",
                file=sys.stderr,
            )
        print(f"sweep_scenes_per_min_1w: {rates[1][0]:.1f}")
        print(f"sweep_scenes_per_min_2w: {rates[2][0]:.1f}")
        print(f"sweep_overhead_per_task_s: {rates[1][1] / N_SCENES - solve_per_scene:.3f}")
        print(f"sweep_cluster_start_s: {rates[2][2]:.2f}")
        print(f"sweep_worker_memory_mb: {max(memory.values()):.0f}")
        print(f"# serial solve per scene: {solve_per_scene:.3f} s", file=sys.stderr)


if __name__ == "__main__":
    main()
