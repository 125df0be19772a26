"""ubersim in this process: simulated SSL worlds with emulated vision and radio.

``Sim`` holds one world, ``VectorSim`` many stepped together on C++ threads;
``ubersim.rsim.SSL`` is rSim's interface, ``ubersim.envs`` holds Gymnasium
environments. docs/python.md is the manual.
"""

import os as _os

from ._ubersim import (  # noqa: F401  (the module's public names)
    BALL_COLUMNS,
    COMMAND_COLUMNS,
    DETECTION_COLUMNS,
    FEEDBACK_COLUMNS,
    FRAME_COLUMNS,
    ROBOT_COLUMNS,
    Sim,
    VectorSim,
    default_config_dir,
)
from . import _ubersim

# An installed package ships the config folder beside this file (setup.py);
# a build tree uses the source tree's.
_shipped = _os.path.join(_os.path.dirname(__file__), "config")
if _os.path.isdir(_shipped):
    _ubersim._set_package_config_dir(_shipped)

# Gymnasium environments (ubersim/GoToBall-v0, ubersim/ScoreGoal-v0) when Gymnasium is there.
try:
    from . import envs as _envs

    _envs.register()
except ImportError:  # Gymnasium present but broken: the rest of the module still works
    pass

YELLOW = 0
BLUE = 1
MODE_LOCAL_VELOCITY = 0
MODE_GLOBAL_VELOCITY = 1
MODE_WHEEL_SPEEDS = 2
# The "kind" column of vision detections.
KIND_BALL = 0
KIND_YELLOW = 1
KIND_BLUE = 2


def column(name, columns=COMMAND_COLUMNS):
    """Index of a column by name, e.g. column("vx") or column("x", ROBOT_COLUMNS)."""
    return columns.index(name)


def commands(n=0):
    """A zeroed commands array of n rows (columns: COMMAND_COLUMNS)."""
    import numpy

    return numpy.zeros((n, len(COMMAND_COLUMNS)))


def command(team, robot_id, vx=0.0, vy=0.0, omega=0.0, kick_speed=0.0, chip_speed=0.0,
            chip_angle=0.0, dribbler_speed=0.0, wheels=None, mode=None):
    """One commands row: local velocity (m/s, m/s, rad/s), or wheel speeds (rad/s) when given."""
    import numpy

    row = numpy.zeros(len(COMMAND_COLUMNS))
    row[0] = _ubersim._team_code(team)  # "yellow", "blue", 0 or 1; anything else raises
    row[1] = robot_id
    row[2] = mode if mode is not None else (MODE_WHEEL_SPEEDS if wheels is not None else
                                            MODE_LOCAL_VELOCITY)
    row[3:6] = (vx, vy, omega)
    if wheels is not None:
        row[6:6 + len(wheels)] = wheels
    row[10:14] = (kick_speed, chip_speed, chip_angle, dribbler_speed)
    return row


__all__ = [
    "Sim", "VectorSim", "COMMAND_COLUMNS", "ROBOT_COLUMNS", "BALL_COLUMNS", "DETECTION_COLUMNS",
    "FRAME_COLUMNS", "FEEDBACK_COLUMNS", "YELLOW", "BLUE", "MODE_LOCAL_VELOCITY",
    "MODE_GLOBAL_VELOCITY", "MODE_WHEEL_SPEEDS", "KIND_BALL", "KIND_YELLOW", "KIND_BLUE",
    "column", "commands", "command", "default_config_dir",
]
