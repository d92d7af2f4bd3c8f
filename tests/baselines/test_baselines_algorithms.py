"""Mechanisms of the individual baselines: Mantegna's Lévy steps and the fuzzy rate controller."""

import math

import numpy as np
import pytest

from pathzoo_baselines.cuckoo import mantegna_steps
from pathzoo_baselines.fuzzy import FuzzyRateController, population_diversity


@pytest.mark.parametrize("beta", [1.2, 1.5, 1.8])
def test_mantegna_steps_have_a_levy_tail_of_exponent_beta(beta):
    steps = np.abs(mantegna_steps(np.random.default_rng(0), (400_000,), beta))
    tail = np.sort(steps)[-4000:]  # Hill estimator on the top 1 %
    hill = 1.0 / np.mean(np.log(tail / tail[0]))
    assert hill == pytest.approx(beta, abs=0.15)


def test_mantegna_scale_is_the_published_sigma_for_beta_1_5():
    """sigma_u(1.5) = 0.6966 (Yang's value): our steps match u / |v|^(2/3) with u ~ N(0, 0.6966^2)."""
    from scipy.stats import ks_2samp

    ours = mantegna_steps(np.random.default_rng(3), (50_000,), 1.5)
    rng = np.random.default_rng(4)
    reference = rng.normal(0, 0.6966, 50_000) / np.abs(rng.normal(0, 1, 50_000)) ** (1 / 1.5)
    assert ks_2samp(ours, reference).pvalue > 0.01
    wrong = rng.normal(0, 1.0, 50_000) / np.abs(rng.normal(0, 1, 50_000)) ** (1 / 1.5)
    assert ks_2samp(ours, wrong).pvalue < 0.01  # the check can tell a wrong scale apart


def test_diversity_reads_one_for_a_uniform_population_and_zero_for_clones():
    rng = np.random.default_rng(2)
    low, high = np.zeros(6), np.full(6, 10.0)
    assert population_diversity(rng.uniform(0, 10, (2000, 6)), low, high, False) == pytest.approx(1.0, abs=0.03)
    assert population_diversity(np.full((50, 6), 3.0), low, high, False) == 0.0
    moves = rng.integers(0, 8, (4000, 6))
    assert population_diversity(moves, low, np.full(6, 7.0), True) == pytest.approx(1.0, abs=0.03)
    assert population_diversity(np.zeros((50, 6)), low, np.full(6, 7.0), True) == 0.0


def _controller():
    return FuzzyRateController(lambda population: 0.5, cxpb_range=(0.5, 1.0), mutpb_range=(0.05, 0.5),
                               window=2, progress_scale=0.05)


def test_stalled_converged_population_gets_mutation_diverse_one_gets_crossover():
    ctl = _controller()
    cx_stalled, mut_stalled = ctl.infer(0.0, 0.0)
    cx_diverse, mut_diverse = ctl.infer(1.0, 0.0)
    assert mut_stalled > 0.4 and cx_stalled < 0.6
    assert cx_diverse > 0.9 and mut_diverse < 0.15
    for d in np.linspace(0, 1, 7):
        for p in np.linspace(0, 1, 7):
            cx, mut = ctl.infer(d, p)
            assert 0.5 <= cx <= 1.0 and 0.05 <= mut <= 0.5
    # mutation never rises with diversity at fixed progress
    muts = [ctl.infer(d, 0.5)[1] for d in np.linspace(0, 1, 11)]
    assert np.all(np.diff(muts) <= 1e-12)


def test_progress_is_the_relative_improvement_over_the_window():
    ctl = _controller()
    assert ctl.progress(math.inf) == 0.0
    assert ctl.progress(100.0) == 1.0  # first feasible best after none
    assert ctl.progress(99.0) == 1.0  # window 2 reaches back to inf
    assert ctl.progress(99.0) == pytest.approx(0.2)  # (100 - 99) / 100 / 0.05
    assert ctl.progress(99.0) == 0.0
