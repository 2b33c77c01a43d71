#!/usr/bin/env python3
"""Batch comparison of methods on one scenario: a table of the metrics, and a
plot of tracking error and obstacle clearance over time saved to PNG when
matplotlib is installed (Debian: python3-matplotlib).

    python3 python/examples/compare_methods.py --url http://127.0.0.1:8080 \\
        --scenario 01_planar7_obstacles --methods pinv dls closest_point --out compare.png
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))  # python/: rrlab.client uninstalled
from rrlab.client import ApiError, Client  # noqa: E402


def number(value, digits=4):
    return "-" if value is None else f"{value:.{digits}g}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--url", default=os.environ.get("RRLAB", "http://127.0.0.1:8080"), help="the rrlab server")
    parser.add_argument("--token", default=None, help="bearer token, if the server wants one")
    parser.add_argument("--scenario", default="01_planar7_obstacles", help="catalogue name")
    parser.add_argument("--methods", nargs="+", default=["pinv", "dls", "closest_point"], help="2 to 8 method names")
    parser.add_argument("--steps", type=int, default=None, help="steps per run (default: the scenario's duration)")
    parser.add_argument("--out", default="compare.png", help="PNG file for the plot")
    args = parser.parse_args()

    client = Client(args.url, token=args.token)
    options = {"steps": args.steps} if args.steps else {}
    try:
        result = client.compare(args.scenario, args.methods, **options)
    except ApiError as e:
        print(f"compare failed: {e}", file=sys.stderr)
        return 2

    print(f"{args.scenario}: group {result['group']}")
    print(f"{'method':<22} {'run':>5} {'collided':>8} {'min_distance':>12} {'max_track_err':>13} {'max_cond':>9}")
    for row in result["comparison"]:
        print(f"{row['method']:<22} {row['run']:>5} {str(row['collided']):>8} {number(row['min_distance']):>12} "
              f"{number(row['max_tracking_error']):>13} {number(row['max_condition_number']):>9}")

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no plot written (Debian: apt install python3-matplotlib); "
              "the table above has every number")
        return 0

    figure, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(8, 6))
    for row in result["comparison"]:
        frames = client.frames(row["run"], arrays=False)
        top.plot(frames["t"], frames["task_error"], label=row["method"])
        bottom.plot(frames["t"], [float("nan") if d is None else d for d in frames["min_distance"]],
                    label=row["method"])
    top.set_ylabel("task error (m)")
    top.set_yscale("log")
    bottom.set_ylabel("min distance (m)")
    bottom.set_xlabel("t (s)")
    top.legend()
    top.set_title(f"{args.scenario}: {', '.join(args.methods)}")
    figure.tight_layout()
    figure.savefig(args.out, dpi=100)
    print(f"plot written to {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
