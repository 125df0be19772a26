"""The Gymnasium API contract of ubersim.envs, with or without Gymnasium installed."""

import os
import subprocess
import sys

import numpy as np
import pytest

from ubersim import envs

ENVS = [envs.GoToBallEnv, envs.ScoreGoalEnv]


@pytest.mark.parametrize("make", ENVS)
def test_reset_and_step_follow_the_gymnasium_api(make):
    env = make()
    obs, info = env.reset(seed=3)
    assert isinstance(info, dict)
    assert obs.dtype == np.float32 and obs.shape == env.observation_space.shape
    assert env.observation_space.contains(obs)
    for _ in range(20):
        action = env.action_space.sample()
        assert env.action_space.contains(action)
        result = env.step(action)
        assert len(result) == 5
        obs, reward, terminated, truncated, info = result
        assert env.observation_space.contains(obs)
        assert isinstance(reward, float) and np.isfinite(reward)
        assert isinstance(terminated, bool) and isinstance(truncated, bool)
        assert isinstance(info, dict)
        if terminated:
            break
    env.close()


@pytest.mark.parametrize("make", ENVS)
def test_same_seed_same_episode(make):
    def episode():
        env = make()
        obs, _ = env.reset(seed=7)
        trace = [obs]
        for k in range(30):
            action = np.array([np.sin(0.1 * k), 0.5, 0.2] + [1.0] * (env.action_space.shape[0] - 3),
                              dtype=np.float32)
            obs, reward, terminated, _, _ = env.step(action)
            trace.append(np.append(obs, reward))
            if terminated:
                break
        return trace

    first, second = episode(), episode()
    assert len(first) == len(second)
    assert all(np.array_equal(a, b) for a, b in zip(first, second))


def test_vision_observations_are_noisy_and_truth_ones_are_not():
    noisy, exact = envs.GoToBallEnv(observe="vision"), envs.GoToBallEnv(observe="truth")
    obs_noisy, _ = noisy.reset(seed=1)
    obs_exact, _ = exact.reset(seed=1)
    # Same start (placements from the seed); vision then lags and jitters.
    assert np.array_equal(obs_noisy, obs_exact)
    still = np.zeros(3, dtype=np.float32)
    for _ in range(10):
        obs_noisy, *_ = noisy.step(still)
        obs_exact, *_ = exact.step(still)
    assert not np.array_equal(obs_noisy[:4], obs_exact[:4])
    assert np.allclose(obs_noisy[:4], obs_exact[:4], atol=0.01)


def test_go_to_ball_is_solvable_by_a_scripted_policy():
    env = envs.GoToBallEnv(observe="truth", radio_profile=None)
    obs, _ = env.reset(seed=2)
    total = 0.0
    for _ in range(400):
        ball, robot = obs[0:2], obs[2:4]
        heading = np.arctan2(obs[4], obs[5])
        to_ball = ball - robot
        local = np.array([np.cos(heading) * to_ball[0] + np.sin(heading) * to_ball[1],
                          -np.sin(heading) * to_ball[0] + np.cos(heading) * to_ball[1]])
        action = np.append(np.clip(local * 4, -1, 1), 0.0).astype(np.float32)
        obs, reward, terminated, truncated, _ = env.step(action)
        total += reward
        if terminated:
            break
    assert terminated
    assert total > 1.0


def test_bad_options():
    with pytest.raises(ValueError, match="observe"):
        envs.GoToBallEnv(observe="radar")
    env = envs.GoToBallEnv()
    env.reset(seed=0)
    with pytest.raises(ValueError, match="action"):
        env.step([np.nan, 0, 0])


def test_gymnasiums_own_env_checker():
    source = os.environ.get("UBERSIM_GYMNASIUM_SRC")
    if not source:
        pytest.skip("UBERSIM_GYMNASIUM_SRC does not name Gymnasium's sources (Debian 12 has no "
                    "gymnasium; docs/python.md, 'Gymnasium')")
    script = r"""
import gymnasium as gym, ubersim
from gymnasium.utils.env_checker import check_env
for name in ["ubersim/GoToBall-v0", "ubersim/ScoreGoal-v0"]:
    env = gym.make(name)
    check_env(env.unwrapped, skip_render_check=True)
    obs, info = env.reset(seed=0)
    for _ in range(500):
        obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
        if terminated or truncated:
            break
    print("checked", name, "truncated" if truncated else "terminated" if terminated else "")
"""
    path = os.pathsep.join([source, os.environ.get("PYTHONPATH", "")])
    result = subprocess.run([sys.executable, "-W", "error::UserWarning:gymnasium", "-c", script],
                            capture_output=True, text=True, timeout=300,
                            env=dict(os.environ, PYTHONPATH=path))
    assert result.returncode == 0, result.stdout + result.stderr
    assert result.stdout.count("checked ") == 2
