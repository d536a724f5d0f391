"""Fail if a source file holds a control byte (< 0x20) other than newline and tab.

Such bytes come from a LaTeX command eaten as a string escape (``\\b`` in ``\\bar``, ``\\f`` in ``\\frac``
written into a non-raw string) and make an equation render broken. ``make lint`` runs this over
``chapters/`` and ``ssi/``: ``python tools/check_control_chars.py [folder ...]``.
"""

import sys
from pathlib import Path

ALLOWED = {0x09, 0x0A}  # tab, newline
DEFAULT_FOLDERS = ("chapters", "ssi")


def control_bytes(path: Path) -> list[tuple[int, int]]:
    """(line number, byte value) of every disallowed control byte in ``path``."""
    data = path.read_bytes()
    found, line = [], 1
    for byte in data:
        if byte == 0x0A:
            line += 1
        elif byte < 0x20 and byte not in ALLOWED:
            found.append((line, byte))
    return found


def main(folders: list[str]) -> int:
    bad = 0
    for folder in folders:
        for path in sorted(Path(folder).rglob("*.py")):
            for line, byte in control_bytes(path):
                print(f"{path}:{line}: control byte 0x{byte:02x} (a LaTeX escape eaten by a non-raw string?)")
                bad += 1
    print(f"control-character check: {bad} finding(s) in {', '.join(folders)}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:] or list(DEFAULT_FOLDERS)))
