#!/usr/bin/env python3
"""Utama-Core's StrategyRunner playing both teams against a simulator on the SSL protocols.

First-Order-RoboCup-SSL/Utama-Core's own runner (utama_core.run.StrategyRunner), as its demos
start it (demo_referee_gui_rsim.py: one runner, a strategy per team), but in its "grsim" mode:
SSL-Vision from 224.5.23.2 (utama_core/config/settings.py VISION_PORT), robot control with the
simulation protocol on 127.0.0.1:10301 (blue) / 10302 (yellow), simulation control on
127.0.0.1:10300, and referee commands from the network (OfficialReferee: 224.5.23.1:10003), so
ubersim's referee runs the game. Nothing of Utama-Core is changed; this file only chooses the
strategies and stops the runner after --seconds.

Run it with Debian's python3 that imports utama_core and py_trees (setup_real_programs.sh makes
OUT/bin/utama-python):
    utama-python utama_both_teams.py --seconds 300 [--strategy wandering|startup|defence]
It prints "utama: running" once both teams have seen the field and "utama: stopped after S s"
at the end.
"""
import argparse
import signal
import sys
import threading
import time


def parse_args():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    parser.add_argument("--seconds", type=float, default=300.0, help="wall seconds to play")
    parser.add_argument("--robots", type=int, default=6, help="robots per team (1-6)")
    parser.add_argument("--strategy", default="wandering",
                        choices=["wandering", "startup", "defence"],
                        help="Utama-Core example strategy for both teams")
    parser.add_argument("--yellow-right", action="store_true",
                        help="yellow defends the positive half (ubersim's default is negative)")
    parser.add_argument("--no-referee", action="store_true",
                        help="ignore the network referee (Utama-Core then plays in FORCE_START)")
    return parser.parse_args()


def make_strategy(name):
    if name == "wandering":
        from utama_core.tests.referee.wandering_strategy import WanderingStrategy
        return WanderingStrategy()
    if name == "startup":
        from utama_core.strategy.examples import StartupStrategy
        return StartupStrategy()
    from utama_core.strategy.examples import DefenceStrategy
    return DefenceStrategy()


def main():
    args = parse_args()
    from utama_core.run import StrategyRunner
    from utama_core.run.referee_source import OfficialReferee

    runner = StrategyRunner(
        strategy=make_strategy(args.strategy),
        opp_strategy=make_strategy(args.strategy),
        my_team_is_yellow=True,
        my_team_is_right=args.yellow_right,
        mode="grsim",
        exp_friendly=args.robots,
        exp_enemy=args.robots,
        referee=None if args.no_referee else OfficialReferee(),
        show_live_status=False,
    )
    print("utama: running", flush=True)
    started = time.monotonic()
    stopper = threading.Timer(args.seconds, lambda: signal.raise_signal(signal.SIGINT))
    stopper.daemon = True
    stopper.start()
    try:
        runner.run()
    except KeyboardInterrupt:
        pass
    print(f"utama: stopped after {time.monotonic() - started:.1f} s", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
