"""The module checks commands as the programs do (docs/design.md, "One check of a robot command")."""
import math

import numpy as np
import pytest

import ubersim


def test_a_value_beyond_the_radios_limits_is_dropped_by_the_radio_and_clamped_without_one():
    command = ubersim.command("yellow", 1, vx=50.0)[None, :]  # beyond LIMIT_SPEED (10 m/s)
    plain = ubersim.Sim(seed=1)
    plain.step(command)
    plain.step()
    assert plain.counters()["commands_clamped"] == 1  # physics: at the robot's top speed
    assert plain.counters()["commands_dropped"] == 0
    emulated = ubersim.Sim(seed=1, radio_profile="cmdragons02")
    for _ in range(10):
        emulated.step(command)
    counters = emulated.counters()
    assert counters["radio_yellow_packets_rejected_entries"] == 10  # the radio's validator
    assert counters["commands_applied"] == 0
    assert counters["commands_clamped"] == 0


def test_what_no_robot_can_apply_raises_with_or_without_a_radio():
    for radio in (None, "cmdragons02"):
        sim = ubersim.Sim(radio_profile=radio)
        bad = ubersim.command("blue", 2, vx=1.0)
        bad[ubersim.column("omega")] = math.inf
        with pytest.raises(ValueError, match=r"row 1 \(blue 2\).*NaN or infinite"):
            sim.step(np.stack([ubersim.command("yellow", 0), bad]))
        with pytest.raises(ValueError, match=r"row 2 \(blue 2\).*twice"):
            sim.step(np.stack([ubersim.command("blue", 2), ubersim.command("yellow", 2),
                               ubersim.command("blue", 2)]))
        assert sim.time == 0.0  # nothing stepped
        assert sim.counters()["commands_applied"] == 0
