#!/usr/bin/env python3
"""A redundancy-resolution method of your own, in Python, measured on rrlab's
scenarios beside the built-in methods: damped least squares with a
joint-centring term in the null space (Liégeois' gradient projection of the
distance to the middle of the joint ranges).

It runs the method on Chen et al.'s joint-limit example, then benchmarks it
against built-in methods on two generated families (a sweep: success with its
interval per family) and plots both to a PNG when matplotlib is installed.

    ~/rrlab-venv/bin/python python/examples/my_method.py --cases 20 --out my_method.png

with the package installed (docs/python.md), or PYTHONPATH=build/python /usr/bin/python3 ...
"""
import argparse
import os

import numpy as np

import rrlab


class CentringDls(rrlab.Method):
    """Damped least squares plus a null-space pull toward the middle of the joint ranges."""
    name = "centring_dls"
    params = [rrlab.Param("damping", default=0.05, min=0.0, max=1.0),
              rrlab.Param("centring", default=1.0, min=0.0, max=100.0, help="gain of the null-space term, 1/s")]

    def step(self, s):
        j, lam = s.J, self.param("damping")
        j_star = j.T @ np.linalg.inv(j @ j.T + lam ** 2 * np.eye(len(j)))  # Wampler's damped inverse
        bounded = np.isfinite(s.q_lower) & np.isfinite(s.q_upper)  # unbounded joints: no pull
        lower, upper = np.where(bounded, s.q_lower, s.q - 1), np.where(bounded, s.q_upper, s.q + 1)
        middle, half = 0.5 * (lower + upper), 0.5 * (upper - lower)
        pull = -self.param("centring") * (s.q - middle) / half ** 2  # minus the gradient of Σ((q − mid)/half)²/2
        return j_star @ s.xdot + (np.eye(len(s.q)) - j_star @ j) @ pull


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cases", type=int, default=20, help="generated cases per family")
    parser.add_argument("--out", default=None, help="PNG of the results (needs matplotlib)")
    parser.add_argument("--scenarios", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                                            "scenarios"))
    args = parser.parse_args()

    # 1. one paper scenario, ours against the built-in methods
    paper = rrlab.load_scenario(os.path.join(args.scenarios, "18_chen_sim3_joint_limits.json"))
    runs = {name: rrlab.run(paper, method=method)
            for name, method in [("centring_dls", CentringDls()), ("dls", "dls"), ("pinv", "pinv")]}
    print(f"{paper.name}: {paper.dof} joints, {paper.steps} steps")
    for name, res in runs.items():  # Chen's arm has joint limits and no obstacle
        print(f"  {name:13s} limits crossed: {str(res['joint_limit_violated']):5s}  smallest margin "
              f"{res['min_joint_limit_margin']:+.4f} rad  largest tracking error {res['max_tracking_error']:.2e} m")

    # 2. a benchmark on two generated families: the same cases for every method
    spec = {"name": "centring", "scenarios": [{"generator": family, "count": args.cases, "seed": 1}
                                              for family in ("planar_limits", "planar_clutter")],
            "success": {"max_tracking_error": 0.01}}  # and, by default, no collision and no limit crossed
    out = rrlab.sweep(spec, methods=[CentringDls(), "dls", "gpm", "closest_point"], jobs=2)
    print(f"\nsweep: {out['stored']} runs, {len(out['failures'])} failed to run")
    groups = out["report"]["groups"]
    for g in sorted(groups, key=lambda g: (g["family"], -g["success_rate"])):
        low, high = g["success_interval"]
        print(f"  {g['family']:15s} {g['config']:13s} {100 * g['success_rate']:5.1f} %  ({100 * low:.0f}–{100 * high:.0f} %)")

    if args.out:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4))
        for name, res in runs.items():
            f = res["frames"]
            left.plot(f["t"], f["joint_limit_margin"], label=name, linestyle="--" if name == "pinv" else "-")
        left.set(xlabel="t (s)", ylabel="smallest joint-limit margin (rad)", title=paper.name)
        left.legend()
        families = sorted({g["family"] for g in groups})
        configs = sorted({g["config"] for g in groups})
        width = 0.8 / len(configs)
        for k, config in enumerate(configs):
            rates = [next(100 * g["success_rate"] for g in groups if g["family"] == fam and g["config"] == config)
                     for fam in families]
            right.bar(np.arange(len(families)) + k * width, rates, width, label=config)
        right.set_xticks(np.arange(len(families)) + 0.4 - width / 2, families)
        right.set(ylabel="success (%)", ylim=(0, 125), title=f"{args.cases} generated cases per family")
        right.legend(ncol=2, loc="upper center", fontsize="small")
        fig.tight_layout()
        fig.savefig(args.out, dpi=100)
        print(f"\nplot: {args.out}")


if __name__ == "__main__":
    main()
