"""The metrics' memo of the path being judged: same answers, never a stale one."""

from __future__ import annotations

import numpy as np
import pytest

from pathzoo.metrics.geometry import turn_angles
from pathzoo.metrics.path_memo import last_call


def test_an_equal_path_is_answered_from_the_memo_and_a_changed_one_is_not():
    calls = []

    @last_call
    def total(scale, path):
        calls.append(1)
        return path * scale

    path = np.array([[0.0, 0.0], [1.0, 0.0]])
    first = total(2.0, path)
    assert total(2.0, path.copy()) is first and len(calls) == 1
    path[1, 0] = 3.0  # changed in place: same object, other bytes
    assert total(2.0, path)[1, 0] == 6.0 and len(calls) == 2
    assert total(3.0, path)[1, 0] == 9.0 and len(calls) == 3
    assert total(3.0, path=path)[1, 0] == 9.0 and len(calls) == 4  # keywords are part of the key
    assert total(2, [1.0]) == [1.0, 1.0] and len(calls) == 5
    assert total(2, [1.0]) == [1.0, 1.0] and len(calls) == 6  # a mutable container: never answered from the memo


def test_kept_answers_are_read_only_and_equal_to_a_fresh_computation():
    path = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [2.0, 2.0]])
    kept = turn_angles(path)
    with pytest.raises(ValueError):
        kept[0] = 0.0
    fresh = turn_angles.__wrapped__(path)
    assert fresh.tobytes() == kept.tobytes()
