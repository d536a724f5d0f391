"""Draw the README's figures into docs/ (committed, so a fresh clone shows them; `make reproduce` is not
needed): the strip forces of examples/rc_strip.toml and the load-settlement path of
examples/pushover_footing.toml, each redrawn from its result file as a user would (``ssi run``, then
``read_result`` and one ``ssi.io.plot`` call). Run after a change to these examples or to the plots:

    .venv/bin/python tools/readme_figures.py
"""

import shutil
import sys
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

from ssi.io import plot  # noqa: E402
from ssi.io.cli import run_scene_file  # noqa: E402
from ssi.io.results import atomic_path, read_result  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
FIGURES = {  # README image -> (example, plot function)
    "readme_rc_strip_forces.png": ("rc_strip", plot.strip_forces),
    "readme_pushover_load_settlement.png": ("pushover_footing", plot.load_settlement),
}


def main() -> int:
    with tempfile.TemporaryDirectory() as tmp:
        for name, (example, draw) in FIGURES.items():
            scene = Path(tmp) / f"{example}.toml"
            shutil.copy2(ROOT / "examples" / f"{example}.toml", scene)
            run_scene_file(scene, figures=False)
            fig = draw(read_result(scene.with_suffix(".h5")))
            with atomic_path(DOCS / name, overwrite=True) as out:
                fig.savefig(out, dpi=90, format="png")
            print(f"wrote {DOCS / name}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
