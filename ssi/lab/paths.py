"""Where the project keeps its inputs and outputs, and the fast/full switch.

``SSI_FAST=1`` (set by ``make test`` and CI) makes chapters use coarse meshes; ``make reproduce`` runs the
full meshes. ``SSI_ROOT`` overrides the project root (default: the folder above the installed package).
"""

import os
from pathlib import Path

ROOT = Path(os.environ.get("SSI_ROOT", Path(__file__).resolve().parents[2]))
FIGURES = ROOT / "figures"
RESULTS = ROOT / "results"
REFERENCE_DATA = ROOT / "reference_data"
FAST = os.environ.get("SSI_FAST", "0") not in ("", "0", "false", "False")
