"""ubersim.rsim.SSL: rSim's constructor, step, get_state, reset, get_field_params and layouts."""

import math
import os
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest

from ubersim import rsim

# rSoccer's FrameSSL.parse: ball x, y, z, vx, vy, then 11 per robot, blue first.
ROBOT_FIELDS = ("x", "y", "theta", "v_x", "v_y", "v_theta", "infrared",
                "v_wheel0", "v_wheel1", "v_wheel2", "v_wheel3")


def robot(state, index):
    base = 5 + 11 * index
    return dict(zip(ROBOT_FIELDS, state[base:base + 11]))


def make(field_type=1, n_blue=2, n_yellow=3, step_ms=25):
    blue = [[-1.0 - 0.5 * i, 0.0, 90.0] for i in range(n_blue)]
    yellow = [[1.0, 0.5 * i, 180.0] for i in range(n_yellow)]
    return rsim.SSL(field_type, n_blue, n_yellow, step_ms, [0.2, -0.3, 0, 0], blue, yellow)


def test_state_layout_as_rsoccer_reads_it():
    sim = make()
    state = sim.get_state()
    assert state.shape == (5 + 11 * 5,)
    assert state[0:2] == pytest.approx([0.2, -0.3], abs=1e-6)
    assert state[2] == pytest.approx(0.0215, abs=2e-3)  # z: resting on the floor
    blue1 = robot(state, 1)
    assert (blue1["x"], blue1["y"]) == pytest.approx((-1.5, 0.0), abs=1e-6)
    assert blue1["theta"] == pytest.approx(90.0, abs=1e-6)  # degrees
    yellow2 = robot(state, 2 + 2)
    assert (yellow2["x"], yellow2["y"]) == pytest.approx((1.0, 1.0), abs=1e-6)
    assert yellow2["theta"] == pytest.approx(180.0, abs=1e-6)


def test_step_local_velocity_moves_the_right_robot():
    sim = make()
    actions = np.zeros((5, 8))
    actions[0, 1] = 1.0  # blue 0: forward (it faces +y) at 1 m/s
    actions[3, 3] = 2.0  # yellow 1: turn at 2 rad/s
    for _ in range(40):
        sim.step(actions)
    state = sim.get_state()
    blue0 = robot(state, 0)
    assert blue0["y"] > 0.6 and abs(blue0["x"] + 1.0) < 0.05
    assert blue0["v_y"] == pytest.approx(1.0, abs=0.1)  # m/s, field frame
    yellow1 = robot(state, 3)
    assert yellow1["v_theta"] == pytest.approx(math.degrees(2.0), rel=0.1)  # deg/s
    assert abs(robot(state, 4)["v_x"]) < 0.05  # yellow 2 was told nothing


def test_wheel_speed_mode_and_field_types():
    sim = make(field_type=0)
    assert sim.get_field_params()["length"] == pytest.approx(12.0)
    actions = np.zeros((5, 8))
    actions[1, 0:5] = [1, 30, 30, 30, 30]
    for _ in range(20):
        sim.step(actions)
    assert abs(robot(sim.get_state(), 1)["v_theta"]) > 50
    assert make(field_type=2).get_field_params()["length"] == pytest.approx(6.0)
    assert make(field_type=2).get_field_params()["goal_width"] == pytest.approx(0.7)


def test_kick_through_rsims_action_columns():
    params = make().get_field_params()
    ball_x = -1.0 + params["rbt_distance_center_kicker"] + params["ball_radius"] + 0.002
    sim = rsim.SSL(1, 1, 0, 25, [ball_x, 0, 0, 0], [[-1.0, 0.0, 0.0]], [])
    actions = np.zeros((1, 8))
    actions[0, 5] = 4.0
    sim.step(actions)
    sim.step(actions)
    state = sim.get_state()
    assert state[3] == pytest.approx(4.0, rel=0.15)
    assert robot(state, 0)["infrared"] == 0.0  # the ball has left the kicker


def test_reset_and_field_params():
    sim = make()
    sim.step(np.ones((5, 8)) * [0, 1, 0, 0, 0, 0, 0, 0])
    sim.reset([1.0, 1.0, 0.5, 0.0], [[0, 0, 0], [0, 2, 0]], [[2, 0, 0], [2, 1, 0], [2, -1, 0]])
    state = sim.get_state()
    assert state[0:2] == pytest.approx([1.0, 1.0], abs=1e-6)
    assert state[3] == pytest.approx(0.5, abs=1e-6)
    params = sim.get_field_params()
    expected = {"length", "width", "penalty_length", "penalty_width", "goal_width", "goal_depth",
                "ball_radius", "rbt_distance_center_kicker", "rbt_kicker_thickness",
                "rbt_kicker_width", "rbt_wheel0_angle", "rbt_wheel1_angle", "rbt_wheel2_angle",
                "rbt_wheel3_angle", "rbt_radius", "rbt_wheel_radius", "rbt_motor_max_rpm"}
    assert set(params) == expected
    assert params["width"] == pytest.approx(6.0)
    assert params["rbt_wheel0_angle"] == pytest.approx(57.0)  # degrees, as rSim's


def test_bad_rsim_input():
    with pytest.raises(ValueError, match="field_type"):
        rsim.SSL(5, 1, 1, 25, [0, 0, 0, 0], [[0, 0, 0]], [[1, 0, 0]])
    with pytest.raises(ValueError, match="blue_robots_pos: 2 positions needed"):
        rsim.SSL(1, 2, 0, 25, [0, 0, 0, 0], [[0, 0, 0]], [])
    sim = make()
    with pytest.raises(ValueError, match="actions must have shape"):
        sim.step(np.zeros((2, 8)))
    with pytest.raises(ValueError, match="finite"):
        sim.step(np.full((5, 8), np.nan))


def rsoccer_sources():
    source = os.environ.get("UBERSIM_RSOCCER_SRC")
    if not source:
        pytest.skip("UBERSIM_RSOCCER_SRC does not name a checkout of robocin/rSoccer "
                    "(docs/python.md, 'rSoccer on ubersim')")
    return source


def test_rsoccer_ssl_environments_run_with_one_import_replaced(tmp_path):
    source = rsoccer_sources()
    shutil.copytree(os.path.join(source, "rsoccer_gym"), tmp_path / "rsoccer_gym")
    simulator = tmp_path / "rsoccer_gym" / "Simulators" / "rsim.py"
    text = simulator.read_text()
    assert re.search(r"^import robosim$", text, re.M), "rSoccer's import line has changed"
    simulator.write_text(re.sub(r"^import robosim$", "from ubersim import rsim as robosim",
                                text, flags=re.M))
    script = r"""
import gymnasium as gym, numpy as np, rsoccer_gym
for name in ["SSLStaticDefenders-v0", "SSLDribbling-v0", "SSLContestedPossession-v0",
             "SSLPassEndurance-v0"]:
    env = gym.make(name)
    obs, info = env.reset(seed=1)
    assert env.observation_space.shape == obs.shape, name
    for _ in range(50):
        obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
        assert np.isfinite(obs).all(), name
        if terminated or truncated:
            obs, info = env.reset()
    env.close()
    print("ran", name)
"""
    # Gymnasium from its sources when UBERSIM_GYMNASIUM_SRC names them (Debian 12 has none).
    path = os.pathsep.join([str(tmp_path), os.environ.get("UBERSIM_GYMNASIUM_SRC", ""),
                            os.environ.get("PYTHONPATH", "")])
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                            env=dict(os.environ, PYTHONPATH=path), timeout=300)
    if "No module named 'gymnasium'" in result.stderr or "No module named 'pygame'" in result.stderr:
        pytest.skip("rSoccer needs gymnasium and pygame importable: " + result.stderr.strip()[-200:])
    assert result.returncode == 0, result.stdout + result.stderr
    assert result.stdout.count("ran ") == 4


def test_side_by_side_with_rsim_itself():
    folder = os.environ.get("UBERSIM_RSIM_BUILD")
    if not folder:
        pytest.skip("UBERSIM_RSIM_BUILD does not name a folder holding rSim's robosim package "
                    "built from robocin/rSim (docs/python.md, 'rSim compatibility')")
    sys.path.insert(0, folder)
    try:
        import robosim
    finally:
        sys.path.remove(folder)
    for field_type in (0, 1, 2):
        args = (field_type, 2, 3, 25, [0.2, -0.3, 0.0, 0.0],
                [[-1.0 - 0.5 * i, 0.0, 90.0] for i in range(2)],
                [[1.0, 0.5 * i, 180.0] for i in range(3)])
        theirs, ours = robosim.SSL(*args), rsim.SSL(*args)
        their_params, our_params = theirs.get_field_params(), ours.get_field_params()
        assert set(their_params) == set(our_params)
        for key in ("length", "width", "penalty_length", "penalty_width", "goal_width"):
            assert our_params[key] == pytest.approx(their_params[key]), (field_type, key)
        actions = np.zeros((5, 8))
        theirs.step(actions)
        ours.step(actions)
        their_state, our_state = np.array(theirs.get_state()), ours.get_state()
        assert their_state.shape == our_state.shape
        # Where everything stands after one still step: the same layout and units.
        for k in range(5):
            base = 5 + 11 * k
            assert our_state[base:base + 2] == pytest.approx(their_state[base:base + 2], abs=0.01)
            assert math.cos(math.radians(our_state[base + 2] - their_state[base + 2])) > 0.999
        assert our_state[0:2] == pytest.approx(their_state[0:2], abs=0.01)
