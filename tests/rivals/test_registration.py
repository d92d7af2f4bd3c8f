"""The rivals plugin registers its planners through the ``pathzoo.planners`` entry points, like the built-in families."""

from __future__ import annotations

import importlib.metadata as md

import pathzoo


def test_rivals_come_through_the_entry_point():
    assert "rivals" in {ep.name for ep in md.entry_points(group="pathzoo.planners")}
    ids = {entry.obj.id for entry in pathzoo.list_plugins("planners")}
    assert {"exact.zstar", "swarm.mosfla", "search.movns"} <= ids
