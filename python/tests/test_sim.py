"""Sim: reset and step shapes and units, placements, geometry, referee situations."""

import math

import numpy as np
import pytest

import ubersim
from conftest import BALL, ROBOT, robot_row


def test_columns_are_named_once():
    assert len(ubersim.COMMAND_COLUMNS) == 14
    assert ubersim.COMMAND_COLUMNS[:3] == ("team", "id", "mode")
    assert ubersim.ROBOT_COLUMNS[:5] == ("team", "id", "x", "y", "orientation")
    assert ubersim.BALL_COLUMNS == ("x", "y", "z", "vx", "vy", "vz")


def test_reset_and_step_shapes(sim):
    truth = sim.reset()
    assert truth["time"] == 0.0
    assert truth["robots"].shape == (12, len(ubersim.ROBOT_COLUMNS))
    assert truth["ball"].shape == (6,)
    out = sim.step()
    assert out["time"] == pytest.approx(0.025)
    assert out["robots"].shape == (12, len(ubersim.ROBOT_COLUMNS))
    # No emulation asked for: no frames, no feedback, but the arrays are there.
    assert out["vision"].shape == (0, len(ubersim.DETECTION_COLUMNS))
    assert out["frames"].shape == (0, len(ubersim.FRAME_COLUMNS))
    assert out["feedback"].shape == (0, len(ubersim.FEEDBACK_COLUMNS))
    assert out["robots"].dtype == np.float64


def test_scenario_lineup_in_metres_and_radians(sim):
    truth = sim.reset()
    keeper = robot_row(truth, ubersim.YELLOW, 0)
    assert keeper[ROBOT["x"]] == pytest.approx(-4.2, abs=1e-3)
    assert keeper[ROBOT["y"]] == pytest.approx(0.0, abs=1e-3)
    blue_keeper = robot_row(truth, ubersim.BLUE, 0)
    assert abs(blue_keeper[ROBOT["orientation"]]) == pytest.approx(math.pi, abs=1e-3)
    assert truth["ball"][BALL["z"]] == pytest.approx(sim.field["ball_radius"], abs=2e-3)


def test_a_local_velocity_command_moves_the_robot_forward(sim):
    sim.reset()
    cmd = ubersim.command(ubersim.YELLOW, 0, vx=1.0)[None, :]
    for _ in range(40):  # 1 s
        out = sim.step(cmd)
    robot = robot_row(out, ubersim.YELLOW, 0)
    # Facing +x at 1 m/s after the acceleration limit's ramp (3 m/s^2: 1/3 s).
    assert robot[ROBOT["vx"]] == pytest.approx(1.0, abs=0.1)
    assert robot[ROBOT["x"]] - (-4.2) == pytest.approx(1.0 - 1.0 / 6, abs=0.1)
    assert out["time"] == pytest.approx(1.0)


def test_wheel_speed_command_has_one_column_per_wheel(sim):
    sim.reset()
    cmd = ubersim.command(ubersim.YELLOW, 0, wheels=[20, 20, 20, 20])[None, :]
    for _ in range(20):
        out = sim.step(cmd)
    robot = robot_row(out, ubersim.YELLOW, 0)
    assert abs(robot[ROBOT["omega"]]) > 1.0  # every wheel the same way: the robot turns


def test_step_length_and_physics_steps():
    sim = ubersim.Sim(step=0.1, seed=0)
    assert sim.step_length == 0.1
    assert sim.dt == pytest.approx(1 / 240)
    out = sim.step()
    assert out["time"] == pytest.approx(0.1, abs=sim.dt / 2)


def test_reset_places_the_robots_and_ball_given(sim):
    robots = np.array([[0, 0, -1.0, 0.5, 0.0], [1, 3, 1.0, -0.5, math.pi / 2]])
    truth = sim.reset(robots=robots, ball=[0.3, 0.2, 1.0, 0.0])
    assert truth["robots"].shape == (2, len(ubersim.ROBOT_COLUMNS))
    blue = robot_row(truth, ubersim.BLUE, 3)
    assert blue[ROBOT["x"]] == pytest.approx(1.0, abs=1e-6)
    assert blue[ROBOT["orientation"]] == pytest.approx(math.pi / 2, abs=1e-6)
    assert truth["ball"][BALL["x"]] == pytest.approx(0.3)
    assert truth["ball"][BALL["vx"]] == pytest.approx(1.0)
    # The next reset without placements goes back to the scenario.
    assert sim.reset()["robots"].shape[0] == 12


def test_field_geometry(sim):
    field = sim.field
    assert field["name"] == "division_b"
    assert field["field_length"] == pytest.approx(9.0)
    assert field["field_width"] == pytest.approx(6.0)
    assert field["goal_width"] == pytest.approx(1.0)


def test_kickoff_puts_everyone_in_their_own_half(sim):
    sim.reset()
    sim.place_ball(1.0, 1.0)
    sim.kickoff("blue")
    truth = sim.truth()
    assert truth["ball"][BALL["x"]] == pytest.approx(0.0, abs=1e-6)
    assert truth["ball"][BALL["y"]] == pytest.approx(0.0, abs=1e-6)
    robots = truth["robots"]
    yellow = robots[robots[:, ROBOT["team"]] == ubersim.YELLOW]
    blue = robots[robots[:, ROBOT["team"]] == ubersim.BLUE]
    assert (yellow[:, ROBOT["x"]] <= 0.01).all()  # yellow defends negative x
    assert (blue[:, ROBOT["x"]] >= -0.01).all()


def test_free_kick_keeps_defenders_away(sim):
    sim.reset()
    sim.free_kick("yellow", 1.5, -1.0)
    truth = sim.truth()
    ball = truth["ball"]
    assert ball[BALL["x"]] == pytest.approx(1.5, abs=1e-6)
    blue = truth["robots"][truth["robots"][:, ROBOT["team"]] == ubersim.BLUE]
    distance = np.hypot(blue[:, ROBOT["x"]] - 1.5, blue[:, ROBOT["y"]] + 1.0)
    assert (distance >= 0.5 - 1e-3).all()


def test_penalty_ball_on_the_mark(sim):
    sim.reset()
    sim.penalty("yellow")
    ball = sim.truth()["ball"]
    # Yellow attacks the positive goal: the mark is penalty_mark_distance from it.
    assert ball[BALL["x"]] == pytest.approx(4.5 - sim.field["penalty_mark_distance"], abs=1e-6)


def test_place_and_remove_robot(sim):
    sim.reset()
    sim.place_robot("blue", 9, 0.5, 0.5, 0.0)
    assert robot_row(sim.truth(), ubersim.BLUE, 9)[ROBOT["x"]] == pytest.approx(0.5)
    sim.remove_robot("blue", 9)
    assert sim.truth()["robots"].shape[0] == 12


def test_counters(sim):
    sim.reset()
    sim.step(ubersim.command(0, 0, vx=1.0)[None, :])
    counters = sim.counters()
    assert counters["commands_applied"] >= 1
