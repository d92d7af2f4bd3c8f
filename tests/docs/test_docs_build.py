"""The Sphinx documentation builds offline with no warnings, and every gallery example runs.

The build runs on a fresh copy of ``docs/`` (the rest of the repository is
linked beside it), so sphinx-gallery executes every example instead of
reusing outputs cached in the working tree, and nothing is written into the
checkout. Examples use the tiny budgets of ``PATHZOO_DOCS_BUDGET=tiny``.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]
DOCS = REPO_ROOT / "docs"
GALLERY = REPO_ROOT / "examples" / "gallery"
GENERATED = ("_build", "auto_examples", "gen_modules", "sg_execution_times.rst", "__pycache__")
BUILD_TIMEOUT_S = 900


@pytest.fixture(scope="module")
def built_docs(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    """Build the HTML docs from a fresh copy; return ``(source dir, html dir)``."""
    root = tmp_path_factory.mktemp("docs-build")
    for entry in REPO_ROOT.iterdir():
        if entry.name not in ("docs", ".git"):
            (root / entry.name).symlink_to(entry)
    src = root / "docs"
    shutil.copytree(DOCS, src, ignore=shutil.ignore_patterns(*GENERATED))
    out = root / "html"
    env = {**os.environ, "PATHZOO_DOCS_BUDGET": "tiny", "MPLBACKEND": "agg"}
    cmd = [sys.executable, "-m", "sphinx", "-b", "html", "-W", "--keep-going", "-q", str(src), str(out)]
    proc = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=BUILD_TIMEOUT_S)
    if proc.returncode != 0:
        pytest.fail(f"sphinx-build failed (exit {proc.returncode}):\n{proc.stderr[-6000:]}", pytrace=False)
    return src, out


@pytest.mark.slow
def test_every_markdown_page_is_built(built_docs: tuple[Path, Path]) -> None:
    _, out = built_docs
    pages = sorted(p.relative_to(DOCS).with_suffix(".html") for p in DOCS.rglob("*.md"))
    assert pages, "no Markdown pages found under docs/"
    missing = [str(p) for p in pages if not (out / p).is_file()]
    assert not missing, f"pages not built: {missing}"
    assert (out / "index.html").is_file()


@pytest.mark.slow
def test_every_gallery_example_ran(built_docs: tuple[Path, Path]) -> None:
    src, out = built_docs
    examples = sorted(GALLERY.glob("plot_*.py"))
    assert len(examples) >= 5
    for example in examples:
        name = example.stem
        rst = (src / "auto_examples" / f"{name}.rst").read_text(encoding="utf-8")
        assert "Total running time of the script" in rst, f"{name} did not run"
        figures = sorted((src / "auto_examples" / "images").glob(f"sphx_glr_{name}_*.png"))
        assert figures, f"{name} drew no figure"
        assert all(f"images/{f.name}" in rst for f in figures)
        assert (out / "auto_examples" / f"{name}.html").is_file()
    index = (out / "auto_examples" / "index.html").read_text(encoding="utf-8")
    assert all(f"{e.stem}.html" in index for e in examples), "an example is missing from the gallery index"


@pytest.mark.slow
def test_api_reference_covers_the_public_packages(built_docs: tuple[Path, Path]) -> None:
    _, out = built_docs
    pages = {p.stem for p in (out / "gen_modules").glob("*.html")}
    public = {
        "pathzoo", "pathzoo.core", "pathzoo.io", "pathzoo.generators", "pathzoo.harness", "pathzoo.analysis",
        "pathzoo.plotting", "pathzoo.testing", "pathzoo.metrics", "pathzoo_exact", "pathzoo_aco",
        "pathzoo_baselines", "pathzoo_ompl", "pathzoo_rivals", "pathzoo_scenarios", "pathzoo_external",
    }
    assert public <= pages, f"no API page for {sorted(public - pages)}"
    top = (out / "gen_modules" / "pathzoo.html").read_text(encoding="utf-8")
    for name in ("load_scenario", "make_planner", "run", "Scenario", "Planner"):
        assert f'id="pathzoo.{name}"' in top, f"pathzoo.{name} is not documented on the top-level page"


@pytest.mark.slow
def test_equations_are_mathematics_served_offline(built_docs: tuple[Path, Path]) -> None:
    _, out = built_docs
    page = (out / "planners" / "aco.as.html").read_text(encoding="utf-8")
    assert 'class="math' in page and "\\tau_{ij}" in page  # MyST dollar maths, left for MathJax to typeset
    assert "_static/mathjax/tex-svg.js" in page and "://" not in page.split("tex-svg.js")[0].rsplit('"', 1)[-1]
    mathjax = out / "_static" / "mathjax" / "tex-svg.js"
    assert mathjax.is_file() and mathjax.stat().st_size > 1_000_000  # the full single-file build, not a stub
