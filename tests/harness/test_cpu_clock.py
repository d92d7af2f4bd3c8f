"""What a run is charged (pathzoo.harness.cpu_clock): a reaped child counts at its exact ``wait4`` figure."""

from __future__ import annotations

import os
import sys
import time

import pytest

from pathzoo.harness.cpu_clock import ChargedCpu

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")


def _burn(seconds: float) -> None:
    end = time.process_time() + seconds
    while time.process_time() < end:
        pass


def test_a_reaped_child_is_charged_its_exact_cpu_not_whole_ticks():
    """The tree reads a reaped child in whole clock ticks (up to two short); given the child's ``wait4`` figure, the
    charge is at least that figure, and exceeds the tick reading by no more than the ticks missed."""
    charged = ChargedCpu(os.getpid())
    charged.start()
    pid = os.fork()
    if pid == 0:
        _burn(0.1057)  # not a whole number of 10 ms ticks
        os._exit(0)
    _, _, usage = os.wait4(pid, 0)
    child = usage.ru_utime + usage.ru_stime
    ticks = charged.spent()
    exact = charged.spent(reaped=child)
    assert child >= 0.1057
    assert exact >= child  # the tree alone may read 0.10 here
    assert ticks <= exact <= ticks + (child - 0.09) + 0.005  # only what the ticks missed: the child is not counted twice


def test_a_lap_ends_one_charge_and_starts_the_next_from_one_reading():
    """Each reading of the cgroup is taken once: the lap's end is the next lap's start, so nothing is read twice or
    falls between two runs."""
    readings = iter([1.0, 2.5, 4.0])
    charged = ChargedCpu(os.getpid(), cgroup=lambda: next(readings))
    charged.start()
    assert charged.lap() == 1.5  # the cgroup's 1.0 to 2.5 (this process's own CPU meanwhile is far less)
    assert charged.spent() == 1.5  # from 2.5, the lap's reading, to 4.0
