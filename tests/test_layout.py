"""The package's layering, read from its imports (``ast``, nothing is imported), and the numba cache key.

Each subpackage of ``ssi`` has a rank; a module may import from its own subpackage, from a lower rank and from
the package root (``ssi/__init__.py``: the version and the cache key), never upwards. Imports inside functions
and under ``TYPE_CHECKING`` count as well.
No two modules import each other, through any chain, at run time (imports inside functions count: a
function-level import hides a circle, it does not remove it); an import under ``if TYPE_CHECKING:`` names a
type for an annotation only (``BuiltScene`` in the ``SceneResult`` that views it) and is left out of that
check, but it too must respect the ranks.
``limit`` (finite-element limit analysis) has its rank before it lands; a folder the list does not rank fails
the test, so a new subpackage gets its place on purpose.
"""

import ast
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parent.parent / "ssi"
ORDER = ("core", "materials", "elements", "solver", "limit", "capacity", "scene", "io", "studies", "lab")
RANK = {name: i for i, name in enumerate(ORDER)}


def _module_name(path: Path, package: Path = PACKAGE) -> str:
    parts = path.relative_to(package.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _imports(path: Path, package: Path = PACKAGE) -> list[tuple[int, str]]:
    """(line, absolute module) of every import in ``path`` that names an ``ssi`` module (``from X import y``
    gives ``X.y``, which is a module or a name in X: both sit in X's subpackage)."""
    here = _module_name(path, package).split(".")
    base_package = here if path.name == "__init__.py" else here[:-1]
    found = []
    for node in ast.walk(ast.parse(path.read_text(), filename=str(path))):
        if isinstance(node, ast.Import):
            found += [(node.lineno, alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = base_package[: len(base_package) - (node.level - 1)]
                module = ".".join(base + ([node.module] if node.module else []))
            else:
                module = node.module
            found += [(node.lineno, f"{module}.{alias.name}") for alias in node.names]
    return [(line, name) for line, name in found if name == "ssi" or name.startswith("ssi.")]


def _room(module: str, package: Path = PACKAGE) -> str | None:
    """The subpackage of an ``ssi`` module, or None for the package root."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 and (package / parts[1]).is_dir() else None


def upward_imports(package: Path = PACKAGE) -> list[str]:
    """Every import of a module from a subpackage of higher rank, as "file:line (room) imports module
    (room)"."""
    found = []
    for path in sorted(package.rglob("*.py")):
        own = _room(_module_name(path, package), package)
        for line, target in _imports(path, package):
            other = _room(target, package)
            if other is None:
                continue
            if own is None or RANK[other] > RANK[own]:
                where = path.relative_to(package.parent)
                found.append(f"{where}:{line} ({own or 'the root'}) imports {target} ({other})")
    return found


def test_every_subpackage_has_a_rank():
    folders = {p.name for p in PACKAGE.iterdir() if p.is_dir() and (p / "__init__.py").exists()}
    assert folders <= set(ORDER), f"subpackages without a rank in ORDER: {sorted(folders - set(ORDER))}"
    assert {"core", "materials", "elements", "solver", "scene", "io", "studies", "lab"} <= folders
    loose = sorted(p.name for p in PACKAGE.glob("*.py") if p.name != "__init__.py")
    assert loose == [], f"modules outside every subpackage: {loose}"


def test_no_import_runs_upwards():
    found = upward_imports()
    assert found == [], "imports that run upwards:\n" + "\n".join(found)


def _runtime_imports(path: Path, package: Path = PACKAGE) -> set[str]:
    """The ``ssi`` modules ``path`` imports at run time (not under ``if TYPE_CHECKING:``), each resolved to a
    module file of the package (``from X import y``: X.y if that is a module, else X)."""
    tree = ast.parse(path.read_text())
    hidden = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            hidden |= {id(n) for n in ast.walk(node)}
    modules = set()
    here = _module_name(path, package).split(".")
    base_package = here if path.name == "__init__.py" else here[:-1]
    for node in ast.walk(tree):
        if id(node) in hidden or not isinstance(node, ast.ImportFrom | ast.Import):
            continue
        if isinstance(node, ast.Import):
            candidates = [alias.name for alias in node.names]
        else:
            base = base_package[: len(base_package) - (node.level - 1)] if node.level else []
            module = ".".join(base + ([node.module] if node.module else [])) if node.level else node.module
            candidates = [f"{module}.{alias.name}" for alias in node.names] + [module]
        for name in candidates:
            if not name.startswith("ssi"):
                continue
            rel = Path(*name.split(".")[1:])
            if (package / rel).with_suffix(".py").exists():
                modules.add(name)
            elif (package / rel / "__init__.py").exists() and name == candidates[-1]:
                modules.add(name)
    return modules


def import_circles(package: Path = PACKAGE) -> list[list[str]]:
    """Every circle of run-time imports between the modules of ``package``, each as [a, b, ..., a]."""
    graph = {_module_name(p, package): _runtime_imports(p, package) for p in package.rglob("*.py")}
    circles, done = [], set()

    def visit(module, stack):
        if module in stack:
            circles.append(stack[stack.index(module) :] + [module])
            return
        if module in done:
            return
        for other in sorted(graph.get(module, ())):
            if other != module:
                visit(other, stack + [module])
        done.add(module)

    for module in sorted(graph):
        visit(module, [])
    return circles


def test_no_import_circles():
    circles = import_circles()
    assert circles == [], "import circles:\n" + "\n".join(" -> ".join(c) for c in circles)


def test_the_circle_check_finds_a_function_level_circle(tmp_path):
    """A function-level import of the scene file written into a copy of the scene module closes a circle
    (the scene file imports the scene module): the check names it."""
    copy = tmp_path / "ssi"
    shutil.copytree(PACKAGE, copy, ignore=shutil.ignore_patterns("__pycache__"))
    assert import_circles(copy) == []
    with open(copy / "scene" / "scene.py", "a") as fh:
        fh.write("\n\ndef _probe():\n    from .scene_file import scene_to_dict\n\n    return scene_to_dict\n")
    circles = import_circles(copy)
    assert circles and {"ssi.scene.scene", "ssi.scene.scene_file"} <= set(circles[0])


def test_the_product_never_imports_the_lab():
    """Nothing in ``ssi`` outside ``lab/`` imports it (tests, chapters, benchmarks and tools may)."""
    hits = [
        f"{p}:{line}"
        for p in PACKAGE.rglob("*.py")
        if _room(_module_name(p)) != "lab"
        for line, target in _imports(p)
        if _room(target) == "lab"
    ]
    assert hits == []


def test_the_layering_check_finds_an_upward_import(tmp_path):
    """The check must be able to fail: a function-level import of the scene written into a copy of a core
    module is reported, with its line."""
    copy = tmp_path / "ssi"
    shutil.copytree(PACKAGE, copy, ignore=shutil.ignore_patterns("__pycache__"))
    assert upward_imports(copy) == []
    with open(copy / "core" / "mesh.py", "a") as fh:
        fh.write("\n\ndef _probe():\n    from ..scene import Scene\n\n    return Scene\n")
    found = upward_imports(copy)
    assert (
        len(found) == 1 and found[0].startswith("ssi/core/mesh.py:") and "ssi.scene.Scene (scene)" in found[0]
    )


def _defines_kernels(path: Path) -> bool:
    """Whether ``path`` uses numba's ``njit``/``jit`` (``@njit(cache=True)``, ``njit(f)``)."""
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Name) and node.id in ("njit", "jit"):
            return True
        if isinstance(node, ast.Attribute) and node.attr in ("njit", "jit"):
            return True
    return False


def test_every_kernel_lives_in_a_hashed_package():
    """Every module that defines a numba kernel is inside a folder the cache key hashes: a kernel elsewhere
    could run stale machine code after its callee changed."""
    from ssi import KERNEL_PACKAGES

    kernels = {p for p in PACKAGE.rglob("*.py") if _defines_kernels(p)}
    assert kernels, "no kernel found: the search is wrong"
    outside = sorted(str(p) for p in kernels if _room(_module_name(p)) not in KERNEL_PACKAGES)
    assert outside == []


# the capabilities ssi.core.protocol.ElementGroup declares (and names groups once answered to probes by)
CAPABILITIES = {
    "assemble_elastic_stiffness",
    "forces_only",
    "history_fields",
    "integration_points",
    "ip_coords",
    "ip_weights",
    "point_code_names",
    "point_codes",
    "status",
    "viscosity",
    "viscous",
}


def capability_probes(package: Path = PACKAGE) -> list[str]:
    """Every ``hasattr(x, "<capability>")`` or ``getattr(x, "<capability>", ...)`` in the product (``lab`` may
    probe), as "file:line name"."""
    found = []
    for p in sorted(package.rglob("*.py")):
        if _room(_module_name(p, package), package) == "lab":
            continue
        for node in ast.walk(ast.parse(p.read_text(), filename=str(p))):
            if (
                isinstance(node, ast.Call)
                and isinstance(node.func, ast.Name)
                and node.func.id in ("hasattr", "getattr")
                and len(node.args) >= 2
                and isinstance(node.args[1], ast.Constant)
                and node.args[1].value in CAPABILITIES
            ):
                found.append(f"{p.relative_to(package.parent)}:{node.lineno} {node.args[1].value}")
    return found


def test_group_capabilities_are_declared_not_probed():
    assert capability_probes() == []


def test_the_probe_check_finds_a_probe(tmp_path):
    pkg = tmp_path / "ssi"
    (pkg / "solver").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "solver" / "__init__.py").write_text("")
    (pkg / "solver" / "x.py").write_text("def f(g):\n    return hasattr(g, 'viscosity')\n")
    assert capability_probes(pkg) == ["ssi/solver/x.py:2 viscosity"]


def test_every_element_group_inherits_the_protocol():
    """Each class in ssi.elements with an ``evaluate`` method is an ElementGroup, so that every capability
    the solver, the scene and the result files read has its declared default."""
    import importlib
    import inspect

    from ssi.core.protocol import ElementGroup

    groups = []
    for p in sorted((PACKAGE / "elements").glob("*.py")):
        module = importlib.import_module(_module_name(p))
        for _, cls in inspect.getmembers(module, inspect.isclass):
            if cls.__module__ == module.__name__ and callable(getattr(cls, "evaluate", None)):
                groups.append(cls)
    assert {cls.__name__ for cls in groups} >= {"SoilQ8", "PlateStrip", "Interface6", "Spring"}
    assert [cls.__name__ for cls in groups if not issubclass(cls, ElementGroup)] == []


def _cache_folder(package_copy: Path) -> str:
    """The numba cache folder a fresh process picks for the package copy under ``package_copy``."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(package_copy / "cache"), PYTHONPATH=str(package_copy))
    code = "import os, ssi; print(ssi.__file__); print(os.environ['NUMBA_CACHE_DIR'])"
    out = subprocess.run(
        [sys.executable, "-c", code], env=env, cwd=package_copy, capture_output=True, text=True
    )
    assert out.returncode == 0, out.stderr
    imported, folder = (Path(line) for line in out.stdout.split())
    assert imported == package_copy / "ssi" / "__init__.py"  # the copy, not the installed package
    assert folder.parent == package_copy / "cache"
    return folder.name


@pytest.fixture
def package_copy(tmp_path):
    shutil.copytree(PACKAGE, tmp_path / "ssi", ignore=shutil.ignore_patterns("__pycache__"))
    return tmp_path


@pytest.mark.parametrize("edited", ["lab/report.py", "scene/scene_file.py", "io/plot.py", "studies/sweep.py"])
def test_editing_a_file_without_kernels_keeps_the_numba_cache(package_copy, edited):
    before = _cache_folder(package_copy)
    with open(package_copy / "ssi" / edited, "a") as fh:
        fh.write("\n# an edit\n")
    assert _cache_folder(package_copy) == before


@pytest.mark.parametrize("edited", ["materials/mc_surface.py", "elements/plate.py", "core/assembly.py"])
def test_editing_a_kernel_file_moves_the_numba_cache(package_copy, edited):
    before = _cache_folder(package_copy)
    with open(package_copy / "ssi" / edited, "a") as fh:
        fh.write("\n# an edit\n")
    assert _cache_folder(package_copy) != before


def load_class_checks(package: Path = PACKAGE) -> list[str]:
    """Every ``isinstance(x, <a load class>)`` in the product outside the load registry (``scene/loads.py``),
    as "file:line name": the bridge, the views and the checks ask a load what it does (``drives``,
    ``columns()``, ``ground_span()``, ``limit_action(frame)``, ``effect(built)``), never its class."""
    from ssi.scene.loads import LOAD_TYPES

    names = set(LOAD_TYPES) | {"Load"}
    found = []
    for p in sorted(package.rglob("*.py")):
        if p.relative_to(package).as_posix() == "scene/loads.py":
            continue
        for node in ast.walk(ast.parse(p.read_text(), filename=str(p))):
            if (
                isinstance(node, ast.Call)
                and isinstance(node.func, ast.Name)
                and node.func.id == "isinstance"
            ):
                classes = node.args[1:] and ast.walk(node.args[1])
                hits = sorted({n.id for n in classes or () if isinstance(n, ast.Name) and n.id in names})
                found += [f"{p.relative_to(package.parent)}:{node.lineno} {name}" for name in hits]
    return found


def test_no_isinstance_on_load_classes_outside_the_registry():
    assert load_class_checks() == []


def test_the_load_class_check_finds_one(tmp_path):
    copy = tmp_path / "ssi"
    shutil.copytree(PACKAGE, copy, ignore=shutil.ignore_patterns("__pycache__"))
    with open(copy / "capacity" / "common.py", "a") as fh:
        fh.write("\n\ndef _probe(ld):\n    return isinstance(ld, (ColumnLoad, int))\n")
    found = load_class_checks(copy)
    assert (
        len(found) == 1 and found[0].startswith("ssi/capacity/common.py:") and found[0].endswith("ColumnLoad")
    )
