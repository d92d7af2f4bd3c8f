"""Random start and goal cells that are free and connected, so generated scenarios are solvable."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from scipy.sparse.csgraph import connected_components

from pathzoo.core.errors import InvalidScenarioError
from pathzoo.generators.checks import check_number, check_seed

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario

__all__ = ["ENDPOINTS_VERSION", "pick_endpoints", "with_random_endpoints"]

ENDPOINTS_VERSION = 1
"""Bumped whenever the same scenario and seed would give other endpoints."""


def pick_endpoints(
    scenario: "Scenario", rng: np.random.Generator, *, min_separation: float = 0.5
) -> tuple[np.ndarray, np.ndarray]:
    """Draw a start and a goal cell centre that the scenario's graph connects both ways.

    Both cells come from the largest strongly connected component of
    ``scenario.graph`` (strong, because terrain edges can be one-way when the
    climb and descent limits differ). The start is uniform over that
    component; the goal is uniform over the component's cells whose straight
    distance from the start is at least ``min_separation`` times the largest
    such distance, which keeps the problems from being trivially short.
    Moving obstacles are not considered.

    Parameters
    ----------
    scenario : Scenario
        Any scenario of the map (its own start and goal are ignored).
    rng : numpy.random.Generator
        Source of randomness.
    min_separation : float
        In ``(0, 1]``.

    Returns
    -------
    start, goal : ndarray
        World coordinates of the two cell centres.

    Raises
    ------
    InvalidScenarioError
        When no two free cells are connected.
    """
    min_separation = check_number(min_separation, "min_separation", low=0.0, high=1.0, low_open=True)
    _, labels = connected_components(scenario.graph.to_sparse(), directed=True, connection="strong")
    free = ~scenario.blocked.ravel()
    sizes = np.bincount(labels[free], minlength=labels.max() + 1)
    largest = int(sizes.argmax())
    if sizes[largest] < 2:
        raise InvalidScenarioError("no two free cells are connected; cannot place a start and a goal", field="map")
    nodes = np.flatnonzero(free & (labels == largest))
    start = int(rng.choice(nodes))
    points = scenario.point_of(nodes)
    dist = np.linalg.norm(points - scenario.point_of(np.array([start])), axis=1)
    goal = int(rng.choice(nodes[dist >= min_separation * dist.max()]))
    return scenario.point_of(np.array([start]))[0], scenario.point_of(np.array([goal]))[0]


def with_random_endpoints(scenario: "Scenario", seed: int, *, min_separation: float = 0.5) -> "Scenario":
    """A copy of ``scenario`` with endpoints from :func:`pick_endpoints`, recorded in its metadata.

    The endpoints are drawn from the first child of ``SeedSequence(seed)``,
    so they do not reuse the random stream a generator drew the map from
    with the same seed. ``metadata["endpoints"]`` records the method, its
    version, the seed and ``min_separation``.
    """
    seed = check_seed(seed, "endpoint_seed")
    rng = np.random.default_rng(np.random.SeedSequence(seed).spawn(1)[0])
    start, goal = pick_endpoints(scenario, rng, min_separation=min_separation)
    record = {"method": "pick_endpoints", "version": ENDPOINTS_VERSION, "seed": seed, "min_separation": min_separation}
    return scenario.with_endpoints(start, goal, metadata={**scenario.metadata, "endpoints": record})
