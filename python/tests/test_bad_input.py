"""Bad input raises a clear Python exception, changes nothing and never crashes."""

import math
import subprocess
import sys

import numpy as np
import pytest

import ubersim


@pytest.fixture
def sim():
    return ubersim.Sim(radio_profile="cmdragons02", vision_profile="cmdragons02")


def test_wrong_shape(sim):
    with pytest.raises(ValueError, match=r"shape \(n, 14\).*got \(2, 3\)"):
        sim.step(np.zeros((2, 3)))
    with pytest.raises(ValueError, match="shape"):
        sim.step(np.zeros((2, 14, 1)))
    with pytest.raises(TypeError, match="numeric array"):
        sim.step("fast please")


def test_nan_and_infinity(sim):
    row = ubersim.command(0, 1, vx=math.nan)
    with pytest.raises(ValueError, match="row 0.*NaN or infinite"):
        sim.step(row[None, :])
    row = ubersim.command(0, 1, kick_speed=math.inf)
    with pytest.raises(ValueError, match="NaN or infinite"):
        sim.step(row[None, :])
    with pytest.raises(ValueError, match="team"):
        sim.step(np.array([[math.nan] + [0.0] * 13]))


def test_unknown_robot(sim):
    with pytest.raises(ValueError, match="yellow 7.*no such robot"):
        sim.step(ubersim.command(0, 7, vx=1.0)[None, :])
    with pytest.raises(ValueError, match="id must be a whole number in 0..99"):
        sim.step(ubersim.command(0, 1000)[None, :])


def test_bad_team_mode_and_wheels(sim):
    with pytest.raises(ValueError, match="team"):
        sim.step(ubersim.command(2, 0)[None, :])
    with pytest.raises(ValueError, match="mode"):
        sim.step(ubersim.command(0, 0, mode=5)[None, :])
    with pytest.raises(ValueError, match="twice"):
        sim.step(np.stack([ubersim.command(0, 0), ubersim.command(0, 0)]))


def test_a_refused_step_changes_nothing(sim):
    sim.step()
    before = sim.truth()
    good_then_bad = np.stack([ubersim.command(0, 0, vx=2.0), ubersim.command(0, 42)])
    with pytest.raises(ValueError):
        sim.step(good_then_bad)
    after = sim.truth()
    assert after["time"] == before["time"]
    assert np.array_equal(after["robots"], before["robots"])


def test_bad_names_and_options():
    with pytest.raises(ValueError, match="no such scenarios config.*available"):
        ubersim.Sim(scenario="no_such_scenario")
    with pytest.raises(ValueError, match="vision"):
        ubersim.Sim(vision_profile="no_such_profile")
    with pytest.raises(ValueError, match="step"):
        ubersim.Sim(step=-1)
    with pytest.raises(ValueError, match="step"):
        ubersim.Sim(step=math.nan)


def test_bad_placements(sim):
    with pytest.raises(ValueError, match="team"):
        sim.place_robot("green", 0, 0, 0)
    with pytest.raises(ValueError, match="finite"):
        sim.place_ball(math.nan, 0)
    with pytest.raises(ValueError, match=r"robots must have shape \(n, 5\)"):
        sim.reset(robots=np.zeros((2, 3)))
    with pytest.raises(ValueError, match="ball must be"):
        sim.reset(ball=[1.0])
    with pytest.raises(ValueError, match="needs a robot_type|robot type"):
        sim.place_robot("blue", 9, 0, 0, robot_type="no_such_type")


def test_bad_vector_input():
    sims = ubersim.VectorSim(2, threads=2)
    with pytest.raises(ValueError, match="one entry per world"):
        sims.step([None])
    with pytest.raises(ValueError, match="world 1: commands row 0"):
        sims.step([None, ubersim.command(0, 0, vx=math.nan)[None, :]])
    with pytest.raises(IndexError):
        sims[5]
    with pytest.raises(IndexError):
        sims.reset(worlds=[3])
    with pytest.raises(ValueError, match="seeds"):
        ubersim.VectorSim(2, seeds=[1])


def test_the_interpreter_survives_a_barrage():
    # Everything above and some more in a fresh interpreter: it must end normally.
    script = r"""
import math, numpy as np, ubersim
sim = ubersim.Sim(radio_profile="cmdragons02", vision_profile="cmdragons02")
bad = [np.zeros((3, 3)), np.full((1, 14), np.nan), np.full((1, 14), 1e308), "x", [[1, 2]],
       np.zeros((0, 14)), np.array([[0, 0, 0] + [1e300] * 11]), object()]
errors = 0
for b in bad:
    try:
        sim.step(b)
    except (ValueError, TypeError):
        errors += 1
for args in [("yellow", -1, 0, 0), ("blue", 0, 1e9, 0), (0, 5, 0, math.inf)]:
    try:
        sim.place_robot(*args)
    except ValueError:
        errors += 1
sim.step()
print("survived", errors)
"""
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                            timeout=120)
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith("survived"), result.stdout


@pytest.mark.parametrize("team", ["Blue", "YELLOW", "y", "b", "0", "1", "", 2, -1, 1.0, 0.0,
                                  True, False, None, np.bool_(True), np.float64(1.0)])
def test_a_team_is_exactly_yellow_blue_0_or_1(sim, team):
    """Anything but "yellow", "blue", 0 or 1 raises wherever a team is taken."""
    with pytest.raises(ValueError, match="team must be 'yellow', 'blue', 0 or 1"):
        ubersim.command(team, 0, vx=1.0)
    with pytest.raises(ValueError, match="team must be 'yellow', 'blue', 0 or 1"):
        sim.place_robot(team, 0, 0.5, 0.5)
    with pytest.raises(ValueError, match="team must be 'yellow', 'blue', 0 or 1"):
        sim.remove_robot(team, 0)
    if team is not None:  # a situation's team may be None: the default kicker
        with pytest.raises(ValueError, match="team must be 'yellow', 'blue', 0 or 1"):
            sim.kickoff(team)


@pytest.mark.parametrize("team, code", [("yellow", 0), ("blue", 1), (0, 0), (1, 1),
                                        (np.int64(1), 1), (ubersim.BLUE, 1)])
def test_the_four_teams_name_the_team_they_say(team, code):
    assert ubersim.command(team, 3)[0] == code
    assert ubersim._ubersim._team_code(team) == code
