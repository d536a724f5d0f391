"""Render the executed chapter notebooks to an HTML book (mkdocs + mkdocs-jupyter) and check its equations.

    python tools/book.py build/notebooks build/book      # what `make book` runs after `make reproduce`

The notebooks are taken as they are (with their outputs and figures, as ``make reproduce`` left them; they
are not executed again). The site gets an index page listing the chapters by their titles. After the build,
:func:`check_html` reads every page and reports what would break the equations in a browser:

* MathJax is not loaded (a ``<script>`` whose ``src`` is empty or not a MathJax URL -- mkdocs-jupyter's
  default leaves it empty, so this script sets ``custom_mathjax_url``);
* TeX mangled by the Markdown converter: HTML tags (``<em>``, ``<strong>``...) inside a ``$...$`` or
  ``$$...$$`` span, i.e. underscores or asterisks read as emphasis;
* control characters inside a math span (``"\\bar"`` written without ``r""`` becomes a backspace + "ar");
* unbalanced braces in a math span.

It does not run MathJax itself (there is no headless browser on the build machine), so a TeX command that
MathJax does not know would pass this check.
"""

import html
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

MATHJAX_URL = "https://cdnjs.cloudflare.com/ajax/libs/mathjax/2.7.7/latest.js?config=TeX-AMS_CHTML-full,Safe"
_MATH = re.compile(r"\$\$(.+?)\$\$|(?<![\\$])\$(?!\$)(.+?)(?<![\\$])\$", re.DOTALL)
_TAG = re.compile(r"<(/?)(em|strong|i|b|code|a|span)\b[^>]*>")
_CONTROL = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f]")


def chapter_title(notebook: Path) -> str:
    """The first Markdown heading of a notebook, without the '#'."""
    nb = json.loads(notebook.read_text())
    for cell in nb["cells"]:
        if cell["cell_type"] == "markdown":
            for line in "".join(cell["source"]).splitlines():
                if line.startswith("#"):
                    return line.lstrip("#").strip()
    return notebook.stem


def prepare(notebooks: Path, source: Path) -> Path:
    """Copy the notebooks into ``source``/docs with an index page and write ``source``/mkdocs.yml."""
    docs = source / "docs"
    if source.exists():
        shutil.rmtree(source)
    docs.mkdir(parents=True)
    pages = sorted(Path(notebooks).glob("*.ipynb"))
    if not pages:
        raise FileNotFoundError(
            f"no notebooks in {notebooks}: run `make reproduce` (or `make notebooks`) first"
        )
    nav = ["  - Contents: index.md"]
    lines = ["# ssi: soil-structure interaction of RC shallow foundations", "", "Chapters:", ""]
    for nb in pages:
        shutil.copy2(nb, docs / nb.name)
        title = chapter_title(nb)
        nav.append(f"  - {json.dumps(title)}: {nb.name}")
        lines.append(f"- [{title}]({nb.name})")
    (docs / "index.md").write_text("\n".join(lines) + "\n")
    (source / "mkdocs.yml").write_text(
        "site_name: ssi\ndocs_dir: docs\nnav:\n" + "\n".join(nav) + "\nplugins:\n  - mkdocs-jupyter:\n"
        "      execute: false\n      cache: false\n      include_source: false\n"
        f'      custom_mathjax_url: "{MATHJAX_URL}"\n'
    )
    return source / "mkdocs.yml"


def build(notebooks, site, source=None) -> Path:
    """Build the HTML book from ``notebooks`` into ``site``; return the site folder."""
    site = Path(site).resolve()
    source = Path(source) if source else site.parent / (site.name + "_src")
    config = prepare(Path(notebooks), source)
    subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "-q", "-f", str(config), "-d", str(site)], check=True
    )
    return site


def check_page(text: str) -> list[str]:
    """Problems of one HTML page (see the module docstring); empty if its equations should render."""
    problems = []
    has_math = bool(_MATH.search(_body_text(text)))
    sources = re.findall(r"<script[^>]*\bsrc=\"([^\"]*)\"", text)
    if has_math and not any("mathjax" in s.lower() for s in sources):
        problems.append("math on the page but MathJax is not loaded (no <script src=...mathjax...>)")
    for m in _MATH.finditer(_body_text(text)):
        tex = m.group(1) if m.group(1) is not None else m.group(2)
        short = tex.strip()[:60]
        if _TAG.search(tex):
            problems.append(f"HTML tag inside math (TeX mangled by Markdown): {short!r}")
        if _CONTROL.search(html.unescape(tex)):
            problems.append(f"control character inside math (a LaTeX string without r''?): {short!r}")
        if tex.count("{") - tex.count("\\{") != tex.count("}") - tex.count("\\}"):
            problems.append(f"unbalanced braces in math: {short!r}")
    return problems


def _body_text(text):
    """The page's rendered cells: code blocks and scripts removed (a '$' in code is not math)."""
    text = re.sub(r"<script\b.*?</script>", "", text, flags=re.DOTALL)
    text = re.sub(r"<style\b.*?</style>", "", text, flags=re.DOTALL)
    return re.sub(r"<pre\b.*?</pre>", "", text, flags=re.DOTALL)


def check_html(site) -> dict:
    """{page: [problems]} for every page of the built site that has a problem."""
    out = {}
    for page in sorted(Path(site).rglob("*.html")):
        problems = check_page(page.read_text(errors="replace"))
        if problems:
            out[str(page.relative_to(site))] = problems
    return out


def main(argv=None) -> int:
    args = sys.argv[1:] if argv is None else argv
    notebooks, site = (Path(a) for a in (args + ["build/notebooks", "build/book"])[:2])
    site = build(notebooks, site)
    problems = check_html(site)
    for page, items in problems.items():
        for p in items:
            print(f"{page}: {p}")
    n_pages = len(list(site.rglob("*.html")))
    print(
        f"book: {site}/index.html ({n_pages} pages); equation check: "
        + ("OK" if not problems else f"{sum(map(len, problems.values()))} problems")
    )
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
