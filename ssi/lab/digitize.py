"""From a plot digitiser's CSV export to the project's reference-data format.

Measured curves that exist only as figures (e.g. Fig. 13a of the paper, from Yin Zong-Ze et al. 1995) are
added to ``reference_data/`` by digitising the figure. This module turns what a digitiser exports into a
reference CSV that the chapters read.

Input: a digitiser export
-------------------------
* **one curve**: two columns ``x,y`` (an optional text header line is skipped);
* **several curves** (WebPlotDigitizer "export all datasets"): a first row with the curve names, each over
  two columns, a second row ``X,Y,X,Y,...``, then the points; curves may have different lengths (blank
  cells at the end).

The numbers are either already in data units (the digitiser was calibrated) or **pixel coordinates**; then
give an :class:`AxisCalibration` per axis: two pixel positions with their known axis values (linear or
logarithmic axis), read off two labelled ticks of each axis.

Output: the reference CSV format
--------------------------------
Comment lines ``# key: value`` with the provenance keys of :data:`REQUIRED_META` (source, figure, units,
trust label A-D, uncertainty, how the numbers were obtained), then one header row of column names, then the
rows. :func:`read_reference` returns ``(meta, columns)``; a file with the header but no rows is an *empty
slot* (columns of length 0).

Command line::

    python -m ssi.lab.digitize export.csv out.csv --columns curve,tau_bar_kPa,displacement_mm \\
        --x-cal 112,0,598,60 --y-cal 410,0,52,5 --swap --meta-from reference_data/zongze1995_fig13a.csv

(``--x-cal px1,val1,px2,val2[,log]``; ``--swap`` when the figure's horizontal axis is the reference file's
second value column; ``--meta-from`` copies the provenance header of the empty slot and marks the trust
label C, hand-digitised.)
"""

import argparse
import csv
import io
import math
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..io.results import atomic_path

__all__ = [
    "REQUIRED_META",
    "AxisCalibration",
    "convert",
    "read_digitizer_csv",
    "read_reference",
    "write_reference",
]

REQUIRED_META = ("source", "figure", "units", "trust", "uncertainty", "how_obtained")
TRUST_LABELS = ("A", "B", "C", "D")


@dataclass(frozen=True)
class AxisCalibration:
    """Map pixel positions to axis values from two reference ticks: pixel ``px1`` shows ``val1``, ``px2``
    shows ``val2``; ``log=True`` for a logarithmic axis (values > 0)."""

    px1: float
    val1: float
    px2: float
    val2: float
    log: bool = False

    def __post_init__(self):
        if not all(math.isfinite(v) for v in (self.px1, self.val1, self.px2, self.val2)):
            raise ValueError("calibration: px1, val1, px2, val2 must be finite numbers")
        if self.px1 == self.px2:
            raise ValueError(f"calibration: px1 and px2 must differ (got both {self.px1})")
        if self.val1 == self.val2:
            raise ValueError(f"calibration: val1 and val2 must differ (got both {self.val1})")
        if self.log and (self.val1 <= 0 or self.val2 <= 0):
            raise ValueError("calibration: a logarithmic axis needs val1 > 0 and val2 > 0")

    def __call__(self, px):
        px = np.asarray(px, dtype=np.float64)
        t = (px - self.px1) / (self.px2 - self.px1)
        if self.log:
            return 10.0 ** (math.log10(self.val1) + t * (math.log10(self.val2) - math.log10(self.val1)))
        return self.val1 + t * (self.val2 - self.val1)

    @classmethod
    def parse(cls, text: str) -> "AxisCalibration":
        """From ``"px1,val1,px2,val2"`` or ``"px1,val1,px2,val2,log"``."""
        parts = [p.strip() for p in text.split(",")]
        log = len(parts) == 5 and parts[4].lower() == "log"
        if len(parts) not in (4, 5) or (len(parts) == 5 and not log):
            raise ValueError(f"calibration must be 'px1,val1,px2,val2[,log]', got {text!r}")
        return cls(*(float(p) for p in parts[:4]), log=log)


def _text(src) -> str:
    """The CSV text of ``src``: a Path, a path string, or the CSV text itself (contains a newline)."""
    if isinstance(src, Path) or (isinstance(src, str) and "\n" not in src):
        path = Path(src)
        if not path.is_file():
            raise ValueError(f"digitiser export {str(src)!r} is not a file")
        return path.read_text(encoding="utf-8-sig")
    return str(src)


def _num(cell):
    try:
        return float(cell)
    except ValueError:
        return None


def read_digitizer_csv(src, name: str = "curve") -> dict[str, np.ndarray]:
    """Curves of a digitiser export (path or CSV text): ``{name: array (n, 2)}`` of raw (x, y) pairs.

    A plain two-column file gives one curve called ``name``."""
    rows = [r for r in csv.reader(io.StringIO(_text(src))) if any(c.strip() for c in r)]
    if not rows:
        raise ValueError("the digitiser export is empty")
    first_numeric = next((i for i, r in enumerate(rows) if _num(r[0]) is not None), None)
    if first_numeric is None:
        raise ValueError("the digitiser export has no numeric rows")
    head = rows[:first_numeric]
    data = rows[first_numeric:]
    width = max(len(r) for r in data)
    if width % 2:
        raise ValueError(f"expected (x, y) column pairs, found {width} columns")
    if width == 2:
        names = [name]
    else:
        if len(head) < 1:
            raise ValueError("a multi-curve export needs a first row with the curve names")
        names_row = head[0] + [""] * (width - len(head[0]))
        names = [names_row[2 * k].strip() or f"{name}{k + 1}" for k in range(width // 2)]
        if len(set(names)) != len(names):
            raise ValueError(f"curve names must be unique, got {names}")
    curves = {}
    for k, nm in enumerate(names):
        pts = []
        for r in data:
            cells = r[2 * k : 2 * k + 2] + ["", ""]
            x, y = _num(cells[0]) if cells[0].strip() else None, _num(cells[1]) if cells[1].strip() else None
            if x is None and y is None:
                continue
            if x is None or y is None:
                raise ValueError(f"curve {nm!r}: a point has only one coordinate ({cells[:2]})")
            pts.append((x, y))
        if not pts:
            raise ValueError(f"curve {nm!r} has no points")
        curves[nm] = np.array(pts)
    return curves


def source_commit(root, uncommitted_in: str | None = None) -> str:
    """The short hash of the git commit checked out at ``root``, for a reference file's ``how_obtained``;
    with ``uncommitted_in`` (a path inside ``root``, e.g. "ssi"), " + uncommitted <path>/ changes" is added
    when that path has changes the commit does not hold."""

    def git(*args):
        return subprocess.run(["git", "-C", str(root), *args], capture_output=True, text=True).stdout.strip()

    commit = git("rev-parse", "--short", "HEAD")
    if uncommitted_in is not None and git("status", "--porcelain", uncommitted_in):
        commit += f" + uncommitted {uncommitted_in}/ changes"
    return commit


def write_reference(path, meta: dict, columns: dict) -> None:
    """Write a reference CSV atomically: provenance comments, header row, rows. ``columns``: name -> sequence
    (equal lengths; may be empty for an empty slot)."""
    missing = [k for k in REQUIRED_META if not str(meta.get(k, "")).strip()]
    if missing:
        raise ValueError(f"meta is missing the provenance keys {missing} (required: {list(REQUIRED_META)})")
    if str(meta["trust"]).strip()[:1] not in TRUST_LABELS:
        raise ValueError(f"meta['trust'] must start with one of {TRUST_LABELS}, got {meta['trust']!r}")
    lengths = {len(v) for v in columns.values()}
    if len(lengths) > 1:
        raise ValueError(f"all columns must have the same length, got {sorted(lengths)}")
    lines = []
    for k, v in meta.items():
        for i, part in enumerate(str(v).splitlines() or [""]):
            lines.append(f"# {k}: {part}" if i == 0 else f"#   {part}")
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(list(columns))
    for row in zip(*columns.values(), strict=True):
        w.writerow([f"{v:.6g}" if isinstance(v, float | np.floating) else v for v in row])
    with atomic_path(path, overwrite=True) as tmp:  # a reader never sees half a file
        tmp.write_text("\n".join(lines) + "\n" + buf.getvalue(), encoding="utf-8")


def read_reference(path) -> tuple[dict, dict]:
    """``(meta, columns)`` of a reference CSV; numeric columns become float arrays, others string arrays.

    ``path``: a file, or the bare name of a file in ``reference_data/`` (``"janney1956_beam.csv"``). The one
    reader of the project's reference files: ``# key: value`` comment lines (continued by ``#   ``) give
    ``meta``, the first other line names the columns."""
    path = Path(path)
    if path.parent == Path(".") and not path.is_file():
        from . import paths

        path = paths.REFERENCE_DATA / path
    meta, body, last = {}, [], None
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("#"):
            text = line[1:].strip()
            if line.startswith("#   ") and last is not None:
                meta[last] += "\n" + text
            elif ":" in text:
                last, val = (s.strip() for s in text.split(":", 1))
                meta[last] = val
        elif line.strip():
            body.append(line)
    rows = list(csv.reader(body))
    if not rows:
        raise ValueError(f"{path}: no header row")
    names, data = rows[0], rows[1:]
    cols = {}
    for j, nm in enumerate(names):
        vals = [r[j] for r in data]
        nums = [_num(v) for v in vals]
        cols[nm] = np.array(nums, dtype=np.float64) if all(v is not None for v in nums) else np.array(vals)
    return meta, cols


def convert(
    src,
    dst,
    meta: dict,
    columns=("curve", "x", "y"),
    x_axis: AxisCalibration | None = None,
    y_axis: AxisCalibration | None = None,
    swap: bool = False,
    rename: dict | None = None,
    sort: bool = True,
) -> dict:
    """Convert a digitiser export ``src`` into the reference CSV ``dst``; returns the written columns.

    ``columns``: names of the (curve, first value, second value) columns of the reference file. The
    digitiser's x goes to the first value column unless ``swap``. ``x_axis``/``y_axis`` calibrate pixel
    coordinates (None: the export is already in data units). ``rename`` maps digitiser curve names to the
    reference names (e.g. ``{"Dataset 1": "point6"}``). ``sort`` orders each curve by its first value."""
    if len(columns) != 3:
        raise ValueError(f"columns must name (curve, value1, value2), got {columns!r}")
    curves = read_digitizer_csv(src)
    rename = rename or {}
    out_c, out_1, out_2 = [], [], []
    for nm, pts in curves.items():
        x = x_axis(pts[:, 0]) if x_axis is not None else pts[:, 0]
        y = y_axis(pts[:, 1]) if y_axis is not None else pts[:, 1]
        if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
            raise ValueError(f"curve {nm!r}: calibration produced non-finite values")
        v1, v2 = (y, x) if swap else (x, y)
        order = np.argsort(v1, kind="stable") if sort else np.arange(len(v1))
        out_c += [rename.get(nm, nm)] * len(v1)
        out_1 += list(v1[order])
        out_2 += list(v2[order])
    cols = {columns[0]: out_c, columns[1]: out_1, columns[2]: out_2}
    write_reference(dst, meta, cols)
    return cols


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m ssi.lab.digitize", description=__doc__.split("\n\n")[0])
    ap.add_argument("export", help="the digitiser's CSV export")
    ap.add_argument("output", help="reference CSV to write")
    ap.add_argument("--columns", default="curve,x,y", help="names of the curve and the two value columns")
    ap.add_argument("--x-cal", help="px1,val1,px2,val2[,log] for the horizontal axis (pixel exports)")
    ap.add_argument("--y-cal", help="px1,val1,px2,val2[,log] for the vertical axis (pixel exports)")
    ap.add_argument("--swap", action="store_true", help="the figure's x is the second value column")
    ap.add_argument("--rename", default="", help="old=new,old=new curve renames")
    ap.add_argument("--meta-from", help="copy provenance from this reference CSV (e.g. the empty slot)")
    for k in REQUIRED_META:
        ap.add_argument(f"--{k.replace('_', '-')}", default=None)
    a = ap.parse_args(argv)
    meta = dict(read_reference(a.meta_from)[0]) if a.meta_from else {}
    if a.meta_from:
        meta["trust"] = "C (hand-digitised from the figure)"
        meta["how_obtained"] = (
            f"digitised with a plot digitiser, converted by ssi.lab.digitize from {a.export}"
        )
    for k in REQUIRED_META:
        v = getattr(a, k)
        if v is not None:
            meta[k] = v
    rename = dict(p.split("=", 1) for p in a.rename.split(",") if p)
    cols = convert(
        a.export,
        a.output,
        meta,
        tuple(a.columns.split(",")),
        AxisCalibration.parse(a.x_cal) if a.x_cal else None,
        AxisCalibration.parse(a.y_cal) if a.y_cal else None,
        a.swap,
        rename,
    )
    print(
        f"wrote {len(next(iter(cols.values())))} points of {len(set(cols[a.columns.split(',')[0]]))} "
        f"curves to {a.output}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
