"""Every planner id a docs page or the README names is a registered planner.

A name reads ``family.name`` with a family of the registered planners
(``aco``, ``exact``, ...). Module paths (``ompl.util.RNG``), file names
(``ompl.md``) and web addresses are not ids and are skipped. The papers'
rivals that are not reconstructed keep an id in the reproduction tables, so
that a row says which method it stands for; they are the only exceptions,
with the example id of a user's own planner in ``docs/aco-engine.md``.
"""

from __future__ import annotations

import re
from functools import cache
from pathlib import Path
from typing import Any

import pytest

from pathzoo.plugins.manager import discover

REPO_ROOT = Path(__file__).resolve().parents[2]
PAGES = sorted(
    [REPO_ROOT / "README.md"]
    + [p for p in (REPO_ROOT / "docs").rglob("*") if p.suffix in (".md", ".rst") and "_build" not in p.parts]
)
NOT_RECONSTRUCTED = {"aco.chen", "swarm.mopso", "evo.lro_ga"}
"""Rivals a paper compares against that pathzoo does not reconstruct (docs/reproduction.md)."""
EXAMPLES = {"aco.mine"}
"""Ids of a user's own planner in a registration example."""
FILE_SUFFIXES = {"md", "py", "rst", "toml", "org", "html", "json", "csv", "txt"}


@cache
def _installed() -> dict[str, Any]:
    """The installed planners, from plugins discovered afresh once: other tests of the same process register planners
    of their own (the hostile tests' ``sandbox.*``) in the process-wide registry and leave them there."""
    return dict(discover().table("planners"))


def _families() -> set[str]:
    return {pid.split(".", 1)[0] for pid in _installed()}


def named_ids(text: str, families: set[str]) -> set[str]:
    """``family.name`` tokens of ``text`` that read as planner ids."""
    pattern = re.compile(
        r"(?<![\w./-])(?<!-m )(" + "|".join(sorted(families)) + r")\.([a-z][a-z0-9_]*)(?![\w-]|\.\w)"
    )
    return {f"{m[1]}.{m[2]}" for m in pattern.finditer(text) if m[2] not in FILE_SUFFIXES}


def test_the_pattern_finds_ids_and_skips_modules() -> None:
    families = {"ompl", "aco", "search"}
    text = ("Run `aco.acs` and ompl.rrt, not ompl.util.RNG, ompl.md, https://ompl.kavrakilab.org, "
            "`python -m ompl.ompl_benchmark_statistics` or pathzoo_baselines.search.helper; aco.nope.")
    assert named_ids(text, families) == {"aco.acs", "ompl.rrt", "aco.nope"}


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(REPO_ROOT)))
def test_page_names_only_registered_planners(page: Path) -> None:
    registered = set(_installed())
    unknown = named_ids(page.read_text(encoding="utf-8"), _families()) - registered - NOT_RECONSTRUCTED - EXAMPLES
    assert not unknown, f"{page.relative_to(REPO_ROOT)} names unregistered planner id(s): {sorted(unknown)}"


@pytest.mark.parametrize("page", sorted((REPO_ROOT / "docs" / "planners").glob("*.md")), ids=lambda p: p.stem)
def test_every_planner_page_says_what_one_evaluation_is(page: Path) -> None:
    text = page.read_text(encoding="utf-8")
    assert "\n## One evaluation\n" in text, f"{page.relative_to(REPO_ROOT)} has no '## One evaluation' section"


def _section(text: str, heading: str) -> str:
    start = text.find(f"\n## {heading}\n")
    if start < 0:
        return ""
    end = text.find("\n## ", start + 1)
    return text[start: end if end >= 0 else len(text)]


def test_every_kind_a_planner_does_not_support_has_a_stated_reason() -> None:
    """Each empty planner x kind cell has a bullet under '## Kinds not supported' on the planner's page.

    A planner without a page of its own (the hybrid metaheuristics) is covered by its family page, whose
    bullet names it.
    """
    from pathzoo.core.scenario import SCENARIO_KINDS

    missing = []
    for pid, entry in sorted(_installed().items()):
        own = REPO_ROOT / "docs" / "planners" / f"{pid}.md"
        page = own if own.exists() else REPO_ROOT / "docs" / "planners" / "metaheuristics.md"
        section = _section(page.read_text(encoding="utf-8"), "Kinds not supported")
        for kind in sorted(set(SCENARIO_KINDS) - set(entry.declared("kinds", ()))):
            bullets = [line for line in section.splitlines() if line.startswith("- ") and f"`{kind}`" in line
                       and (own.exists() or f"`{pid}`" in line)]
            if not bullets:
                missing.append(f"{pid} x {kind} ({page.name})")
    assert not missing, "no stated reason for: " + ", ".join(missing)
