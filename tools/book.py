"""Render the executed chapter notebooks to an HTML book that works offline, and check it.

    python tools/book.py build/notebooks build/book      # what `make book` runs after `make reproduce`
    python tools/book.py --execute build/notebooks build/book   # execute (SSI_FAST as set) what is not

The notebooks are taken as ``make reproduce`` left them, with their outputs and figures. A notebook that is
not executed (``make notebooks`` or ``make test`` leave the chapters as converted, without outputs), that
stopped at an error, or that makes figures but holds none (a kernel run with ``MPLBACKEND`` set to a
non-inline backend, which shows no figure), is refused with a message saying which and what to run;
``--execute`` runs such notebooks instead (in the mode ``SSI_FAST`` selects) and renders the result.

The book needs no network when read: the mkdocs Material theme without web fonts and without the search
plugin (whose worker cannot start from ``file://``), ``use_directory_urls: false`` (links point at ``.html``
files, not at folders, so the pages work from ``file://``), MathJax 3 copied into the site from the
``django-static-mathjax`` package (PyPI: MathJax's release files and nothing else, no dependency; so a
machine with Python alone builds the book, no Node, no CDN) with its SVG output (no font files), code
highlighted at build time by Pygments (no highlight.js), nbconvert's mermaid loader (a CDN import, for
diagrams no chapter has) removed, and wide tables in a horizontal scroller (``book_extra.css``).

After the build, :func:`check_html` reads every page and reports what would break it in a browser:

* a resource (script, style sheet, image, font) loaded from the network;
* math on a page that does not load the bundled MathJax;
* TeX mangled by the Markdown converter: HTML tags (``<em>``, ``<strong>``...) inside a ``$...$`` or
  ``$$...$$`` span, i.e. underscores or asterisks read as emphasis;
* control characters inside a math span (``"\\bar"`` written without ``r""`` becomes a backspace + "ar");
* unbalanced braces in a math span.

What only a browser can tell (the math typeset, every image decoded, no console error, the layout) is
checked with headless Chromium (``tools/browser.py``, offline) on every chapter page when Chromium is
installed (:func:`check_in_browser`; screenshots in ``build/browser/book/``), and on two chapters by
``tests/test_browser.py`` in ``make test``.
"""

import html
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

TOOLS = Path(__file__).resolve().parent
# MathJax 3 from the django-static-mathjax package (a plain copy of MathJax's release, no dependency; its
# Django glue is not used), loaded by mathjax_load.js, which configures it; pages are flat
# (use_directory_urls: false), so the path is relative to every page
MATHJAX_DIR = "assets/mathjax"
MATHJAX_URL = "assets/mathjax_load.js"
# what the site needs of MathJax's es5 folder: the tex-svg component and what it loads on demand (TeX
# extensions, the menu, the a11y helpers); not the speech engine nor the other combined components
_MATHJAX_SKIP = ("sre", "*-speech.js", "node-main.js", "tex-chtml*", "tex-mml-*", "mml-*", "tex-svg-full.js")
EXTRA_CSS = "book_extra.css"
_MATH = re.compile(r"\$\$(.+?)\$\$|(?<![\\$])\$(?!\$)(.+?)(?<![\\$])\$", re.DOTALL)
_TAG = re.compile(r"<(/?)(em|strong|i|b|code|a|span)\b[^>]*>")
_CONTROL = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f]")
# a resource the page loads (not a link the reader may follow): script/img/iframe src, stylesheet href
_RESOURCE = re.compile(
    r"<(?:script|img|iframe|source)\b[^>]*\bsrc=[\"']([^\"']+)[\"']"
    r"|<link\b[^>]*\bhref=[\"']([^\"']+)[\"']"
    r"|@import\s+(?:url\()?[\"']?([^\"')\s]+)"
    r"|url\([\"']?(https?:[^\"')]+)"
    r"|import\(\s*[\"']((?:https?:)?//[^\"']+)",
    re.IGNORECASE,
)
# nbconvert's loader of mermaid diagrams (a <script type="module"> importing mermaid from a CDN when a page
# has a diagram; no chapter has one)
_MERMAID = re.compile(
    r"<script type=\"module\">(?:(?!</script>).)*?mermaid(?:(?!</script>).)*</script>", re.DOTALL
)
_FIGURE_CALL = re.compile(r"\bplt\.(subplots|figure)\(|\.plot_\w+\(|\bplot\.\w+\(")


class NotExecutedError(RuntimeError):
    """Notebooks that cannot be rendered as they are (not executed, failed, or without their figures)."""


def chapter_title(notebook: Path) -> str:
    """The first Markdown heading of a notebook, without the '#'."""
    nb = json.loads(Path(notebook).read_text())
    for cell in nb["cells"]:
        if cell["cell_type"] == "markdown":
            for line in "".join(cell["source"]).splitlines():
                if line.startswith("#"):
                    return line.lstrip("#").strip()
    return Path(notebook).stem


def notebook_problem(notebook: Path) -> str | None:
    """Why ``notebook`` cannot go into the book as it is, or None when it is executed with its figures."""
    nb = json.loads(Path(notebook).read_text())
    code = [c for c in nb["cells"] if c["cell_type"] == "code" and "".join(c["source"]).strip()]
    if not code:
        return None
    unrun = [c for c in code if c.get("execution_count") is None]
    if unrun:
        return f"not executed ({len(unrun)} of {len(code)} code cells have no execution count)"
    for c in code:
        for out in c.get("outputs", []):
            if out.get("output_type") == "error":
                return f"stopped at an error: {out.get('ename')}: {out.get('evalue', '')[:120]}"
    makes_figures = any(_FIGURE_CALL.search("".join(c["source"])) for c in code)
    has_figures = any(
        "image/png" in out.get("data", {}) or "image/svg+xml" in out.get("data", {})
        for c in code
        for out in c.get("outputs", [])
    )
    if makes_figures and not has_figures:
        return (
            "makes figures but holds none (executed with MPLBACKEND set to a non-inline backend such as Agg? "
            "the chapters' kernels need ipykernel's inline backend: leave MPLBACKEND unset)"
        )
    return None


def execute(notebook: Path, timeout: int = 3600) -> None:
    """Execute ``notebook`` in place with nbclient (the mode from ``SSI_FAST``, as the environment sets)."""
    import nbformat
    from nbclient import NotebookClient
    from nbclient.exceptions import CellExecutionError

    nb = nbformat.read(notebook, as_version=4)
    env_backend = os.environ.pop("MPLBACKEND", None)  # the kernel must use the inline backend
    try:
        NotebookClient(
            nb, timeout=timeout, kernel_name="python3", resources={"metadata": {"path": str(Path.cwd())}}
        ).execute()
    except CellExecutionError:
        pass  # the error is in the cell's outputs: notebook_problem() reports it
    finally:
        if env_backend is not None:
            os.environ["MPLBACKEND"] = env_backend
    nbformat.write(nb, notebook)


def check_notebooks(notebooks: Path, run: bool = False) -> list[Path]:
    """The chapter notebooks of ``notebooks``, sorted; refuse (or, with ``run``, execute) unfit ones.

    Raises :class:`NotExecutedError` naming every notebook that is not executed, failed or lost its figures
    (unless ``run``: then each such notebook is executed and checked again).
    """
    pages = sorted(Path(notebooks).glob("*.ipynb"))
    if not pages:
        raise FileNotFoundError(f"no notebooks in {notebooks}: run `make reproduce` first")
    bad = {}
    for nb in pages:
        problem = notebook_problem(nb)
        if problem and run:
            print(f"book: executing {nb.name} ({problem})", flush=True)
            execute(nb)
            problem = notebook_problem(nb)
        if problem:
            bad[nb] = problem
    if bad:
        lines = "\n".join(f"  {nb}: {why}" for nb, why in bad.items())
        raise NotExecutedError(
            f"{len(bad)} of {len(pages)} notebooks cannot go into the book as they are:\n{lines}\n"
            "`make book` renders the notebooks that `make reproduce` executed (make test and make notebooks "
            "leave them unexecuted): run `make reproduce` first, or `python tools/book.py --execute` to "
            "execute these now."
        )
    return pages


def prepare(pages: list[Path], source: Path) -> Path:
    """Copy the notebooks into ``source``/docs with an index page and write ``source``/mkdocs.yml."""
    docs = source / "docs"
    if source.exists():
        shutil.rmtree(source)
    docs.mkdir(parents=True)
    nav = ["  - Contents: index.md"]
    lines = ["# ssi: soil-structure interaction of RC shallow foundations", "", "Chapters:", ""]
    for nb in pages:
        shutil.copy2(nb, docs / nb.name)
        title = chapter_title(nb)
        nav.append(f"  - {json.dumps(title)}: {nb.name}")
        lines.append(f"- [{title}]({nb.name})")
    (docs / "index.md").write_text("\n".join(lines) + "\n")
    shutil.copy2(TOOLS / EXTRA_CSS, docs / EXTRA_CSS)
    (source / "mkdocs.yml").write_text(
        "site_name: ssi\n"
        "docs_dir: docs\n"
        "use_directory_urls: false\n"  # file:// has no index.html for a folder link
        "theme:\n"
        "  name: material\n"
        "  font: false\n"  # the system fonts: no web-font request
        "  features: [navigation.top]\n"
        f"extra_css: [{EXTRA_CSS}]\n"
        "nav:\n" + "\n".join(nav) + "\n"
        # no search plugin: its worker cannot start from file:// and Material's offline plugin that would
        # make it work adds a polyfill from a CDN
        "plugins:\n"
        "  - mkdocs-jupyter:\n"
        "      execute: false\n"
        "      cache: false\n"  # no .cache/ folder in the working directory
        "      include_source: false\n"
        "      include_requirejs: false\n"
        f'      custom_mathjax_url: "{MATHJAX_URL}"\n'
    )
    return source / "mkdocs.yml"


def mathjax_source() -> Path:
    """MathJax 3's es5 folder as shipped by the ``django-static-mathjax`` package (the book extra)."""
    try:
        import mathjax
    except ImportError as err:
        raise ImportError(
            "the book bundles MathJax from the django-static-mathjax package: pip install -e '.[book]'"
        ) from err
    folder = Path(mathjax.__file__).parent / "static" / "mathjax"
    if not (folder / "es5" / "tex-svg.js").is_file():
        raise FileNotFoundError(
            f"{folder}/es5/tex-svg.js missing: not the MathJax 3 of django-static-mathjax"
        )
    return folder


def build(notebooks, site, source=None, run: bool = False) -> Path:
    """Build the HTML book from the executed ``notebooks`` into ``site``; return the site folder.

    Raises :class:`NotExecutedError` for notebooks that are not executed (see :func:`check_notebooks`).
    """
    site = Path(site).resolve()
    source = Path(source) if source else site.parent / (site.name + "_src")
    pages = check_notebooks(Path(notebooks), run=run)
    config = prepare(pages, source)
    subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "-q", "-f", str(config), "-d", str(site)],
        check=True,
        env={**os.environ, "NO_MKDOCS_2_WARNING": "1"},  # Material's banner about a future mkdocs 2
    )
    for page in site.glob("*.html"):  # mermaid from a CDN, for diagrams that no chapter has
        text = page.read_text()
        page.write_text(_MERMAID.sub("", text))
    source_mj = mathjax_source()
    shutil.copytree(source_mj / "es5", site / MATHJAX_DIR, ignore=shutil.ignore_patterns(*_MATHJAX_SKIP))
    shutil.copy2(source_mj / "LICENSE", site / MATHJAX_DIR / "LICENSE")
    shutil.copy2(TOOLS / "mathjax_load.js", site / MATHJAX_URL)
    return site


def check_page(text: str) -> list[str]:
    """Problems of one HTML page (see the module docstring); empty if it should render offline."""
    problems = []
    for m in _RESOURCE.finditer(text):
        url = next(g for g in m.groups() if g)
        if re.match(r"(https?:)?//", url):
            problems.append(f"resource loaded from the network: {url[:100]}")
    has_math = bool(_MATH.search(_body_text(text)))
    sources = re.findall(r"<script[^>]*\bsrc=\"([^\"]*)\"", text)
    if has_math and not any(s.endswith(MATHJAX_URL) for s in sources):
        problems.append(
            f"math on the page but the bundled MathJax is not loaded (no <script src={MATHJAX_URL}>)"
        )
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
    for page in sorted(Path(site).glob("*.html")):
        problems = check_page(page.read_text(errors="replace"))
        if problems:
            out[str(page.relative_to(site))] = problems
    return out


def check_in_browser(site, shots=Path("build/browser/book")) -> dict | None:
    """{page: [problems]} of every page of ``site`` opened in headless Chromium with no network (see
    ``PageReport.problems`` in tools/browser.py), or None when Chromium is not installed."""
    sys.path.insert(0, str(TOOLS))
    try:
        import browser
    finally:
        sys.path.remove(str(TOOLS))
    if browser.find_chromium() is None:
        return None
    out = {}
    with browser.Chromium() as chromium:
        for page in sorted(Path(site).glob("*.html")):
            if page.name == "404.html":  # a web server's page, with links from the server's root
                continue
            report = browser.inspect_page(chromium, page, Path(shots) / (page.stem + ".png"))
            problems = report.problems()
            # TeX outside code blocks and scripts (a '$' in code or in the page's scripts is not math)
            has_math = _MATH.search(_body_text(page.read_text(errors="replace")))
            if has_math and report.math_elements == 0:
                problems.append("no equation typeset (MathJax did not run?)")
            if problems:
                out[page.name] = problems
    return out


def main(argv=None) -> int:
    args = sys.argv[1:] if argv is None else list(argv)
    run = "--execute" in args
    args = [a for a in args if a != "--execute"]
    notebooks, site = (Path(a) for a in (args + ["build/notebooks", "build/book"])[:2])
    try:
        site = build(notebooks, site, run=run)
    except NotExecutedError as err:
        print(f"book: refused. {err}", file=sys.stderr)
        return 2
    problems = check_html(site)
    for page, items in problems.items():
        for p in items:
            print(f"{page}: {p}")
    n_pages = len(list(site.glob("*.html")))
    n_img = sum(p.read_text(errors="replace").count("<img") for p in site.glob("*.html"))
    print(
        f"book: {site}/index.html ({n_pages} pages, {n_img} images); offline and equation check: "
        + ("OK" if not problems else f"{sum(map(len, problems.values()))} problems")
    )
    in_browser = check_in_browser(site)
    if in_browser is None:
        print(
            "book: no chromium installed, the pages were not opened in a browser (apt-get install chromium)"
        )
    else:
        for page, items in in_browser.items():
            for p in items:
                print(f"{page} (in Chromium): {p}")
        print(
            "book: every page opened in headless Chromium, offline (screenshots in build/browser/book): "
            + ("OK" if not in_browser else f"{sum(map(len, in_browser.values()))} problems")
        )
    return 1 if problems or in_browser else 0


if __name__ == "__main__":
    sys.exit(main())
