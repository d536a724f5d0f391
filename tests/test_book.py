"""The HTML book: mkdocs-jupyter renders a chapter-like notebook with the bundled MathJax and no network
resource, and the checks pass it; the page check fails on each way an equation or the offline reading breaks
(MathJax not loaded, TeX mangled, a LaTeX string without r'', a CDN script); notebooks that are not executed,
stopped at an error, or make figures but hold none are refused by name."""

import importlib.util
import json
from pathlib import Path

import pytest

_spec = importlib.util.spec_from_file_location(
    "book", Path(__file__).resolve().parent.parent / "tools" / "book.py"
)
book = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(book)

EQUATIONS = [
    r"# # 99 — A chapter",
    r"# Inline $\sigma_n = k_n g_n$, a sum $a_b + c_d$ and a display",
    "#",
    r"# $$\tau \le c - \sigma_n \tan\varphi_i, \qquad \bar{m} = \frac{M}{EI} \tag{6.3}$$",
]


def _notebook(folder, lines, execution_count=1, outputs=None, code="print('$5 and $6')"):
    cells = [
        {
            "cell_type": "markdown",
            "metadata": {},
            "source": "\n".join(x.removeprefix("# ").removeprefix("#") for x in lines),
        },
        {
            "cell_type": "code",
            "metadata": {},
            "execution_count": execution_count,
            "source": code,
            "outputs": [{"output_type": "stream", "name": "stdout", "text": "$5 and $6\n"}]
            if outputs is None
            else outputs,
        },
    ]
    nb = {
        "cells": cells,
        "metadata": {"kernelspec": {"name": "python3", "display_name": "Python 3", "language": "python"}},
        "nbformat": 4,
        "nbformat_minor": 5,
    }
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "99_chapter.ipynb").write_text(json.dumps(nb))
    return folder / "99_chapter.ipynb"


def test_rendered_book_keeps_equations(tmp_path):
    pytest.importorskip("mkdocs_jupyter", reason="the book extra (mkdocs-jupyter) is not installed")
    pytest.importorskip("mathjax", reason="the book extra (django-static-mathjax) is not installed")
    _notebook(tmp_path / "nb", EQUATIONS)
    site = book.build(tmp_path / "nb", tmp_path / "site")
    page = (site / "99_chapter.html").read_text()
    assert r"\tan\varphi_i" in page and r"\frac{M}{EI}" in page  # the TeX reaches the page intact
    assert book.check_html(site) == {}
    # MathJax is in the site, loaded by a relative path, with the book's font settings; nothing from a CDN
    assert (site / book.MATHJAX_DIR / "tex-svg.js").is_file() and (site / book.MATHJAX_URL).is_file()
    assert f'src="{book.MATHJAX_URL}"' in page
    assert "cdnjs" not in page and "highlight.min.js" not in page and "unpkg" not in page


_IMAGE = {
    "output_type": "display_data",
    "metadata": {},
    "data": {"image/png": "iVBORw0KGgo=", "text/plain": "F"},
}


@pytest.mark.parametrize(
    "execution_count, outputs, code, why",
    [
        (None, [], "x = 1", "not executed"),
        (
            1,
            [{"output_type": "error", "ename": "ValueError", "evalue": "bad", "traceback": []}],
            "x = 1",
            "error",
        ),
        (1, [], "fig, ax = plt.subplots()", "makes figures but holds none"),
    ],
)
def test_unfit_notebooks_are_refused(tmp_path, execution_count, outputs, code, why):
    nb = _notebook(tmp_path / "nb", EQUATIONS, execution_count, outputs, code)
    assert why in book.notebook_problem(nb)
    with pytest.raises(book.NotExecutedError, match="99_chapter.ipynb.*" + why):
        book.check_notebooks(tmp_path / "nb")
    assert book.main([str(tmp_path / "nb"), str(tmp_path / "site")]) == 2  # make book stops, nothing built
    assert not (tmp_path / "site").exists()


def test_executed_notebook_with_its_figure_is_accepted(tmp_path):
    nb = _notebook(tmp_path / "nb", EQUATIONS, 1, [_IMAGE], "fig, ax = plt.subplots()")
    assert book.notebook_problem(nb) is None
    assert book.check_notebooks(tmp_path / "nb") == [nb]


@pytest.mark.parametrize(
    "page, word",
    [
        ('<script src=""></script><p>$a_b$</p>', "MathJax is not loaded"),
        ('<script src="https://cdnjs.example/mathjax.js"></script><p>$a_b$</p>', "MathJax is not loaded"),
        (f'<script src="{book.MATHJAX_URL}"></script><script src="https://cdn.x/h.js"></script>', "network"),
        ('<link rel="stylesheet" href="//fonts.example/css">', "network"),
        ('<script type="module">await import("https://cdn.x/m.mjs")</script>', "network"),
        (f'<script src="{book.MATHJAX_URL}"></script><p>$a<em>b</em>c$</p>', "HTML tag inside math"),
        (f'<script src="{book.MATHJAX_URL}"></script><p>$\x08ar m$</p>', "control character"),
        ('<script src="' + book.MATHJAX_URL + r'"></script><p>$\frac{a}{{b}$</p>', "unbalanced braces"),
    ],
)
def test_check_finds_broken_equations(page, word):
    assert any(word in p for p in book.check_page(page))
