"""Every TOML example in docs/scenario-format.md loads as documented."""

import re
import shutil
from pathlib import Path

import numpy as np
import pytest

from pathzoo.io import load_scenario_file

DOC = Path(__file__).resolve().parents[2] / "docs" / "scenario-format.md"
EXAMPLES = re.findall(r"```toml\n(.*?)```", DOC.read_text(), flags=re.S)


def test_the_doc_has_its_examples():
    assert len(EXAMPLES) == 7


@pytest.mark.parametrize("text", EXAMPLES, ids=[re.search(r'id = "(.*?)"', t).group(1) for t in EXAMPLES])
def test_doc_example_loads(text, tmp_path, shared_data):
    shutil.copy(shared_data / "movingai" / "grid" / "dao" / "arena.map", tmp_path)
    for name in ("hugo_site.asc", "SRTMGL3_40.09_-105.55_40.21_-105.35.asc"):
        shutil.copy(shared_data / "dem" / name, tmp_path)
    np.savez(tmp_path / "soil.npz", rci=np.full((21, 21), 50.0))
    path = tmp_path / "example.toml"
    path.write_text(text)
    s = load_scenario_file(path)
    assert s.id == re.search(r'id = "(.*?)"', text).group(1)
    assert s.kind == re.search(r'kind = "(.*?)"', text).group(1)
