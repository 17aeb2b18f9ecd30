#!/usr/bin/env python3
"""Sweeps the contact stiffness k_C of an experiment config through contactlab.run and prints
each model's force statistics per k_C from the run's summary.csv.

    PYTHONPATH=build/python python3 examples/python/sweep_stiffness.py \\
        experiments/continuity-models.yaml --k-C 500 1000 2000 --set models=[pointshell,vps]
"""

import argparse

import contactlab


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("config", help="experiment YAML (experiments/*.yaml)")
    parser.add_argument("--k-C", type=float, nargs="+", default=[500.0, 1000.0, 2000.0], help="k_C values, N/m")
    parser.add_argument("--out", default="results/sweep-k_C", help="results folder")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="further overrides, as `contactlab run --set`")
    args = parser.parse_args()

    # The sweep replaces the config's own: one job per k_C, in the order given.
    overrides = [f"sweep={{k_C: [{', '.join(repr(k) for k in args.k_C)}]}}"] + args.set
    out = contactlab.run(args.config, out=args.out, set=overrides)
    results = contactlab.load_results(out)
    # summary.csv holds one column per sweep axis (k_C here) beside each model's metrics.
    summary = results.summary.sort_values(["k_C", "model"])
    print(f"{results.meta['experiment']}: {len(summary)} rows in {out}")
    print(summary[["k_C", "model", "cycles", "max_force_N", "mean_force_N", "max_jump_rel"]].to_string(index=False))


if __name__ == "__main__":
    main()
