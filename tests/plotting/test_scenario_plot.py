"""plot_scenario on every scenario kind: orientation, markers, overlays and PNG output."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.collections import LineCollection
from matplotlib.patches import Circle

from pathzoo.core import MovingObstacle, Scenario
from pathzoo.core.errors import InvalidParameterError
from pathzoo.plotting.scenario import plot_scenario, save_scenario_png


def grid() -> Scenario:
    occ = np.zeros((4, 6), bool)
    occ[0, 5] = True  # top-right cell: row 0, col 5
    return Scenario(id="g", kind="grid2d", occupancy=occ, cell_size=2.0, start=[1.0, 1.0], goal=[11.0, 7.0])


def test_grid_image_follows_world_convention():
    ax = plot_scenario(grid(), np.array([[1.0, 1.0], [11.0, 7.0]]))
    img = ax.images[0]
    assert tuple(img.get_extent()) == (0.0, 12.0, 8.0, 0.0)
    assert ax.get_ylim() == (8.0, 0.0)  # y grows downwards
    # the blocked cell (row 0, col 5) is drawn where world point (11, 1) is
    data = img.get_array()
    assert data[0, 5] == 1 and data.sum() == 1
    lines = {ln.get_label(): ln for ln in ax.lines}
    assert lines["start"].get_xydata().tolist() == [[1.0, 1.0]]
    assert lines["goal"].get_xydata().tolist() == [[11.0, 7.0]]
    assert lines["path"].get_xydata().tolist() == [[1.0, 1.0], [11.0, 7.0]]


def test_graph_overlay_draws_each_undirected_edge_once():
    sc = grid()
    ax = plot_scenario(sc, show_graph=True)
    seg = [c for c in ax.collections if isinstance(c, LineCollection)][0].get_segments()
    assert len(seg) == sc.graph.n_edges // 2


def test_terrain_hillshade_with_blocked_overlay_and_colorbar():
    y, x = np.mgrid[0:10, 0:12]
    elev = np.hypot(x - 6, y - 5).astype(float)
    elev[0, 0] = np.nan
    occ = np.zeros((10, 12), bool)
    occ[5, 1] = True
    sc = Scenario(id="t", kind="terrain", occupancy=occ, elevation=elev, cell_size=1.0, start=[8.5, 8.5], goal=[2.5, 2.5])
    ax = plot_scenario(sc)
    shade, overlay = ax.images
    assert shade.get_array().shape[:2] == (10, 12)
    alpha = np.asarray(overlay.get_array())[..., 3]
    assert alpha[5, 1] > 0.5 and alpha[0, 0] > 0.5 and alpha.astype(bool).sum() == 2
    assert len(ax.figure.axes) == 2  # map + colour bar


def test_air_top_view_shows_highest_obstacle():
    occ = np.zeros((3, 4, 5), bool)
    occ[:2, 1, 1] = True
    occ[:, 2, 3] = True
    sc = Scenario(id="a", kind="air3d", occupancy=occ, cell_size=1.0, vertical_cell_size=2.0,
                  start=[0.5, 0.5, 1.0], goal=[4.5, 3.5, 5.0])
    ax = plot_scenario(sc, np.array([[0.5, 0.5, 1.0], [4.5, 3.5, 5.0]]))
    top = np.asarray(ax.images[0].get_array())
    assert top[1, 1] == 4.0 and top[2, 3] == 6.0 and top[0, 0] == 0.0
    assert np.asarray(ax.images[1].get_array())[2, 3, 3] > 0  # column blocked at every height


def test_dynamic_obstacles_at_t0_and_trajectories():
    ob = MovingObstacle(radius=0.5, waypoints=[[2.0, 2.0], [8.0, 2.0]], speed=1.0, phase_s=2.0)
    occ = np.zeros((5, 10), bool)
    sc = Scenario(id="d", kind="dynamic", occupancy=occ, cell_size=1.0, start=[0.5, 4.5], goal=[9.5, 4.5],
                  moving_obstacles=(ob,))
    ax = plot_scenario(sc)
    disc = [p for p in ax.patches if isinstance(p, Circle)][0]
    assert disc.center == pytest.approx((4.0, 2.0)) and disc.radius == 0.5
    traj = [ln for ln in ax.lines if ln.get_label() == "obstacle path"][0]
    assert traj.get_xydata().tolist() == [[2.0, 2.0], [8.0, 2.0]]


def test_draws_on_given_axes_and_saves_png(tmp_path):
    ax0 = plot_scenario(grid())
    ax = plot_scenario(grid(), ax=ax0, legend=False, title="again")
    assert ax is ax0 and ax.get_title() == "again"
    out = save_scenario_png(grid(), tmp_path / "sub" / "g.png", planned_path=np.array([[1.0, 1.0], [11.0, 7.0]]))
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with pytest.raises(InvalidParameterError, match="path must be"):
        plot_scenario(grid(), np.array([1.0, 2.0]))
