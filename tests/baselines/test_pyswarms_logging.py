"""swarm.pso must not reconfigure the process's logging or write report.log (pyswarms does both on import)."""

import subprocess
import sys
import textwrap

import pytest


@pytest.mark.slow
def test_pso_leaves_logging_and_the_working_directory_alone(tmp_path):
    script = textwrap.dedent(
        """
        import logging
        import numpy as np
        import pathzoo
        from pathzoo.core.tiny_scenarios import check_scenario

        root = logging.getLogger()
        before = (list(root.handlers), root.level)
        planner = pathzoo.make_planner("swarm.pso", particles=8)
        result = planner.plan(check_scenario("grid2d"), budget=pathzoo.Budget(iterations=3),
                              rng=np.random.default_rng(0))
        assert (list(root.handlers), root.level) == before, (root.handlers, root.level)
        print(result.status.value)
        """
    )
    out = subprocess.run([sys.executable, "-c", script], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert not (tmp_path / "report.log").exists()
    assert "INFO" not in out.stderr
