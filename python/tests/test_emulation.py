"""Vision and radio emulated in process: latency, noise and loss as the profiles say."""

import numpy as np
import pytest

import ubersim
from conftest import DETECTION, ROBOT, robot_row

# config/vision/cmdragons02.cfg
LATENCY, JITTER, PROCESSING = 0.066, 0.002, 0.02
ROBOT_SIGMA, DETECTION_PROBABILITY, FRAME_RATE = 0.004, 0.98, 30
# config/radio/cmdragons02.cfg
RADIO_LATENCY, FEEDBACK_RATE = 0.033, 30


def collect(sim, seconds):
    frames, detections, arrivals = [], [], []
    while sim.time < seconds - 1e-9:
        out = sim.step()
        frames.append(out["frames"])
        detections.append(out["vision"])
        arrivals.extend([out["time"]] * len(out["frames"]))
    return np.concatenate(frames), np.concatenate(detections), np.array(arrivals)


def test_vision_latency_against_the_profile():
    # One physics step per step: a frame comes out at the first step at or after
    # its publication, so arrival - capture is the latency plus up to one dt.
    sim = ubersim.Sim(vision_profile="cmdragons02", seed=3, step=1 / 240)
    frames, _, arrivals = collect(sim, 4.0)
    capture = frames[:, ubersim.FRAME_COLUMNS.index("t_capture")]
    sent = frames[:, ubersim.FRAME_COLUMNS.index("t_sent")]
    assert len(frames) == pytest.approx(FRAME_RATE * (4.0 - LATENCY), abs=2)
    assert np.diff(capture) == pytest.approx(1 / FRAME_RATE, abs=1e-9)
    assert sent - capture == pytest.approx(PROCESSING, abs=1e-9)
    delay = arrivals - capture
    assert delay.min() >= LATENCY - 4 * JITTER
    assert delay.mean() == pytest.approx(LATENCY + sim.dt / 2, abs=sim.dt / 2 + 0.001)
    assert delay.std() < JITTER + sim.dt


def test_vision_noise_and_detection_rate_against_the_profile():
    sim = ubersim.Sim(vision_profile="cmdragons02", seed=4)
    truth = sim.reset()
    _, detections, _ = collect(sim, 3.0)
    robots = detections[detections[:, DETECTION["kind"]] != ubersim.KIND_BALL]
    errors = []
    for team, kind in ((ubersim.YELLOW, ubersim.KIND_YELLOW), (ubersim.BLUE, ubersim.KIND_BLUE)):
        for robot_id in range(6):
            seen = robots[(robots[:, DETECTION["kind"]] == kind)
                          & (robots[:, DETECTION["robot_id"]] == robot_id)]
            true = robot_row(truth, team, robot_id)
            errors.append(seen[:, DETECTION["x"]] - true[ROBOT["x"]])
            errors.append(seen[:, DETECTION["y"]] - true[ROBOT["y"]])
    errors = np.concatenate(errors)
    frames = FRAME_RATE * 3.0 - LATENCY * FRAME_RATE
    rate = len(robots) / (12 * round(frames))
    assert rate == pytest.approx(DETECTION_PROBABILITY, abs=0.015)
    assert abs(errors.mean()) < 0.001
    assert errors.std() == pytest.approx(ROBOT_SIGMA, rel=0.15)


def first_moving_time(sim):
    cmd = ubersim.command(ubersim.YELLOW, 1, vx=1.0)[None, :]
    while sim.time < 0.5:
        out = sim.step(cmd)
        if robot_row(out, ubersim.YELLOW, 1)[ROBOT["vx"]] > 0.01:
            return out["time"]
    return None


def test_radio_latency_delays_commands():
    direct = first_moving_time(ubersim.Sim(step=1 / 240, seed=1))
    radio = first_moving_time(ubersim.Sim(step=1 / 240, seed=1, radio_profile="cmdragons02"))
    assert direct < 0.02
    assert radio - direct == pytest.approx(RADIO_LATENCY, abs=0.01)


def test_radio_feedback_rate_and_latency():
    sim = ubersim.Sim(radio_profile="cmdragons02", seed=2)
    rows = []
    while sim.time < 2.0 - 1e-9:
        rows.append(sim.step()["feedback"])
    feedback = np.concatenate(rows)
    column = ubersim.FEEDBACK_COLUMNS.index
    packets = np.unique(feedback[:, [column("team"), column("t_measured")]], axis=0)
    assert len(packets) == pytest.approx(2 * FEEDBACK_RATE * 2.0, rel=0.1)
    delay = feedback[:, column("t_sent")] - feedback[:, column("t_measured")]
    assert delay.mean() == pytest.approx(RADIO_LATENCY, abs=0.003)
