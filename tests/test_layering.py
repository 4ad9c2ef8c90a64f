"""The package's shape: one subpackage per step of the method, imports only
from the same or an earlier step, no import circles.

The order of the steps is written once, as ``cracklip.LAYERS`` (its
docstring says what each step owns). ``errors``, ``_cracklip`` (the C++
module) and the package's own ``__init__`` come before every step;
``__main__`` after them all. Every import counts, also one inside a
function (a lazy import is still a dependency).

The checker runs on any package folder, so its own unit tests below build
small packages with a wrong import and see it caught, e.g.::

    pkg/scene/a.py:  from ..model import b      # scene imports model: upward
    -> ["pkg.scene.a imports pkg.model.b: scene (step 1) from model (step 2)"]
"""
from __future__ import annotations

import ast
import pathlib

import pytest
from conftest import ROOT

import cracklip

PACKAGE = ROOT / "python" / "cracklip"
#: Modules every step may import.
BASE = ("errors", "_cracklip", "__init__")
#: The only modules outside a subpackage.
TOP_LEVEL = {"__init__", "__main__", "errors"}


def module_name(root: pathlib.Path, path: pathlib.Path) -> str:
    rel = path.relative_to(root.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def is_package(root: pathlib.Path, name: str) -> bool:
    return (root.parent / pathlib.Path(*name.split(".")) / "__init__.py").exists()


def module_exists(root: pathlib.Path, name: str) -> bool:
    base = root.parent / pathlib.Path(*name.split("."))
    return base.with_suffix(".py").exists() or (base / "__init__.py").exists()


def module_imports(root: pathlib.Path) -> dict[str, set[str]]:
    """Every module of the package under root -> the package's modules it
    imports (absolute names), from every import statement at any depth."""
    out: dict[str, set[str]] = {}
    top = root.name
    for path in sorted(root.rglob("*.py")):
        name = module_name(root, path)
        package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
        found: set[str] = set()
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.Import):
                found |= {a.name for a in node.names if a.name.split(".")[0] == top}
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    base = package.split(".")
                    base = base[:len(base) - (node.level - 1)]
                    target = ".".join(base + ([node.module] if node.module else []))
                else:
                    target = node.module or ""
                if target.split(".")[0] != top:
                    continue
                for a in node.names:  # `from pkg import module` imports the module
                    sub = f"{target}.{a.name}"
                    found.add(sub if module_exists(root, sub) else target)
        out[name] = {m for m in found if m != name}
    return out


def step_of(root: pathlib.Path, name: str, layers: tuple[str, ...]) -> int:
    """-1 for the base modules, the index in layers for a step's modules,
    len(layers) for __main__."""
    parts = name.split(".")[1:]
    if not parts or parts[0] in BASE:
        return -1
    if parts[0] == "__main__":
        return len(layers)
    if parts[0] not in layers:
        raise ValueError(f"{name}: not in a step of LAYERS {layers} (nor a base module {BASE})")
    return layers.index(parts[0])


def layer_violations(root: pathlib.Path, layers: tuple[str, ...]) -> list[str]:
    """One message per import of a later step than the importer's own."""
    out = []
    for name, imported in module_imports(root).items():
        mine = step_of(root, name, layers)
        for other in sorted(imported):
            theirs = step_of(root, other, layers)
            if theirs > mine:
                label = (lambda k: "base" if k < 0 else layers[k] if k < len(layers) else "__main__")
                out.append(f"{name} imports {other}: {label(mine)} (step {mine + 1}) from {label(theirs)} "
                           f"(step {theirs + 1})")
    return out


def import_cycles(root: pathlib.Path) -> list[list[str]]:
    """The import circles: strongly connected components of more than one
    module (Tarjan), each sorted. A package's __init__ importing its own
    submodules (a re-export) is left out of the graph."""
    graph = module_imports(root)
    for name, imported in graph.items():
        if is_package(root, name):
            graph[name] = {m for m in imported if not m.startswith(name + ".")}
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    cycles: list[list[str]] = []
    counter = [0]

    def visit(v: str) -> None:
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on_stack.add(v)
        for w in graph.get(v, ()):
            if w not in graph:
                continue
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                cycles.append(sorted(comp))
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return cycles


# -- the package ----------------------------------------------------------------------------------

def test_every_module_is_in_a_step():
    """Acceptance (issue 25): nothing but __init__, __main__ and errors
    (and the C++ module) outside a subpackage; every subpackage a step of
    LAYERS with a docstring saying what it owns."""
    loose = {p.stem for p in PACKAGE.glob("*.py")} - TOP_LEVEL
    assert not loose, f"modules outside a subpackage: {sorted(loose)}"
    steps = {p.name for p in PACKAGE.iterdir() if p.is_dir() and (p / "__init__.py").exists()}
    assert steps == set(cracklip.LAYERS)
    for step in steps:
        doc = ast.get_docstring(ast.parse((PACKAGE / step / "__init__.py").read_text()))
        assert doc and len(doc) > 40, f"{step}/__init__.py has no docstring saying what it owns"


def test_no_upward_imports():
    assert layer_violations(PACKAGE, cracklip.LAYERS) == []


def test_no_import_circles():
    assert import_cycles(PACKAGE) == []


# -- the checker itself ---------------------------------------------------------------------------

def write_package(root: pathlib.Path, files: dict[str, str]) -> pathlib.Path:
    pkg = root / "pkg"
    for rel, text in files.items():
        path = pkg / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    for d in [pkg, *[p for p in pkg.rglob("*") if p.is_dir()]]:
        (d / "__init__.py").touch()
    return pkg


@pytest.mark.parametrize("statement", [
    "from ..model import b",                # relative, module level
    "def f():\n    from ..model.b import g",  # lazy, inside a function
    "import pkg.model.b",                   # absolute
    "from pkg.model import b",              # absolute, a module by name
])
def test_checker_catches_an_upward_import(tmp_path, statement):
    pkg = write_package(tmp_path, {"scene/a.py": statement + "\n", "model/b.py": "def g():\n    pass\n"})
    found = layer_violations(pkg, ("scene", "model"))
    assert found == ["pkg.scene.a imports pkg.model.b: scene (step 1) from model (step 2)"]
    # The same import the other way round is allowed.
    assert layer_violations(pkg, ("model", "scene")) == []


def test_checker_allows_base_and_own_step(tmp_path):
    pkg = write_package(tmp_path, {"errors.py": "", "scene/a.py": "from ..errors import X\nfrom .c import y\n",
                                   "scene/c.py": "y = 1\n"})
    assert layer_violations(pkg, ("scene",)) == []


def test_checker_finds_a_circle(tmp_path):
    pkg = write_package(tmp_path, {"scene/a.py": "from . import c\n", "scene/c.py": "def f():\n    from .a import x\n",
                                   "scene/d.py": "from .a import x\n"})
    assert import_cycles(pkg) == [["pkg.scene.a", "pkg.scene.c"]]


def test_checker_rejects_a_module_outside_the_steps(tmp_path):
    pkg = write_package(tmp_path, {"stray/a.py": "from ..scene import b\n", "scene/b.py": ""})
    with pytest.raises(ValueError, match=r"pkg\.stray(\.a)?: not in a step"):
        layer_violations(pkg, ("scene",))
