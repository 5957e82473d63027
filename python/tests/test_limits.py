"""The span a Python run accepts is the file's (issue 24): steps beyond the file's
limit of 10,000,000 and non-finite times are refused up front with the message the
file gets, instead of a run that allocates gigabytes or stops with a misleading reason."""
import json
import math
import os
import subprocess

import pytest

import mechkin


@pytest.fixture
def four_bar(root):
    return os.path.join(root, "mechanisms", "planar-four-bar.json")


def test_steps_past_the_files_limit_are_refused_with_the_files_message(four_bar):
    model = mechkin.load(four_bar)
    with pytest.raises(ValueError, match="'steps' is larger than 10,000,000"):
        model.run(order=0, steps=10**7 + 1)
    doc = json.load(open(four_bar))
    doc["analysis"]["steps"] = 10**7 + 1
    with pytest.raises(mechkin.FormatError) as file_error:
        mechkin.loads(doc)
    assert "'steps' is larger than 10,000,000" in str(file_error.value)


@pytest.mark.parametrize("span", [{"end": math.inf}, {"start": -math.inf}, {"end": math.nan}])
def test_non_finite_times_are_refused(four_bar, span):
    model = mechkin.load(four_bar)
    with pytest.raises(ValueError, match="must be finite times in seconds"):
        model.run(order=0, **span)


def test_a_finite_span_within_the_limit_runs(four_bar):
    model = mechkin.load(four_bar)
    motion = model.run(order=0, start=0, end=0.5, steps=10)
    assert motion.complete and len(motion) == 11


@pytest.mark.parametrize("command, option, call, value", [
    ("tolerance", "--monte-carlo", lambda m, v: m.tolerance(monte_carlo=v), 200_000_000),
    ("tolerance", "--monte-carlo", lambda m, v: m.tolerance(monte_carlo=v), -1),
    ("range", "--steps", lambda m, v: m.range(steps=v), 3),
    ("range", "--steps", lambda m, v: m.range(steps=v), 20_000_000),
])
def test_counts_are_refused_in_the_same_words_by_the_cli_and_python(cli, root, command, option, call, value):
    path = os.path.join(root, "mechanisms", "parametric-four-bar.json")
    proc = subprocess.run([cli, command, path, option, str(value)], capture_output=True, text=True)
    assert proc.returncode != 0
    with pytest.raises(ValueError) as py_error:
        call(mechkin.load(path), value)
    message = str(py_error.value)
    assert "must be a whole number from" in message, message
    assert message in proc.stderr + proc.stdout, (message, proc.stderr)
