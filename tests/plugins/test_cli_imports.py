"""``pathzoo list`` and ``pathzoo --help`` import no numba, pandas or scipy (plugins are listed from declarations)."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

HEAVY = ("numba", "pandas", "scipy")

_PROBE = """
import json, sys
from pathzoo.cli.main import main
code = main(sys.argv[1:])
sys.stdout.flush()
print(json.dumps({"code": code, "heavy": sorted(m for m in %r if m in sys.modules)}), file=sys.stderr)
""" % (HEAVY,)


@pytest.mark.parametrize("argv", [["list", "planners"], ["list", "scenarios"], ["list", "metrics"],
                                  ["list", "planners", "aco.*"], ["--help"], ["list", "--help"]])
def test_no_heavy_import(argv):
    done = subprocess.run([sys.executable, "-c", _PROBE, *argv], capture_output=True, text=True, timeout=120)
    report = json.loads(done.stderr.strip().splitlines()[-1])
    assert report == {"code": 0, "heavy": []}, done.stderr
    assert done.stdout.strip()


def test_the_probe_sees_heavy_imports():
    """The control: a command that does need pandas is caught by the same probe."""
    done = subprocess.run([sys.executable, "-c", _PROBE.replace("main(sys.argv[1:])", "__import__('pandas') and 0"),
                           "list", "planners"], capture_output=True, text=True, timeout=120)
    assert json.loads(done.stderr.strip().splitlines()[-1])["heavy"] == ["pandas"]


def test_listing_keeps_unavailable_planners_with_their_install_hint(monkeypatch, capsys):
    from pathzoo.cli.main import main
    from pathzoo.plugins import requirements

    real = requirements._installed
    monkeypatch.setattr(requirements, "_installed", lambda module: module != "pyswarms" and real(module))
    assert main(["list", "planners", "swarm.*"]) == 0
    rows = {line.split()[0]: line for line in capsys.readouterr().out.splitlines()[2:]}
    assert rows["swarm.pso"].endswith(
        '[unavailable, needs pyswarms: pip install "pathzoo[evo]"] Particle swarm optimisation (pyswarms) of K '
        'straight-segment waypoints, no graph search')
    assert "unavailable" not in rows["swarm.cuckoo"]
