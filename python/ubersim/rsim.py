"""rSim's Python interface (robosim.SSL) on ubersim's physics.

rSoccer's SSL environments run on ubersim when rsoccer_gym/Simulators/rsim.py
imports this module in place of robosim::

    from ubersim import rsim as robosim   # was: import robosim

The constructor, step, get_state, reset and get_field_params take and return
what rSim's do, in its units and array layouts (checked against rSim's
src/robosim/robosim_py.cpp and sslworld.cpp):

* field_type: 0 Division A (12 x 9 m), 1 Division B (9 x 6 m), 2 rSim's 6 x 4 m
  hardware-challenge field (config/fields/rsim_hardware_challenge.cfg);
* ball_pos: [x, y, vx, vy] (m, m/s); robot positions: [x, y, theta] (m, degrees);
* step(actions): one row of 8 per robot, blue robots first, then yellow, each
  team by id: [wheel_mode, vx | wheel0, vy | wheel1, vtheta | wheel2, wheel3,
  kick_v_x, kick_v_z, dribbler] (m/s, rad/s; wheel_mode > 0: wheel speeds in
  rad/s; kick_v_z > 0: a chip; dribbler > 0: on);
* get_state(): [ball x, y, z, vx, vy] then 11 per robot in the same order:
  [x, y, theta (deg, 0..360), vx, vy, vtheta (deg/s), infrared (ball at the
  kicker), wheel0..wheel3 (rad/s)].

Differences (docs/python.md, "rSim compatibility"): velocities are the
bodies' own, not differences of positions between calls; wheel speeds are
measured, not the set points; the robots are ubersim's omni4_ssl type; VSS is
not provided. Keyword arguments beyond rSim's go to ubersim.Sim (e.g.
radio_profile="cmdragons02" for radio latency and loss, seed=...).
"""

import math

import numpy as np

from ._ubersim import Sim

_FIELDS = {
    0: ("division_a_11v11", None),
    1: ("division_b_6v6", None),
    2: ("division_b_6v6", "rsim_hardware_challenge"),
}
_ACTION_COLUMNS = 8
_STATE_PER_ROBOT = 11


def _positions(values, count, what, width):
    rows = np.asarray(values, dtype=float)
    rows = rows.reshape(-1, width) if rows.size else np.zeros((0, width))
    if len(rows) < count:
        raise ValueError(f"{what}: {count} positions needed, got {len(rows)}")
    rows = rows[:count]
    if not np.isfinite(rows).all():
        raise ValueError(f"{what}: every value must be finite")
    return rows


class SSL:
    """rSim's SSL simulator: blue and yellow robots numbered from 0, no vision or radio."""

    def __init__(self, field_type, n_robots_blue, n_robots_yellow, time_step_ms, ball_pos,
                 blue_robots_pos, yellow_robots_pos, **sim_options):
        if field_type not in _FIELDS:
            raise ValueError(f"field_type must be 0 (Division A), 1 (Division B) or 2 "
                             f"(hardware challenge), got {field_type!r}")
        if n_robots_blue < 0 or n_robots_yellow < 0:
            raise ValueError("robot counts must not be negative")
        if not time_step_ms > 0:
            raise ValueError(f"time_step_ms must be positive, got {time_step_ms!r}")
        scenario, field = _FIELDS[field_type]
        self._n_blue = int(n_robots_blue)
        self._n_yellow = int(n_robots_yellow)
        self._sim = Sim(scenario=scenario, field=field, step=time_step_ms / 1000.0,
                        **sim_options)
        robot = self._sim.robot_type_info()
        self._dribbler_speed = robot["dribbler_max_speed"]
        self._robot = robot
        self._commands = np.zeros((self._n_blue + self._n_yellow, 14))
        self.reset(ball_pos, blue_robots_pos, yellow_robots_pos)

    @property
    def sim(self):
        """The ubersim.Sim underneath (for vision frames, radio feedback, referee situations)."""
        return self._sim

    def _order(self):
        """(team, id) of each action row: blue 0.. first, then yellow 0.."""
        return [(1, i) for i in range(self._n_blue)] + [(0, i) for i in range(self._n_yellow)]

    def reset(self, ball_pos, blue_robots_pos, yellow_robots_pos):
        given = np.asarray(ball_pos, dtype=float).ravel()
        if given.size < 2 or not np.isfinite(given).all():
            raise ValueError(f"ball_pos must be finite [x, y, vx, vy], got {ball_pos!r}")
        ball = np.zeros(4)
        ball[:min(4, given.size)] = given[:4]
        blue = _positions(blue_robots_pos, self._n_blue, "blue_robots_pos", 3)
        yellow = _positions(yellow_robots_pos, self._n_yellow, "yellow_robots_pos", 3)
        robots = []
        for (team, robot_id), (x, y, theta) in zip(self._order(), np.vstack([blue, yellow])):
            robots.append([team, robot_id, x, y, math.radians(theta)])
        self._sim.reset(robots=np.array(robots).reshape(-1, 5), ball=ball)
        for row, (team, robot_id) in enumerate(self._order()):
            self._commands[row, 0:2] = (team, robot_id)
        self._truth = self._sim.truth()

    def step(self, actions):
        actions = np.asarray(actions, dtype=float)
        rows = self._n_blue + self._n_yellow
        if actions.ndim != 2 or actions.shape[1] < _ACTION_COLUMNS or actions.shape[0] < rows:
            raise ValueError(f"actions must have shape ({rows}, {_ACTION_COLUMNS}), "
                             f"got {actions.shape}")
        actions = actions[:rows, :_ACTION_COLUMNS]
        if not np.isfinite(actions).all():
            raise ValueError("actions: every value must be finite")
        commands = self._commands
        commands[:, 2:] = 0.0
        wheels = actions[:, 0] > 0
        commands[:, 2] = np.where(wheels, 2, 0)
        commands[~wheels, 3:6] = actions[~wheels, 1:4]
        commands[wheels, 6:10] = actions[wheels, 1:5]
        kick_x, kick_z = actions[:, 5], actions[:, 6]
        chip = kick_z > 0
        commands[:, 10] = np.where(~chip & (kick_x > 0), kick_x, 0.0)
        commands[:, 11] = np.where(chip, np.hypot(kick_x, kick_z), 0.0)
        commands[:, 12] = np.where(chip, np.arctan2(kick_z, np.maximum(kick_x, 0.0)), 0.0)
        commands[:, 13] = np.where(actions[:, 7] > 0, self._dribbler_speed, 0.0)
        self._truth = self._sim.step(commands)

    def get_state(self):
        truth = self._truth
        robots = truth["robots"]
        ball = truth["ball"]
        state = np.empty(5 + _STATE_PER_ROBOT * (self._n_blue + self._n_yellow))
        state[0:5] = ball[[0, 1, 2, 3, 4]]
        index = {(int(r[0]), int(r[1])): r for r in robots}
        for k, key in enumerate(self._order()):
            r = index.get(key)
            base = 5 + _STATE_PER_ROBOT * k
            if r is None:  # taken off the field by the caller through .sim
                state[base:base + _STATE_PER_ROBOT] = np.nan
                continue
            state[base + 0] = r[2]
            state[base + 1] = r[3]
            state[base + 2] = math.degrees(r[4]) % 360.0
            state[base + 3] = r[5]
            state[base + 4] = r[6]
            state[base + 5] = math.degrees(r[7])
            state[base + 6] = r[8]
            state[base + 7:base + 11] = np.nan_to_num(r[10:14])
        return state

    def get_field_params(self):
        field = self._sim.field
        robot = self._robot
        angles = [math.degrees(a) for a in robot["wheel_angles"]] + [0.0] * 4
        return {
            "length": field["field_length"],
            "width": field["field_width"],
            "penalty_length": field["penalty_area_depth"],
            "penalty_width": field["penalty_area_width"],
            "goal_width": field["goal_width"],
            "goal_depth": field["goal_depth"],
            "ball_radius": field["ball_radius"],
            "rbt_distance_center_kicker": robot["kicker_distance"],
            # ubersim's kicker is a face, not a box: rSim's thickness for what reads it.
            "rbt_kicker_thickness": 0.005,
            "rbt_kicker_width": robot["kicker_width"],
            "rbt_wheel0_angle": angles[0],
            "rbt_wheel1_angle": angles[1],
            "rbt_wheel2_angle": angles[2],
            "rbt_wheel3_angle": angles[3],
            "rbt_radius": robot["radius"],
            "rbt_wheel_radius": robot["wheel_radius"],
            "rbt_motor_max_rpm": robot["motor_max_speed"] * 60.0 / (2.0 * math.pi),
        }
