"""The HTML report: self-contained, every section present, figures embedded or linked, from frames and from a database."""

from __future__ import annotations

import re
from html.parser import HTMLParser

import numpy as np
import pytest

import pathzoo
from pathzoo.analysis.report import render_report, write_report
from pathzoo.analysis.synthetic import make_runs, random_history, random_runs
from pathzoo.core.errors import InvalidParameterError
from pathzoo.harness.store import read_path, read_runs


class Tags(HTMLParser):
    """Collect start tags and check that every non-void tag is closed."""

    VOID = {"meta", "img", "br", "link", "hr", "input"}

    def __init__(self) -> None:
        super().__init__()
        self.tags: list[tuple[str, dict]] = []
        self.stack: list[str] = []

    def handle_starttag(self, tag, attrs):
        self.tags.append((tag, dict(attrs)))
        if tag not in self.VOID:
            self.stack.append(tag)

    def handle_endtag(self, tag):
        assert self.stack and self.stack[-1] == tag, f"</{tag}> closes <{self.stack[-1] if self.stack else None}>"
        self.stack.pop()


def parse(doc: str) -> Tags:
    p = Tags()
    p.feed(doc)
    p.close()
    assert p.stack == []
    return p


def assert_offline(doc: str) -> None:
    tags = parse(doc).tags
    names = {t for t, _ in tags}
    assert not names & {"script", "link", "iframe", "object"}
    for tag, attrs in tags:
        for key in ("src", "href"):
            value = attrs.get(key)
            if value is not None:
                assert value.startswith(("data:image/png;base64,", "#", "figures/")), value
    assert "url(" not in doc and "@import" not in doc


@pytest.mark.slow
def test_report_from_frames_is_self_contained():
    runs = random_runs(("a", "b"), ("s1", "s2"), n_seeds=8, seed=3)
    page = render_report(runs, random_history(runs), reference="a", meta={"note": "x<y"}, max_scenarios=1,
                         detail=["s2"])
    doc = page.html("t")
    assert_offline(doc)
    for anchor in ("outcomes", "leaderboard", "comparison", "ranks", "boxes", "scenarios", "anytime", "metrics",
                   "failures"):
        assert f'id="{anchor}"' in doc and f'href="#{anchor}"' in doc
    assert "x&lt;y" in doc  # escaped
    assert "2 scenarios: figures of their own for s2 (name scenarios with --scenario" in doc
    imgs = re.findall(r'<img src="data:image/png;base64,', doc)
    # CD diagram, 4 box plots across scenarios (length, planning_time, energy, turns) and 4 of the named
    # scenario s2, its convergence figure, ECDF
    boxes = [f"box-{m}{tail}" for m in ("length", "planning_time", "energy", "turns") for tail in ("", "-named")]
    assert len(imgs) == 11  # embedded; only their SVG and PDF copies are files
    assert sorted(page.files) == sorted(f"{i:02d}-{n}.{x}" for i, n in enumerate(
        ["cd", *boxes, "conv-s2", "ecdf"]) for x in ("svg", "pdf"))
    assert "Leaderboard: length [m], lower is better" in doc and "w/t/l of a" in doc


def test_inline_runs_are_flagged_as_not_isolated():
    runs = make_runs({"s1": {"a": [1.0, 1.1], "b": [2.0, 2.1]}})
    assert "not isolated" not in render_report(runs.assign(isolated=True)).html("t")
    doc = render_report(runs.assign(isolated=[True, False, True, True])).html("t")
    assert "1 of 4 runs ran inline" in doc and "not isolated" in doc


@pytest.mark.slow
def test_power_warning_and_empty_runs():
    few = make_runs({"s1": {"a": [1.0, 1.1, 1.2], "b": [2.0, 2.1, 2.2]},
                     "s2": {"a": [1.0, 1.1, 1.2], "b": [2.0, 2.1, 2.2]}})
    doc = render_report(few, reference="a").html("t")
    assert "marked n/s: with 3 run(s) per planner no result can be significant" in doc
    assert "run at least 6 seeds" in doc
    enough = make_runs({"s1": {"a": list(np.arange(8.0)), "b": list(np.arange(8.0) + 10)}})
    assert "marked n/s" not in render_report(enough, reference="a").html("t")
    with pytest.raises(InvalidParameterError, match="runs is empty"):
        render_report(few.iloc[:0])


@pytest.mark.slow
def test_write_report_from_database(small_db, tmp_path):
    db, sc = small_db
    index = write_report(db, tmp_path / "rep", scenarios=[sc], embed=False)
    doc = index.read_text(encoding="utf-8")
    assert_offline(doc)
    linked = re.findall(r'<img src="(figures/[^"]+)"', doc)
    assert linked and all((index.parent / f).is_file() for f in linked)
    assert any("paths" in f for f in linked)  # the map with both planners' paths
    assert "pathzoo report: tiny" in doc and str(db.resolve()) in doc
    assert "Every run succeeded." in doc
    assert "Against each planner&#39;s own optimum" in doc and "graph optimum" in doc
    # without the Scenario object the map is missing, and the page says why
    runs = read_runs(db, "tiny")
    doc = render_report(runs, path_of=lambda key: read_path(db, "tiny", key)[0]).html("t")
    assert "No map for testing.grid2d" in doc and "pass scenarios=" in doc


def test_write_report_needs_an_experiment_name_when_several(small_db, tmp_path):
    db, sc = small_db
    pathzoo.run(["exact.dijkstra"], [sc], seeds=1, db=db, executor="inline", progress=False, experiment="other")
    with pytest.raises(InvalidParameterError, match="holds 2 experiments"):
        write_report(db, tmp_path / "x")


def test_every_figure_is_also_written_as_svg_and_pdf_beside_the_report(tmp_path):
    db = tmp_path / "r.sqlite"
    pathzoo.run(["exact.astar", "exact.dijkstra"], ["gant.fig7"], seeds=2, db=db, executor="inline", progress=False)
    index = write_report(db, tmp_path / "rep")
    doc = index.read_text()
    links = re.findall(r'href="(figures/[^"]+)"', doc)
    svgs = [link for link in links if link.endswith(".svg")]
    pdfs = [link for link in links if link.endswith(".pdf")]
    n_figures = doc.count("<figure>")
    assert n_figures >= 3 and len(svgs) == len(pdfs) == n_figures
    for svg, pdf in zip(svgs, pdfs):
        assert (tmp_path / "rep" / svg).read_text().lstrip().startswith(("<?xml", "<svg"))
        assert (tmp_path / "rep" / pdf).read_bytes().startswith(b"%PDF")
    assert "exact.astar" in (tmp_path / "rep" / svgs[0]).read_text()  # text kept as text, not paths


def test_untestable_comparisons_show_bare_numbers():
    from pathzoo.analysis.comparison_table import format_paper_table, paper_table

    runs = random_runs(("a", "b", "c"), ("s1", "s2"), n_seeds=3, seed=5)  # 3 runs: nothing can reach alpha
    text = format_paper_table(paper_table(runs, "a", ["length"]))
    rows = [line for line in text.splitlines() if line.startswith(("s1", "s2"))]
    assert rows and not any("n/s" in line for line in rows)
    assert "no mark: not testable with this many runs" in text
