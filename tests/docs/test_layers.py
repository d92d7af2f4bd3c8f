"""The import layers of ``docs/layers.md``, checked: no module imports from a layer above its own.

Every ``import`` and ``from ... import`` in ``pathzoo/``, ``plugins/`` and
``scenarios/`` is read with :mod:`ast`, those inside functions and under
``TYPE_CHECKING`` included, and the relative ones resolved. Imports written
as strings count too: ``importlib.import_module("...")`` and
``__import__("...")`` with a literal name, and the modules named in a
:func:`~pathzoo.lazy_names.lazy_getattr` table. A module belongs
to the unit with the longest matching name in :data:`LAYERS`; it may import
its own unit and any unit of a lower layer, nothing else, except the pairs
in :data:`ALLOWED` (each explained in ``docs/layers.md``).

No two modules import each other either, directly or round a longer loop,
at any time of the run: the imports that run (``TYPE_CHECKING`` blocks
left out), string imports included, form no cycle (:func:`import_cycles`).
"""

from __future__ import annotations

import ast
import functools
from collections.abc import Iterator
from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]
SOURCES = ("pathzoo", "plugins", "scenarios")

LAYERS: tuple[tuple[str, ...], ...] = (
    ("pathzoo.lazy_names", "pathzoo.text_table", "pathzoo.version", "pathzoo.experiments", "pathzoo.parent_death"),
    ("pathzoo.core",),
    ("pathzoo.grid", "pathzoo.generators"),
    ("pathzoo.rules",),
    ("pathzoo.grid.reference",),
    ("pathzoo.metrics",),
    ("pathzoo.io",),
    ("pathzoo.plugins",),
    ("pathzoo.builtin", "pathzoo_exact", "pathzoo_scenarios"),
    ("pathzoo_aco", "pathzoo_baselines", "pathzoo_rivals", "pathzoo_ompl", "pathzoo_external"),
    ("pathzoo.harness", "pathzoo.testing"),
    ("pathzoo.analysis",),
    ("pathzoo.plotting",),
    ("report",),
    ("pathzoo.tuning",),
    ("pathzoo",),
    ("pathzoo.cli",),
)
"""Units from the lowest layer up; units of one layer do not import each other.

``pathzoo`` is the package's top-level interface (``pathzoo/__init__.py``
alone); a unit named in :data:`UNIT_MODULES` is the modules listed there;
every other name covers its submodules too.
"""

UNIT_MODULES: dict[str, tuple[str, ...]] = {
    "report": ("pathzoo.analysis.report", "pathzoo.analysis.report_page", "pathzoo.analysis.tuning_report"),
}
"""Units made of named modules: the HTML report, which draws with :mod:`pathzoo.plotting`."""

ALLOWED: dict[tuple[str, str], str] = {
    ("pathzoo.core.scenario", "pathzoo.grid"): "a scenario's geometry queries and graph, built on first use",
    ("pathzoo.core.scenario", "pathzoo.rules"): "a scenario's segment and path queries, answered by the rules",
    ("pathzoo.plugins.external", "pathzoo_external"): "a program planner's declaration loads the bundled bridge "
                                                       "(planner code) on first use, in the worker only",
    ("pathzoo.analysis", "report"): "the analysis package's facade names write_report and render_report, "
                                    "loaded on first use; no analysis module imports the report",
}
"""(importing module, imported unit) pairs allowed across the layers, each explained in ``docs/layers.md``."""

PLUGIN_PACKAGES = frozenset(unit for layer in LAYERS for unit in layer if unit.startswith("pathzoo_"))


def module_name(path: Path) -> str:
    parts = list(path.relative_to(REPO_ROOT).with_suffix("").parts)
    if parts[0] in ("plugins", "scenarios"):
        parts = parts[1:]
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def unit_of(module: str) -> str | None:
    """The unit of ``module`` (longest matching name), or None for a module outside pathzoo and its plugins."""
    best, longest = None, -1
    for layer in LAYERS:
        for unit in layer:
            for name in UNIT_MODULES.get(unit, (unit,)):
                matches = module == name if name == "pathzoo" else module == name or module.startswith(name + ".")
                if matches and len(name) > longest:
                    best, longest = unit, len(name)
    return best


RANK = {unit: rank for rank, layer in enumerate(LAYERS) for unit in layer}


STRING_IMPORTERS = frozenset({"import_module", "__import__"})
"""Functions whose first argument, a literal module name, is an import (``importlib.import_module``, ``__import__``)."""


def _called_name(call: ast.Call) -> str | None:
    func = call.func
    return func.id if isinstance(func, ast.Name) else func.attr if isinstance(func, ast.Attribute) else None


def _lazy_table(call: ast.Call, tables: dict[str, ast.Dict]) -> ast.Dict | None:
    """The mapping literal given to ``lazy_getattr(package, mapping)``: written in the call or bound to a name."""
    if len(call.args) < 2:
        return None
    table = call.args[1]
    if isinstance(table, ast.Name):
        return tables.get(table.id)
    return table if isinstance(table, ast.Dict) else None


def string_imports(tree: ast.Module, module: str, package: str) -> list[tuple[int, str]]:
    """``(line, module)`` of the imports written as strings in ``tree`` (see the module docstring)."""
    tables = {target.id: node.value for node in tree.body if isinstance(node, ast.Assign)
              and isinstance(node.value, ast.Dict) for target in node.targets if isinstance(target, ast.Name)}
    found = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        name = _called_name(node)
        first = node.args[0] if node.args else None
        if name in STRING_IMPORTERS and isinstance(first, ast.Constant) and isinstance(first.value, str):
            target = first.value
            if target.startswith("."):
                target = package + target if target != "." else package
            found.append((node.lineno, target))
        elif name == "lazy_getattr" and (table := _lazy_table(node, tables)) is not None:
            base = first.value if isinstance(first, ast.Constant) and isinstance(first.value, str) else module
            found.extend((value.lineno, value.value if "." in value.value else f"{base}.{value.value}")
                         for value in table.values
                         if isinstance(value, ast.Constant) and isinstance(value.value, str))
    return found


def _package(path: Path) -> str:
    """The package that relative imports in ``path`` start from."""
    module = module_name(path)
    return module if path.name == "__init__.py" else module.rpartition(".")[0]


def statements(tree: ast.Module, package: str) -> Iterator[tuple[int, str, tuple[str, ...]]]:
    """``(line, module, names)`` of each ``import`` and ``from ... import`` in ``tree``, relative ones resolved.

    ``import a.b`` gives ``(line, "a.b", ())``; ``from a import b, c`` gives
    ``(line, "a", ("b", "c"))``, ``b`` and ``c`` being names of ``a`` or
    its submodules.
    """
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            yield from ((node.lineno, alias.name, ()) for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            yield node.lineno, target, tuple(alias.name for alias in node.names)


def imports(path: Path, text: str) -> list[tuple[int, str]]:
    """``(line, imported module)`` of every import in ``text``, the source of ``path``; relative ones resolved."""
    module, package = module_name(path), _package(path)
    tree = ast.parse(text, str(path))
    found = string_imports(tree, module, package)
    for line, target, names in statements(tree, package):
        found.append((line, target))
        # ``from pathzoo import analysis`` imports a submodule: judge the submodule
        found.extend((line, f"{target}.{name}") for name in names
                     if unit_of(f"{target}.{name}") not in (None, unit_of(target)))
    return found


def source_files() -> dict[Path, str]:
    """Every module of pathzoo and its plugins, with its source."""
    return {p: p.read_text(encoding="utf-8") for root in SOURCES for p in sorted((REPO_ROOT / root).rglob("*.py"))}


def layer_violations(sources: dict[Path, str]) -> list[str]:
    """One line per import against the layers."""
    out = []
    for path, text in sources.items():
        module = module_name(path)
        source = unit_of(module)
        assert source is not None, f"{path}: in no unit of LAYERS (add it here and to docs/layers.md)"
        for line, target in imports(path, text):
            unit = unit_of(target)
            if unit is None or unit == source or (module, unit) in ALLOWED:
                continue
            if unit in PLUGIN_PACKAGES and source.startswith("pathzoo."):
                problem = "pathzoo imports no plugin package"
            elif RANK[unit] >= RANK[source]:
                problem = "same layer" if RANK[unit] == RANK[source] else "higher layer"
            else:
                continue
            out.append(f"{path.relative_to(REPO_ROOT)}:{line}: {source} imports {target} ({problem})")
    return out


def test_no_module_imports_from_a_layer_above_its_own() -> None:
    found = layer_violations(source_files())
    assert not found, "imports against the layers of docs/layers.md:\n" + "\n".join(found)


def _type_checking_lines(tree: ast.Module) -> set[int]:
    """Lines inside ``if TYPE_CHECKING:`` blocks: imports for the type checker, never run."""
    lines: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and (
                (isinstance(node.test, ast.Name) and node.test.id == "TYPE_CHECKING")
                or (isinstance(node.test, ast.Attribute) and node.test.attr == "TYPE_CHECKING")):
            lines.update(range(node.body[0].lineno, (node.body[-1].end_lineno or node.body[-1].lineno) + 1))
    return lines


@functools.lru_cache(maxsize=4096)
def run_time_imports(path: Path, text: str, modules: frozenset[str]) -> list[tuple[int, str]]:
    """``(line, module)`` of the imports that ``text`` runs, at import time or later, among ``modules``.

    Module-level and function-level imports and those written as strings
    count, ``TYPE_CHECKING`` blocks do not; ``from package import name``
    imports the submodule ``package.name`` when there is one, else the
    package.
    """
    tree = ast.parse(text, str(path))
    module, package = module_name(path), _package(path)
    skip = _type_checking_lines(tree)
    found = string_imports(tree, module, package)
    for line, target, names in statements(tree, package):
        submodules = [f"{target}.{name}" for name in names if f"{target}.{name}" in modules]
        found.extend((line, name) for name in submodules)
        if not names or len(submodules) < len(names):
            found.append((line, target))
    out = []
    for line, target in found:
        while target and target not in modules:  # ``import a.b.c`` of a name in a.b: the module a.b
            target = target.rpartition(".")[0]
        if target and target != module and line not in skip:
            out.append((line, target))
    return out


def _reached(start: str, edges: dict[str, dict[str, int]]) -> dict[str, str]:
    """Every module reached from ``start``, with the one it was first reached from (breadth first)."""
    came_from: dict[str, str] = {}
    frontier = [start]
    while frontier:
        nxt = []
        for name in frontier:
            for target in sorted(edges[name]):
                if target not in came_from:
                    came_from[target] = name
                    nxt.append(target)
        frontier = nxt
    return came_from


def import_cycles(sources: dict[Path, str]) -> list[str]:
    """One line per import cycle among the modules of ``sources``: ``a.py:12 -> b.py:30 -> a``.

    A cycle whose imports all run at import time fails at once; one closed
    by an import inside a function or written as a string shows only when
    that function runs, and ties a lower module to a higher one meanwhile.
    Modules that reach each other round several loops are one line: the
    shortest loop through the first of them, and how many modules are tied.
    """
    paths = {module_name(path): path for path in sources}
    modules = frozenset(paths)
    edges: dict[str, dict[str, int]] = {name: {} for name in paths}
    back: dict[str, dict[str, int]] = {name: {} for name in paths}
    for name, path in paths.items():
        for line, target in run_time_imports(path, sources[path], modules):
            edges[name].setdefault(target, line)
            back[target].setdefault(name, line)
    out, placed = [], set()
    for start in sorted(paths):
        forward = _reached(start, edges)
        if start in placed or start not in forward:
            continue
        tied = (set(forward) & set(_reached(start, back))) | {start}
        placed |= tied
        cycle = [start]
        while forward[cycle[-1]] != start:
            cycle.append(forward[cycle[-1]])
        cycle = [start, *reversed(cycle[1:])]
        hops = [f"{paths[a].relative_to(REPO_ROOT)}:{edges[a][b]}" for a, b in zip(cycle, [*cycle[1:], start])]
        more = f" ({len(tied)} modules tied)" if len(tied) > len(cycle) else ""
        out.append(" -> ".join(hops) + f" -> {start}{more}")
    return out


def test_no_import_cycle() -> None:
    """No module imports one that imports it back, directly or round a longer loop, at any time of the run."""
    found = import_cycles(source_files())
    assert not found, "import cycles (move the shared piece to the lower module):\n" + "\n".join(found)


@pytest.mark.parametrize(("module", "code"), [
    ("pathzoo/cli/cmd_completion.py", "def _run(args):\n    from pathzoo.cli.main import build_parser\n"),
    ("pathzoo/io/geotiff.py", "def read_geotiff(path):\n    from pathzoo.io import dem\n"),
    ("pathzoo/harness/executors/warmup.py", "import importlib\n"
     "def preload():\n    importlib.import_module('pathzoo.harness.executors.process')\n"),
])
def test_the_cycle_check_finds_a_cycle_closed_at_run_time(module: str, code: str) -> None:
    """The run-time cycles this check was written for, planted again inside functions, are each found."""
    sources = source_files()
    path = REPO_ROOT / module
    assert not import_cycles(sources)
    found = import_cycles({**sources, path: sources[path] + "\n\n" + code})
    assert len(found) == 1 and f"{module}:" in found[0], found


def test_imports_for_the_type_checker_close_no_cycle() -> None:
    sources = source_files()
    path = REPO_ROOT / "pathzoo/core/budget.py"
    planted = "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from pathzoo.core.scenario import Scenario\n"
    assert import_cycles({**sources, path: sources[path] + "\n" + planted}) == []


def plugin_files_read(sources: dict[Path, str]) -> list[str]:
    """pathzoo's modules that name a plugin package in a string (``resources.files("pathzoo_scenarios")``)."""
    out = []
    for path, text in sources.items():
        module = module_name(path)
        if not module.startswith("pathzoo."):
            continue
        for node in ast.walk(ast.parse(text, str(path))):
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and (
                    node.value.split(".")[0].split("/")[0] in PLUGIN_PACKAGES) and (
                    (module, node.value.split(".")[0]) not in ALLOWED):
                out.append(f"{path.relative_to(REPO_ROOT)}:{node.lineno}: names the plugin package {node.value!r}")
    return out


def test_pathzoo_reads_no_plugin_package_by_name() -> None:
    """What a plugin ships reaches pathzoo through a hook (the papers' tables: ``pathzoo_paper_tables``)."""
    found = plugin_files_read(source_files())
    assert not found, "\n".join(found)
    planted = 'from importlib import resources\nfile = resources.files("pathzoo_scenarios") / "papers"\n'
    assert len(plugin_files_read({REPO_ROOT / "pathzoo/analysis/reproduction.py": planted})) == 1


def test_every_allowed_exception_is_used_and_explained() -> None:
    page = (REPO_ROOT / "docs" / "layers.md").read_text(encoding="utf-8")
    sources = source_files()
    by_module = {module_name(p): p for p in sources}
    for (module, unit), _why in ALLOWED.items():
        assert module in by_module, f"ALLOWED names {module}, which does not exist"
        path = by_module[module]
        assert any(unit_of(target) == unit for _, target in imports(path, sources[path])), (
            f"ALLOWED lets {module} import {unit}, which it no longer does: remove the exception")
        assert f"`{module}`" in page and f"`{unit}`" in page, f"docs/layers.md does not explain {module} -> {unit}"


@pytest.mark.parametrize(("module", "code", "expected"), [
    ("pathzoo/harness/executors/warmup.py", "from pathzoo.testing.scenarios import check_scenario\n", "same layer"),
    ("pathzoo/plotting/boxplots.py", "def f():\n    from pathzoo.analysis.report import write_report\n",
     "higher layer"),
    ("pathzoo/analysis/summary.py", "def f():\n    from pathzoo.plotting.figure import new_figure\n",
     "higher layer"),
    ("pathzoo/harness/worker.py", "def f():\n    import pathzoo_aco.acs\n", "pathzoo imports no plugin package"),
    ("pathzoo/grid/graph.py", "from ..rules import segments\n", "higher layer"),
    ("plugins/pathzoo_exact/astar.py", "from pathzoo.harness import run_experiment\n", "higher layer"),
    ("pathzoo/core/budget.py", "import pathzoo.grid\n", "higher layer"),
    ("pathzoo/grid/graph.py", "import importlib\nimportlib.import_module('pathzoo.harness.runner')\n",
     "higher layer"),
    ("pathzoo/grid/graph.py", "from importlib import import_module\ndef f():\n    import_module('pathzoo.harness')\n",
     "higher layer"),
    ("pathzoo/grid/graph.py", "def f():\n    return __import__('pathzoo.analysis.stats')\n", "higher layer"),
    ("pathzoo/core/__init__.py", "from pathzoo.lazy_names import lazy_getattr\n"
     "_WHERE = {'run_experiment': 'pathzoo.harness.runner'}\n__getattr__ = lazy_getattr(__name__, _WHERE)\n",
     "higher layer"),
    ("pathzoo/core/__init__.py", "from pathzoo.lazy_names import lazy_getattr\n"
     "__getattr__ = lazy_getattr('pathzoo.grid', {'Graph': 'graph'})\n", "higher layer"),
])
def test_the_check_finds_upward_imports(module: str, code: str, expected: str) -> None:
    """A planted import of each kind (module level, in a function, relative, written as a string) is reported."""
    found = layer_violations({REPO_ROOT / module: code})
    assert len(found) == 1 and expected in found[0], found


def test_a_lazy_table_of_own_submodules_is_no_violation() -> None:
    """Plain names in a ``lazy_getattr`` table are the package's own modules, resolved against it."""
    planted = ("from pathzoo.lazy_names import lazy_getattr\n"
               "_WHERE = {'read_map': 'movingai'}\n__getattr__ = lazy_getattr(__name__, _WHERE)\n")
    path = REPO_ROOT / "pathzoo/io/__init__.py"
    assert layer_violations({path: planted}) == []
    assert "pathzoo.io.movingai" in [target for _, target in imports(path, planted)]
