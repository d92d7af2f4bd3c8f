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
"""

from __future__ import annotations

import ast
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


def imports(path: Path, text: str) -> list[tuple[int, str]]:
    """``(line, imported module)`` of every import in ``text``, the source of ``path``; relative ones resolved."""
    module = module_name(path)
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    tree = ast.parse(text, str(path))
    found = string_imports(tree, module, package)
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found.extend((node.lineno, alias.name) for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            found.append((node.lineno, target))
            # ``from pathzoo import analysis`` imports a submodule: judge the submodule
            found.extend((node.lineno, f"{target}.{alias.name}") for alias in node.names
                         if unit_of(f"{target}.{alias.name}") not in (None, unit_of(target)))
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
