"""A site solved in phases (``Site.phases``, as a scene's): a fill beside a strip on sloping ground, then a
column on the strip, then the column removed. Each phase's contact resultant is its applied load (the plate's
equilibrium: the soil carries what stands on the strip), and unloading leaves a permanent settlement on
plastic soil but none on elastic soil."""

import numpy as np
import pytest

from ssi.elements.section import homogeneous
from ssi.scene import ColumnLoad, Contact, Excavation, Foundation, MeshSize, Phase, SoilLayer, SurfacePressure
from ssi.scene.site import RigidStrip, Site, Strip

SLOPE = [(-12.0, 2.0), (-2.0, 2.0), (4.0, 0.0), (12.0, 0.0)]  # a 1:3 slope between two level benches
N = 350e3  # [N/m] the column, at x = -6.5 m on the 3 m strip on the upper bench
PHASES = [
    Phase("fill", loads=(SurfacePressure(-11.0, -9.0, 20e3),)),
    Phase("column", loads=(ColumnLoad(-6.5, N=N),)),
    Phase("unload", factors={"column": 0.0}),
]


def _site(c, phases=PHASES, **kw):
    # c None: elastic soil; else Mohr-Coulomb with phi = 25 deg
    strength = {} if c is None else {"c": c, "phi_deg": 25.0}
    soil = SoilLayer(1.0, E=20e6, nu=0.3, unit_weight=18e3, **strength)
    strip = Strip(Foundation(-8.0, -5.0, homogeneous(0.5, 30e9, 0.2)), Contact(kn=1e10, kt=1e9))
    return Site(24.0, 10.0, [soil], ground=SLOPE, strips=[strip], mesh=MeshSize(h_fine=0.5, h_coarse=2.5),
                phases=phases, **kw)  # fmt: skip


@pytest.fixture(scope="module")
def plastic():
    return _site(15e3).build().solve()


def test_each_phase_contact_resultant_is_its_applied_load(plastic):
    out = plastic
    assert out.status == "completed"
    assert [r["name"] for r in out.phases] == ["geostatic", "fill", "column", "unload"]
    ends = {r["name"]: r["last"] for r in out.phases}
    # the fill stands beside the strip, the unloaded strip carries nothing: no contact force
    for name in ("geostatic", "fill", "unload"):
        assert abs(out.contact_resultant(0, ends[name])["N"]) <= 1e-9 * N, name
    column = out.contact_resultant(0, ends["column"])
    assert column["N"] == pytest.approx(N, rel=1e-9)
    assert column["eccentricity"] == pytest.approx(-6.5, abs=1e-6)  # under the column: the moment balances
    assert out.plastic_points(ends["column"]).any()  # the soil under the strip's edges yields


def test_unloading_leaves_a_permanent_settlement_on_plastic_soil_only(plastic):
    def settlements(out):
        ends = {r["name"]: r["last"] for r in out.phases}
        return {k: out.strip_summary(0, ends[k])["mean"] for k in ("fill", "column", "unload")}

    p = settlements(plastic)
    e = settlements(_site(None).build().solve())
    # elastic: the column's settlement is recovered exactly on unloading
    assert e["unload"] == pytest.approx(e["fill"], rel=1e-9, abs=1e-12)
    # plastic: more than a tenth of the column's settlement stays
    assert p["unload"] - p["fill"] > 0.1 * (p["column"] - p["fill"]) > 0.0


def test_a_phased_site_has_one_result_rows_per_phase_and_phase_time(plastic):
    """Phase i runs from phase time i - 1 to i (the geostatic phase at 0), as a phased scene's rows."""
    lam = np.asarray(plastic.load_factor)
    for i, r in enumerate(plastic.phases[1:]):
        assert lam[r["last"]] == pytest.approx(i + 1.0)
        assert lam[r["first"] - 1] == pytest.approx(float(i))


def test_phase_input_a_site_cannot_build_is_refused_by_name():
    with pytest.raises(ValueError, match="excavations and drainage switches are built on a Scene only"):
        _site(None, [Phase("dig", excavate=(Excavation(-3.0, 3.0, 1.0),))])
    with pytest.raises(ValueError, match=r"factors\['nope'\]: no earlier phase"):
        _site(None, [Phase("a", factors={"nope": 0.0})])
    with pytest.raises(ValueError, match="name is taken"):
        _site(None, [Phase("a"), Phase("a")])
    with pytest.raises(ValueError, match="RigidStrip.settle"):
        Site(24.0, 10.0, [SoilLayer(1.0, E=20e6, nu=0.3)], strips=[RigidStrip(-1.0, 1.0, settle=0.01)],
             phases=[Phase("a")])  # fmt: skip
    with pytest.raises(ValueError, match="limit analysis of a phased site is not built"):
        _site(None).limit_analysis()


def test_a_phased_site_round_trips_through_its_file_form():
    import json

    from ssi.scene.scene_file import model_from_dict, scene_to_dict

    site = _site(15e3, water_table=6.0)
    plain = scene_to_dict(site)
    again = model_from_dict(json.loads(json.dumps(plain)))
    assert isinstance(again, Site) and scene_to_dict(again) == plain
    assert [ph.name for ph in again.phases] == ["fill", "column", "unload"]
    assert again.phases[2].factors == {"column": 0.0} and again.phases[1].loads == PHASES[1].loads


def test_a_phased_site_result_file_reads_back_its_phases(plastic, tmp_path):
    """The result file of a phased site keeps each phase's record: read back, the same phases, rows and
    per-phase contact resultants (the one result-file kind for a scene and a site)."""
    from ssi.io.results import read_result, write_result

    path = write_result(tmp_path / "phased.h5", plastic)
    back = read_result(path)
    assert [(r["name"], r["first"], r["last"]) for r in back.phases] == [
        (r["name"], r["first"], r["last"]) for r in plastic.phases
    ]
    np.testing.assert_array_equal(back.load_factor, plastic.load_factor)
    k = plastic.phases[2]["last"]  # the column phase's end
    assert back.contact_resultant(0, k)["N"] == plastic.contact_resultant(0, k)["N"]
    assert back.status == plastic.status


def test_a_scene_and_a_site_share_one_phase_list():
    """``loads`` as a first phase "loads", then ``phases``: one function (``ssi.scene.parts.load_phases``)
    for a scene and a site, and no other place in ssi that builds that list (found by ast; the check is
    shown to find a probe)."""
    import ast
    import pathlib

    from ssi.scene import Scene

    col, unload = ColumnLoad(-6.5, N=N), Phase("unload", factors={"loads": 0.0})
    soil = SoilLayer(10.0, E=20e6, nu=0.3)
    strip = Strip(Foundation(-8.0, -5.0, homogeneous(0.5, 30e9, 0.2)), Contact(kn=1e10, kt=1e9))
    site = Site(24.0, 10.0, [soil], strips=[strip], loads=[col], phases=[unload])
    scene = Scene(24.0, 10.0, [soil], foundation=strip.foundation, contact=strip.contact, loads=[col],
                  phases=[unload])  # fmt: skip
    for model in (site, scene):
        phases = model.load_phases()
        assert [ph.name for ph in phases] == ["loads", "unload"]
        assert phases[0].loads == (col,) and phases[1] is unload
    assert [ph.name for ph in _site(None).load_phases()] == [
        "fill",
        "column",
        "unload",
    ]  # no loads: no "loads"

    def builders(source):  # calls Phase("loads", ...): where the list is built
        return [
            n.lineno
            for n in ast.walk(ast.parse(source))
            if isinstance(n, ast.Call) and getattr(n.func, "id", None) == "Phase"
            and n.args and isinstance(n.args[0], ast.Constant) and n.args[0].value == "loads"
        ]  # fmt: skip

    assert builders('x = 1\nphases = [Phase("loads", tuple(loads))]') == [2]
    root = pathlib.Path(__file__).resolve().parent.parent / "ssi"
    found = {str(p.relative_to(root)): builders(p.read_text()) for p in sorted(root.rglob("*.py"))}
    assert {k: v for k, v in found.items() if v} == {"scene/parts.py": [found["scene/parts.py"][0]]}
