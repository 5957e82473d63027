"""Ctrl-C during a long call (issue 24): run(), tolerance() and sweep() raise
KeyboardInterrupt at the core's next step instead of finishing the work first. A
timer thread sends SIGINT to this process while the call runs; the call must end
in KeyboardInterrupt and leave the interpreter able to run again. (How soon it
ends is measured by hand, not asserted: no timing in tests.)"""
import os
import signal
import threading

import pytest

import mechkin


@pytest.fixture
def four_bar(root):
    return mechkin.load(os.path.join(root, "mechanisms", "parametric-four-bar.json"))


def interrupt_after(seconds):
    timer = threading.Timer(seconds, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    return timer


def test_run_raises_keyboard_interrupt(four_bar):
    timer = interrupt_after(0.5)
    try:
        with pytest.raises(KeyboardInterrupt):
            four_bar.run(order=0, bodies=[], steps=3_000_000)  # a run of about 10 s
    finally:
        timer.cancel()
    assert four_bar.run(order=0, steps=10).complete  # the next call runs normally


def test_tolerance_monte_carlo_raises_keyboard_interrupt(four_bar):
    timer = interrupt_after(0.5)
    try:
        with pytest.raises(KeyboardInterrupt):
            four_bar.tolerance(monte_carlo=100_000, threads=2)  # about 45 s
    finally:
        timer.cancel()


def test_sweep_raises_keyboard_interrupt(four_bar):
    pytest.importorskip("pandas")
    variants = [{"a": 30 + 20 * k / 20000} for k in range(20000)]  # about 40 s on 2 threads
    timer = interrupt_after(0.5)
    try:
        with pytest.raises(KeyboardInterrupt):
            mechkin.sweep(four_bar, variants, threads=2)
    finally:
        timer.cancel()
    frame = mechkin.sweep(four_bar, variants[:2], threads=2)  # the stop flag was lowered again
    assert list(frame["status"]) == ["complete", "complete"]
