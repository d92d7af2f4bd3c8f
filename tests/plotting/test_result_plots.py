"""Box plots, convergence curves, time-to-target ECDFs, CD diagrams and path overlays draw what the data says."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from matplotlib.collections import PolyCollection

from pathzoo.analysis.anytime import convergence_curves, time_to_target
from pathzoo.analysis.ranks import friedman
from pathzoo.analysis.synthetic import make_runs, random_history, random_runs
from pathzoo.core import Scenario
from pathzoo.core.errors import InvalidParameterError
from pathzoo.plotting.boxplots import plot_metric_boxes, plot_metric_panels
from pathzoo.plotting.cd_diagram import plot_cd_diagram
from pathzoo.plotting.convergence import plot_convergence
from pathzoo.plotting.ecdf import plot_time_to_target_ecdf
from pathzoo.plotting.figure import new_figure, planner_colors, png_bytes
from pathzoo.plotting.paths import plot_paths

LEN = dict(direction="min", unit="m")  # no registry needed


@pytest.fixture(scope="module")
def runs() -> pd.DataFrame:
    return random_runs(("a", "b", "c"), ("s1", "s2"), n_seeds=8, seed=11)


def test_boxes_and_success_annotations():
    runs = make_runs({"s1": {"a": [1.0, 2.0, 3.0, np.nan], "b": [2.0, 3.0, 4.0, 5.0]},
                      "s2": {"a": [1.0, 1.0, 1.0, 1.0], "b": [np.nan] * 4}})
    ax = plot_metric_boxes(runs, "length", **LEN)
    notes = sorted(t.get_text() for t in ax.texts)
    assert notes == ["0%", "75%"]
    assert [t.get_text() for t in ax.get_xticklabels()] == ["s1", "s2"]
    assert ax.get_ylabel() == "length [m]" and "lower is better" in ax.get_title()
    assert ax.get_yscale() == "linear"
    assert png_bytes(ax.figure)[:4] == b"\x89PNG"


def test_convergence_lines_are_the_medians(runs):
    history = random_history(runs)
    ax = plot_convergence(history, runs, "s1", x="time_s")
    sub = runs[runs.scenario == "s1"]
    curves = convergence_curves(history[history.run_key.isin(sub.run_key)], sub, x="time_s")
    assert len(ax.lines) == 3 and len([c for c in ax.collections if isinstance(c, PolyCollection)]) == 3
    for line, (_, c) in zip(ax.lines, curves.groupby("config", sort=True)):
        np.testing.assert_allclose(line.get_ydata(), c["median"].to_numpy())
    assert ax.get_xlabel() == "time [s]" and ax.get_xscale() == "linear"
    t = history.loc[history.run_key.isin(sub.run_key), "time_s"]
    auto = plot_convergence(history, runs, "s1", x="time_s", log=None)
    assert auto.get_xscale() == ("log" if t.max() > 20 * t[t > 0].min() else "linear")
    # a scenario where nothing succeeded: no curve, a note, and a linear axis even when log was asked
    failed = runs[runs.scenario == "s2"].assign(status="failed", valid=False)
    ax = plot_convergence(history[history.run_key.isin(failed.run_key)], failed, x="time_s", log=True)
    assert [t.get_text() for t in ax.texts] == ["no run holds a solution"] and ax.get_xscale() == "linear"
    png_bytes(ax.figure)
    with pytest.raises(InvalidParameterError, match="scenario is required"):
        plot_convergence(history, runs)
    with pytest.raises(InvalidParameterError, match="scenario 'zz'"):
        plot_convergence(history, runs, "zz")


def test_ecdf_reaches_the_share_of_hits(runs):
    history = random_history(runs, seed=2)
    ax = plot_time_to_target_ecdf(history, runs, eps=0.05)
    hits = time_to_target(history, runs, eps=0.05)
    for line in ax.lines:
        cfg = line.get_label().split(" (")[0]
        h = hits[(hits.config == cfg) & hits.comparable]
        assert line.get_ydata()[-1] == pytest.approx(np.isfinite(h["hit"]).mean())
        assert f"n={len(h)}" in line.get_label()


def test_panels_give_each_scenario_its_own_axis():
    runs = make_runs({"small": {"a": [60.0, 61.0], "b": [62.0, 63.0]},
                      "large": {"a": [400.0, 410.0], "b": [420.0, 430.0]}})
    fig = plot_metric_panels(runs, "length")
    shown = [ax for ax in fig.axes if ax.get_visible()]
    assert [ax.get_title() for ax in shown] == ["large", "small"]
    (lo1, hi1), (lo2, hi2) = (ax.get_ylim() for ax in shown)
    assert lo1 > 300 and hi2 < 100  # no panel squashed under the other's range
    for ax in shown:  # every panel names its planners and its axes
        assert [t.get_text() for t in ax.get_xticklabels()] == ["a", "b"]
        assert ax.get_xlabel() == "planner" and ax.get_ylabel() == "length [m]"


def test_one_far_outlier_does_not_squash_the_boxes():
    runs = make_runs({"s": {"a": [10.0, 10.5, 11.0, 11.5, 12.0, 1000.0], "b": [20.0, 20.5, 21.0, 21.5, 22.0, 22.5]}})
    fig = plot_metric_panels(runs, "length")
    ax = fig.axes[0]
    lo, hi = ax.get_ylim()
    assert 5 < lo < 10 and 22.5 < hi < 30  # the whiskers, with a margin; the outlier is off the axis
    assert [t.get_text() for t in ax.texts] == ["1 at 1000"]


def test_a_spread_without_far_outliers_keeps_every_point_in_view():
    runs = make_runs({"s": {"a": [10.0, 12.0, 14.0, 30.0], "b": [20.0, 21.0, 22.0, 23.0]}})
    ax = plot_metric_panels(runs, "length").axes[0]
    assert ax.get_ylim()[1] > 30 and not ax.texts


def test_a_panel_without_values_says_so_instead_of_crashing():
    # length_ratio is NaN on a dynamic scenario (no reference length): the report must still draw the others
    runs = make_runs({"static": {"a": [1.0, 1.1], "b": [1.2, 1.3]},
                      "dynamic": {"a": [np.nan, np.nan], "b": [np.nan, np.nan]}})
    runs.loc[runs["scenario"] == "dynamic", "status"] = "solved"
    runs.loc[runs["scenario"] == "dynamic", "valid"] = True
    fig = plot_metric_panels(runs, "length")
    texts = [t.get_text() for ax in fig.axes for t in ax.texts]
    assert any(t.startswith("no length value") for t in texts)


def test_palette_is_distinct_and_stable():
    labels = [f"p{i:02d}" for i in range(30)]
    colors = planner_colors(labels)
    assert len({tuple(np.round(c, 6)) for c in colors.values()}) == 30
    assert planner_colors(labels[:5]) == {k: colors[k] for k in labels[:5]}  # sorted-order assignment


def _lab(rgb):
    """CIELAB (D65) of an sRGB colour."""
    c = np.asarray(rgb, float)
    c = np.where(c > 0.04045, ((c + 0.055) / 1.055) ** 2.4, c / 12.92)
    xyz = np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]]) @ c
    xyz = xyz / [0.95047, 1.0, 1.08883]
    f = np.where(xyz > 216 / 24389, np.cbrt(xyz), (24389 / 27 * xyz + 16) / 116)
    return np.array([116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])])


def test_the_default_experiments_planners_get_clearly_different_colours():
    """The newcomer's report drew mmas and anyangle both orange, astar and pso both pink."""
    import itertools

    labels = ["aco.acs", "aco.as", "aco.dsaco", "aco.fgdaco", "aco.gant", "aco.ggaco", "aco.iaca", "aco.mmas",
              "exact.astar", "exact.dijkstra", "exact.thetastar", "swarm.pso"]
    lab = [_lab(c) for c in planner_colors(labels).values()]
    closest = min(np.linalg.norm(a - b) for a, b in itertools.combinations(lab, 2))
    assert closest >= 25  # CIELAB distance; the old palette had 20.7 (two pinks)


def test_cd_diagram_labels_ranks_and_cd():
    rows = {f"s{i}": {"a": [1.0], "b": [2.0], "c": [3.0]} for i in range(5)}
    res = friedman(make_runs(rows), "length", direction="min")
    ax = plot_cd_diagram(res)
    texts = [t.get_text() for t in ax.texts]
    assert "a (1.00)" in texts and "(3.00) c" in texts and any(t.startswith("CD = 1.5") for t in texts)
    assert f"p = {res.pvalue:.3g}" in ax.get_title()


def test_paths_overlay():
    sc = Scenario(id="g", kind="grid2d", occupancy=np.zeros((5, 5), bool), cell_size=1.0,
                  start=[0.5, 0.5], goal=[4.5, 4.5])
    p1 = np.array([[0.5, 0.5], [4.5, 4.5]])
    p2 = np.array([[0.5, 0.5], [4.5, 0.5], [4.5, 4.5]])
    ax = plot_paths(sc, {"one": p1, "two": p2})
    lines = {ln.get_label(): ln for ln in ax.lines}
    assert lines["two"].get_xydata().tolist() == p2.tolist()
    assert lines["one"].get_color() != lines["two"].get_color()
    legend = ax.figure.legends[0]  # a figure legend below the map: the figure holds only this plot
    assert [t.get_text() for t in legend.get_texts()] == ["start", "goal", "one", "two"]
    # on a figure with several plots the legend stays with its axes
    fig = new_figure()
    left, right = fig.subplots(1, 2)
    plot_paths(sc, {"one": p1}, ax=right)
    assert right.get_legend() is not None and not fig.legends
