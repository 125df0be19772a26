"""A goal scored by a scripted kick."""

import numpy as np
import pytest

import ubersim
from conftest import BALL, ROBOT, robot_row


def test_a_scripted_kick_scores():
    sim = ubersim.Sim(seed=1)
    field = sim.field
    half_length = field["field_length"] / 2
    # A yellow striker 1.5 m before the blue goal, the ball at its kicker.
    robots = np.array([[ubersim.YELLOW, 0, half_length - 1.5, 0.0, 0.0]])
    ball_x = half_length - 1.5 + 0.075 + field["ball_radius"] + 0.002
    sim.reset(robots=robots, ball=[ball_x, 0.0])
    kick = ubersim.command(ubersim.YELLOW, 0, kick_speed=5.0)[None, :]
    still = ubersim.command(ubersim.YELLOW, 0)[None, :]
    scored_at = None
    for k in range(80):  # 2 s: kick in the first step, then stand
        out = sim.step(kick if k == 0 else still)
        ball = out["ball"]
        inside = (ball[BALL["x"]] > half_length + field["ball_radius"]
                  and abs(ball[BALL["y"]]) < field["goal_width"] / 2)
        if inside and scored_at is None:
            scored_at = out["time"]
    assert scored_at is not None, "the ball never crossed the goal line between the posts"
    # About 1.4 m at 5 m/s (a little less as it rolls): well under a second.
    assert scored_at < 0.6
    assert sim.counters()["kicks"] == 1
    assert robot_row(sim.truth(), ubersim.YELLOW, 0)[ROBOT["x"]] < half_length
