"""The controlled path's corrector where the residual has kinks (issue 31, crack8): chapter 11's cracking RC
strip on Mohr-Coulomb soil with contact."""

from ssi.lab.examples import chapter11_foundation
from ssi.solver import Settings


def test_cracking_strip_takes_no_failed_step_on_the_controlled_path():
    """Chapter 11's scene at h = 0.25 m, 10 targets: the step that raised |r| up to 300 times (a root of G
    taken where no backtracking step lowers |r|) is not taken any more (path.G_GROWTH), and the run ends
    at lambda = 1 without a failed step. At 3a5ff09 (G's root always taken) the run and four copies with
    the column load x (1 +- 1e-13), (1 +- 1e-12) each had one failed step; with G_GROWTH none has."""
    out = chapter11_foundation(0.25).build().solve(n_steps=10, settings=Settings(control="work"))
    res = out.solver_result
    assert out.status == "completed"
    assert res.load_factor[-1] == 1.0
    assert res.cuts == 0, f"{res.cuts} failed steps"
