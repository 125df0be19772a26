"""Shared helpers of the ubersim Python tests (run by CTest as test_python)."""

import numpy as np
import pytest

import ubersim

ROBOT = {name: i for i, name in enumerate(ubersim.ROBOT_COLUMNS)}
BALL = {name: i for i, name in enumerate(ubersim.BALL_COLUMNS)}
DETECTION = {name: i for i, name in enumerate(ubersim.DETECTION_COLUMNS)}


def robot_row(truth, team, robot_id):
    """The ground-truth row of one robot."""
    robots = truth["robots"]
    match = (robots[:, ROBOT["team"]] == team) & (robots[:, ROBOT["id"]] == robot_id)
    assert match.sum() == 1, f"robot {team}/{robot_id} not in the truth"
    return robots[match][0]


def weave_commands(truth, t):
    """Every robot of the truth weaving on its own phase: a busy, repeatable game."""
    robots = truth["robots"]
    rows = ubersim.commands(len(robots))
    for i, robot in enumerate(robots):
        phase = 0.7 * i
        rows[i, 0:2] = robot[0:2]
        rows[i, 3] = 1.5 * np.cos(0.8 * t + phase)
        rows[i, 4] = 1.5 * np.sin(1.1 * t + 2 * phase)
        rows[i, 5] = 2.0 * np.sin(0.5 * t + phase)
    return rows


@pytest.fixture
def sim():
    return ubersim.Sim(scenario="division_b_6v6", seed=1)
