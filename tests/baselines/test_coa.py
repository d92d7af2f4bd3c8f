"""swarm.coa, equation by equation (Rajabioun 2011's steps as docs/planners/swarm.coa.md numbers them)."""

import numpy as np
import pytest

from pathzoo import Budget, InvalidParameterError, make_planner
from pathzoo.testing import check_scenario
from pathzoo_baselines.coa import (
    egg_counts,
    egg_laying_radii,
    goal_habitat,
    immigrate,
    lay_eggs,
    limit_population,
    surviving_eggs,
)


def test_egg_counts_are_uniform_integers_in_the_closed_range():
    eggs = egg_counts(np.random.default_rng(0), 5000, 5, 20)
    assert eggs.min() == 5 and eggs.max() == 20
    assert np.allclose(np.bincount(eggs)[5:] / 5000, 1 / 16, atol=0.015)


def test_egg_laying_radius_is_alpha_times_share_of_eggs_times_the_variable_range():
    eggs = np.array([5, 10, 25])
    span = np.array([32.0, 16.0])
    elr = egg_laying_radii(eggs, alpha=2.0, span=span)
    assert elr.shape == (3, 2)
    np.testing.assert_allclose(elr[1], 2.0 * 10 / 40 * span)
    np.testing.assert_allclose(elr.sum(axis=0), 2.0 * span)  # the shares add up to one


def test_eggs_are_laid_inside_each_habitats_radius_and_counted_per_habitat():
    rng = np.random.default_rng(1)
    habitats = np.array([[10.0, 10.0, 3.0], [20.0, 5.0, 1.0]])
    eggs = np.array([300, 200])
    radii = np.array([[2.0, 1.0, 0.5], [4.0, 4.0, 4.0]])
    laid, owner = lay_eggs(rng, habitats, eggs, radii)
    assert laid.shape == (500, 3) and np.bincount(owner).tolist() == [300, 200]
    scaled = (laid - habitats[owner]) / radii[owner]
    norm = np.linalg.norm(scaled, axis=1)
    assert norm.max() <= 1.0 + 1e-12  # inside the ellipsoid of semi-axes ELR
    assert norm.max() > 0.9 and norm.min() < 0.2  # spread over the radius, not on its rim


def test_the_worst_tenth_of_the_eggs_is_killed():
    costs = np.array([5.0, 1.0, 9.0, 3.0, 7.0, 2.0, 8.0, 4.0, 6.0, 10.0, 0.5, 11.0, 12.0, 13.0, 14.0, 15.0,
                      16.0, 17.0, 18.0, 19.0])
    keep = surviving_eggs(costs, 0.1)
    assert sorted(costs[~keep].tolist()) == [18.0, 19.0]
    assert surviving_eggs(costs, 0.0).all()


def test_population_control_keeps_the_best_cheapest_first():
    habitats = np.arange(10.0).reshape(5, 2)
    costs = np.array([3.0, 1.0, 4.0, 1.5, 9.0])
    kept, kept_costs = limit_population(habitats, costs, 3)
    assert kept_costs.tolist() == [1.0, 1.5, 3.0]
    np.testing.assert_array_equal(kept, habitats[[1, 3, 0]])


def test_the_goal_is_the_best_habitat_of_the_group_with_the_best_mean():
    habitats = np.array([[0.0], [1.0], [2.0], [10.0], [11.0]])
    costs = np.array([0.5, 9.0, 9.0, 2.0, 2.5])  # group 0 holds the best single habitat, group 1 the best mean
    labels = np.array([0, 0, 0, 1, 1])
    assert goal_habitat(habitats, costs, labels).tolist() == [10.0]


def test_immigration_moves_each_variable_a_random_share_of_the_way_to_the_goal():
    habitats = np.array([[0.0, 10.0], [4.0, 4.0]])
    goal = np.array([2.0, 2.0])
    moved = immigrate(np.random.default_rng(5), habitats, goal, motion_coeff=2.0)
    factor = 2.0 * np.random.default_rng(5).random(habitats.shape)  # F = motion_coeff * U(0, 1), per variable
    np.testing.assert_allclose(moved, habitats + factor * (goal - habitats))
    one = immigrate(np.random.default_rng(6), habitats, goal, motion_coeff=1.0)
    low, high = np.minimum(habitats, goal), np.maximum(habitats, goal)
    assert np.all((one >= low) & (one <= high))  # with coefficient 1 it never overshoots


def test_parameters_are_checked_together():
    with pytest.raises(InvalidParameterError, match="min_eggs"):
        make_planner("swarm.coa", min_eggs=9, max_eggs=3)


def test_one_generation_costs_the_eggs_laid_plus_the_migrants():
    planner = make_planner("swarm.coa", cuckoos=4, max_cuckoos=6, min_eggs=3, max_eggs=3)
    result = planner.plan(check_scenario("grid2d"), budget=Budget(iterations=1), rng=np.random.default_rng(0))
    # 4 initial habitats; 4 x 3 eggs; 16 habitats capped to 6, of which 5 migrate (the best stays)
    assert result.iterations == 1 and result.evaluations == 4 + 12 + 5
