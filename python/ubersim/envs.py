"""Gymnasium environments on ubersim (docs/python.md, "Gymnasium").

The agent sees the field the way a team's software does: through the emulated
vision (noise, latency, dropped detections) by default, and its commands go
through the emulated radio (latency, loss). observe="truth" gives ground truth.

    ubersim/GoToBall-v0   one robot drives to the ball
    ubersim/ScoreGoal-v0  one robot takes the ball into the opponents' goal

They are registered with Gymnasium when it is importable (``import ubersim``
does it); without Gymnasium the classes still work with the same API
(reset -> (obs, info), step -> (obs, reward, terminated, truncated, info),
observation_space / action_space with low, high, shape, dtype, sample(),
contains()).
"""

import math

import numpy as np

from ._ubersim import COMMAND_COLUMNS, DETECTION_COLUMNS, ROBOT_COLUMNS, Sim

try:  # Gymnasium is optional (Debian 12 has none).
    import gymnasium as _gym
    from gymnasium import spaces as _spaces

    _Env = _gym.Env
except ImportError:  # pragma: no cover - depends on the machine
    _gym = None
    _spaces = None
    _Env = object


class _Box:
    """The part of gymnasium.spaces.Box these environments use, for when it is absent."""

    def __init__(self, low, high, shape, dtype):
        self.shape = tuple(shape)
        self.dtype = np.dtype(dtype)
        self.low = np.full(self.shape, low, dtype=self.dtype)
        self.high = np.full(self.shape, high, dtype=self.dtype)
        self._random = np.random.default_rng()

    def seed(self, seed=None):
        self._random = np.random.default_rng(seed)

    def sample(self):
        return self._random.uniform(self.low, self.high).astype(self.dtype)

    def contains(self, x):
        x = np.asarray(x)
        return (x.shape == self.shape and x.dtype == self.dtype
                and bool(np.all(x >= self.low)) and bool(np.all(x <= self.high)))


def _box(low, high, shape):
    if _spaces is not None:
        return _spaces.Box(low=low, high=high, shape=shape, dtype=np.float32)
    return _Box(low, high, shape, np.float32)


_R = {name: i for i, name in enumerate(ROBOT_COLUMNS)}
_C = {name: i for i, name in enumerate(COMMAND_COLUMNS)}
_D = {name: i for i, name in enumerate(DETECTION_COLUMNS)}
_BLUE = 1
_OBS_LIMIT = 10.0  # normalised observations are clipped to +-this


class _SSLEnv(_Env):
    """One blue robot (id 0) and the ball on the Division B field."""

    metadata = {"render_modes": []}
    _action_size = 3

    def __init__(self, vision_profile="cmdragons02", radio_profile="cmdragons02",
                 observe="vision", max_speed=2.0, max_angular_speed=6.0, render_mode=None):
        if observe not in ("vision", "truth"):
            raise ValueError(f"observe must be 'vision' or 'truth', got {observe!r}")
        if observe == "vision" and not vision_profile:
            raise ValueError("observe='vision' needs a vision_profile")
        self.render_mode = render_mode
        self._options = dict(scenario="division_b_6v6", vision_profile=vision_profile,
                             radio_profile=radio_profile)
        self._observe = observe
        self._max_speed = max_speed
        self._max_angular_speed = max_angular_speed
        self._sim = Sim(seed=0, **self._options)
        self.field = self._sim.field
        self._scale = self.field["field_length"] / 2
        self.observation_space = _box(-_OBS_LIMIT, _OBS_LIMIT, (9,))
        self.action_space = _box(-1.0, 1.0, (self._action_size,))
        self._seen = None
        self._random = np.random.default_rng()

    # -- episode ----------------------------------------------------------
    def reset(self, *, seed=None, options=None):
        if _gym is not None:
            super().reset(seed=seed)
            self._random = self.np_random
        elif seed is not None:
            self._random = np.random.default_rng(seed)
        if seed is not None:
            self.action_space.seed(seed)
        sim_seed = int(self._random.integers(0, 2**31))
        robot, ball = self._placement()
        truth = self._sim.reset(seed=sim_seed, robots=np.array([[_BLUE, 0, *robot]]), ball=ball)
        self._seen = self._from_truth(truth)
        self._truth = truth
        self._steps = 0
        self._start()
        return self._observation(), {}

    def step(self, action):
        action = np.clip(np.asarray(action, dtype=np.float64).ravel(), -1.0, 1.0)
        if action.shape != (self._action_size,) or not np.isfinite(action).all():
            raise ValueError(f"action must be {self._action_size} finite numbers, got {action!r}")
        out = self._sim.step(self._command(action)[None, :])
        self._truth = out
        self._steps += 1
        self._update_seen(out)
        reward, terminated = self._reward()
        return self._observation(), float(reward), bool(terminated), False, {"time": out["time"]}

    def close(self):
        pass

    # -- what the robot sees ----------------------------------------------
    @staticmethod
    def _from_truth(truth):
        r = truth["robots"][0]
        return {"ball": truth["ball"][0:2].copy(),
                "robot": np.array([r[_R["x"]], r[_R["y"]], r[_R["orientation"]]]),
                "velocity": np.array([r[_R["vx"]], r[_R["vy"]], r[_R["omega"]]]),
                "t_capture": truth["time"]}

    def _update_seen(self, out):
        if self._observe == "truth":
            self._seen = self._from_truth(out)
            return
        seen = out["vision"]
        balls = seen[seen[:, _D["kind"]] == 0]
        if len(balls):  # the most confident ball of the newest frame
            newest = balls[balls[:, _D["t_capture"]] == balls[:, _D["t_capture"]].max()]
            best = newest[np.argmax(newest[:, _D["confidence"]])]
            self._seen["ball"] = best[[_D["x"], _D["y"]]]
        robots = seen[(seen[:, _D["kind"]] == 2) & (seen[:, _D["robot_id"]] == 0)]
        if len(robots):  # velocity: between the last two detections, by their capture times
            last = robots[-1]
            old = self._seen["robot"]
            new = last[[_D["x"], _D["y"], _D["orientation"]]]
            dt = last[_D["t_capture"]] - self._seen["t_capture"]
            if dt > 1e-6:
                turn = math.remainder(new[2] - old[2], 2 * math.pi)
                self._seen["velocity"] = np.array(
                    [(new[0] - old[0]) / dt, (new[1] - old[1]) / dt, turn / dt])
            self._seen["robot"] = new
            self._seen["t_capture"] = last[_D["t_capture"]]

    def _observation(self):
        s = self._seen
        x, y, heading = s["robot"]
        vx, vy, omega = s["velocity"]
        obs = np.array([s["ball"][0] / self._scale, s["ball"][1] / self._scale, x / self._scale,
                        y / self._scale, math.sin(heading), math.cos(heading),
                        vx / self._max_speed, vy / self._max_speed,
                        omega / self._max_angular_speed])
        return np.clip(obs, -_OBS_LIMIT, _OBS_LIMIT).astype(np.float32)

    def _command(self, action):
        row = np.zeros(len(COMMAND_COLUMNS))
        row[[_C["team"], _C["id"], _C["mode"]]] = (_BLUE, 0, 0)  # local velocity
        row[_C["vx"]] = action[0] * self._max_speed
        row[_C["vy"]] = action[1] * self._max_speed
        row[_C["omega"]] = action[2] * self._max_angular_speed
        return row

    # -- task -------------------------------------------------------------
    def _ball_distance(self):
        r = self._truth["robots"][0]
        return math.hypot(self._truth["ball"][0] - r[_R["x"]], self._truth["ball"][1] - r[_R["y"]])

    def _placement(self):
        half_length = self.field["field_length"] / 2 - 0.3
        half_width = self.field["field_width"] / 2 - 0.3
        robot = [self._random.uniform(-half_length, half_length),
                 self._random.uniform(-half_width, half_width),
                 self._random.uniform(-math.pi, math.pi)]
        while True:
            ball = [self._random.uniform(-half_length, half_length),
                    self._random.uniform(-half_width, half_width)]
            if math.hypot(ball[0] - robot[0], ball[1] - robot[1]) > 0.5:
                return robot, ball

    def _start(self):
        self._distance = self._ball_distance()


class GoToBallEnv(_SSLEnv):
    """Drive the blue robot to the ball: reward is the distance gained (m), +1 on arrival."""

    def _reward(self):
        distance = self._ball_distance()
        reward = self._distance - distance
        self._distance = distance
        arrived = distance < 0.09 + self.field["ball_radius"] + 0.05
        return reward + (1.0 if arrived else 0.0), arrived


class ScoreGoalEnv(_SSLEnv):
    """Take the ball into the goal at positive x: +10 for a goal, shaped by the ball's progress.

    Actions: local vx, vy, omega and kick (> 0 kicks at 5 m/s when the ball is at the kicker).
    """

    _action_size = 4
    kick_speed = 5.0

    def _command(self, action):
        row = super()._command(action)
        row[_C["kick_speed"]] = self.kick_speed if action[3] > 0 else 0.0
        return row

    def _goal_distance(self):
        ball = self._truth["ball"]
        return math.hypot(self.field["field_length"] / 2 - ball[0], ball[1])

    def _start(self):
        super()._start()
        self._to_goal = self._goal_distance()

    def _reward(self):
        ball = self._truth["ball"]
        half_length = self.field["field_length"] / 2
        goal = ball[0] > half_length + self.field["ball_radius"] and \
            abs(ball[1]) < self.field["goal_width"] / 2
        out = abs(ball[0]) > half_length or abs(ball[1]) > self.field["field_width"] / 2
        to_goal = self._goal_distance()
        distance = self._ball_distance()
        reward = (self._to_goal - to_goal) + 0.2 * (self._distance - distance)
        self._to_goal, self._distance = to_goal, distance
        if goal:
            return reward + 10.0, True
        return reward, out


def register():
    """Registers the environments with Gymnasium (done by ``import ubersim`` when it is there)."""
    if _gym is None:
        return False
    for name, entry, steps in (("ubersim/GoToBall-v0", "ubersim.envs:GoToBallEnv", 400),
                               ("ubersim/ScoreGoal-v0", "ubersim.envs:ScoreGoalEnv", 800)):
        if name not in _gym.envs.registry:
            _gym.register(id=name, entry_point=entry, max_episode_steps=steps)
    return True
