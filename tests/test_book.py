"""The HTML book: mkdocs-jupyter renders a chapter-like notebook and the equation check passes it, and the
check fails on each way an equation breaks (MathJax not loaded, TeX mangled, a LaTeX string without r'')."""

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


def _notebook(folder, lines):
    cells = [
        {
            "cell_type": "markdown",
            "metadata": {},
            "source": "\n".join(x.removeprefix("# ").removeprefix("#") for x in lines),
        },
        {
            "cell_type": "code",
            "metadata": {},
            "execution_count": 1,
            "source": "print('$5 and $6')",
            "outputs": [{"output_type": "stream", "name": "stdout", "text": "$5 and $6\n"}],
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


def test_rendered_book_keeps_equations(tmp_path):
    pytest.importorskip("mkdocs_jupyter")
    _notebook(tmp_path / "nb", EQUATIONS)
    site = book.build(tmp_path / "nb", tmp_path / "site")
    page = (site / "99_chapter" / "index.html").read_text()
    assert r"\tan\varphi_i" in page and r"\frac{M}{EI}" in page  # the TeX reaches the page intact
    assert book.check_html(site) == {}


@pytest.mark.parametrize(
    "page, word",
    [
        ('<script src=""></script><p>$a_b$</p>', "MathJax is not loaded"),
        (f'<script src="{book.MATHJAX_URL}"></script><p>$a<em>b</em>c$</p>', "HTML tag inside math"),
        (f'<script src="{book.MATHJAX_URL}"></script><p>$\x08ar m$</p>', "control character"),
        ('<script src="' + book.MATHJAX_URL + r'"></script><p>$\frac{a}{{b}$</p>', "unbalanced braces"),
    ],
)
def test_check_finds_broken_equations(page, word):
    assert any(word in p for p in book.check_page(page))
