#!/usr/bin/env python3
"""Drives a live joystick run: starts the scenario live, steers its
end-effector around a square with joystick commands while printing the
streamed frames, moves an obstacle half-way, then stops the run and prints
its summary.

    python3 python/examples/joystick.py --url http://127.0.0.1:8080 --seconds 8

With --keys, commands come from standard input instead, one per line:
w/a/s/d (up/left/down/right at --speed), x (halt), q (quit).
"""

import argparse
import os
import sys
import threading
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))  # python/: rrlab.client uninstalled
from rrlab.client import Client  # noqa: E402

KEYS = {"w": (0, 1), "a": (-1, 0), "s": (0, -1), "d": (1, 0), "x": (0, 0)}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--url", default=os.environ.get("RRLAB", "http://127.0.0.1:8080"), help="the rrlab server")
    parser.add_argument("--token", default=None, help="bearer token, if the server wants one")
    parser.add_argument("--scenario", default="04_planar7_joystick", help="a scenario whose task is a joystick")
    parser.add_argument("--method", default=None, help="method (default: the scenario's)")
    parser.add_argument("--seconds", type=float, default=8.0, help="how long to drive (scripted mode)")
    parser.add_argument("--speed", type=float, default=0.1, help="end-effector speed, m/s")
    parser.add_argument("--keys", action="store_true", help="read w/a/s/d/x/q commands from standard input")
    args = parser.parse_args()

    client = Client(args.url, token=args.token)
    run = client.run(args.scenario, args.method, mode="live")
    run_id = run["id"]
    print(f"live run {run_id} ({run['method']}), streaming {run['ws']}")
    state = {"quit": False}

    def drive_scripted():
        # a square: right, up, left, down, a quarter of the time each
        quarter = args.seconds / 4
        for i, (dx, dy) in enumerate([(1, 0), (0, 1), (-1, 0), (0, -1)]):
            client.joystick(run_id, [dx * args.speed, dy * args.speed])
            if i == 2:
                snapshot = client.get_run(run_id)
                print(f"moving obstacle 'box' at step {snapshot['live']['step']}")
                try:
                    client.move_obstacle(run_id, "box", position=[1.9, 0.6])
                except Exception as e:  # a scenario without a "box"
                    print(f"(no obstacle moved: {e})")
            time.sleep(quarter)
        state["quit"] = True

    def drive_keys():
        for line in sys.stdin:
            key = line.strip()[:1]
            if key == "q":
                break
            if key in KEYS:
                dx, dy = KEYS[key]
                client.joystick(run_id, [dx * args.speed, dy * args.speed])
        state["quit"] = True

    driver = threading.Thread(target=drive_keys if args.keys else drive_scripted, daemon=True)
    driver.start()
    shown = 0
    for frame in client.stream(run_id):
        if shown % 30 == 0:
            ee = frame["ee"]
            print(f"t={frame['t']:6.2f} s  ee=({ee[0]:+.3f}, {ee[1]:+.3f})  "
                  f"task error={frame['metrics']['task_error']:.2e}  status={frame['status']}")
        shown += 1
        if state["quit"]:
            break
    final = client.stop(run_id)
    summary = client.get_run(run_id)["summary"] or {}
    print(f"run {run_id} {final['status']} after {final['step']} steps; "
          f"max tracking error {summary.get('max_tracking_error')}, collided {summary.get('collided')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
