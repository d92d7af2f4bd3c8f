"""Reading answers: every malformed value is a one-line protocol error naming the planner and the field."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pathzoo.core.errors import ExternalPlannerError
from pathzoo_external.answer import decode_answer, read_answer


@pytest.mark.parametrize(("data", "error"), [
    (b"", "wrote nothing on standard output"),
    (b"{\"status\": \"solved\"} {}", "standard output is not one JSON object (Extra data at line 1 column 22)"),
    (b"\xff\xfe", "standard output is not one JSON object"),
    (b"[1, 2]", "the answer must be a JSON object, got list"),
    (b"{\"status\": \"solved\", \"length\": 3}", "unknown field(s) ['length'] in the answer"),
    (b"{}", "'status' must be one of solved, no_path, failed, got nothing"),
    (b"{\"status\": \"solved\", \"path\": [1, 2]}", "got a flat list of 2 numbers"),
    (b"{\"status\": \"solved\", \"path\": [[1, \"a\"]]}", "'path' point 0 has a coordinate that is not a number"),
    (b"{\"status\": \"solved\", \"path\": {\"x\": 1}}", "'path' must be a list of points [x, y], got dict"),
    (b"{\"status\": \"solved\", \"path\": [[1, 2]], \"times\": [0, 1]}", "'times' must be a list of 1 numbers"),
    (b"{\"status\": \"failed\", \"times\": [0]}", "'times' given without a path"),
    (b"{\"status\": \"failed\", \"iterations\": -1}", "'iterations' must be an integer in [0, 2**62], got -1"),
    (b"{\"status\": \"failed\", \"evaluations\": 1e300}", "'evaluations' must be an integer in [0, 2**62]"),
    (b"{\"status\": \"failed\", \"iterations\": true}", "'iterations' must be an integer"),
    (b"{\"status\": \"failed\", \"history\": [[1, 2]]}", "'history' point 0 must be [iteration, evaluations, best_cost]"),
    (b"{\"status\": \"failed\", \"history\": [[1, 2, \"x\"]]}", "best_cost must be a number or null"),
    (b"{\"status\": \"failed\", \"message\": 3}", "'message' must be a string, got 3"),
])
def test_malformed_answers(data, error):
    with pytest.raises(ExternalPlannerError) as info:
        read_answer(decode_answer(data, "ext.p"), dim=2, who="ext.p")
    assert str(info.value).startswith("ext.p: ") and error in str(info.value)
    assert "\n" not in str(info.value)


def test_a_good_answer_and_nulls_left_for_the_judge():
    data = (b'{"status": "solved", "path": [[0.5, 0.5], [1.5, null]], "times": [0, 2], "iterations": 3.0,'
            b' "evaluations": 7, "history": [[1, 4, null], [3, 7, 2.5]], "message": "ok"}')
    answer = read_answer(decode_answer(data, "ext.p"), dim=2, who="ext.p")
    r = answer.result
    assert r.status.value == "solved" and r.iterations == 3 and r.evaluations == 7 and r.message == "ok"
    assert r.path.shape == (2, 2) and math.isnan(r.path[1, 1]) and np.array_equal(r.times, [0.0, 2.0])
    assert answer.history == ((1, 4, math.inf), (3, 7, 2.5))


def test_air_paths_have_three_coordinates():
    with pytest.raises(ExternalPlannerError, match=r"must be \[x, y, z\] \(3 numbers\), got 2 numbers"):
        read_answer({"status": "solved", "path": [[1, 2], [3, 4], [5, 6]]}, dim=3, who="ext.p")
