#!/usr/bin/env python3
"""Times Model.query_many of the contactlab Python module on the poses bench_query_loop times
in C++ (sphere-on-plate, A circling and sinking), and a Python loop of Model.query for scale.

    CONTACTLAB_DATA=$PWD/data PYTHONPATH=build/python python3 experiments/bench_python/bench_query_many.py
"""

import argparse
import time

import numpy as np

import contactlab


def path_poses(pose_A, n):
    """The poses of bench_query_loop.cc's PathPoses."""
    t = np.linspace(0.0, 1.0, n) if n > 1 else np.zeros(1)
    angle = 7.0 * 2.0 * np.pi * t
    poses = np.tile(pose_A, (n, 1))
    poses[:, 0] += 0.005 * np.cos(angle)
    poses[:, 1] += 0.005 * np.sin(angle)
    poses[:, 2] += 0.0005 - 0.003 * t
    return poses


def best_of(repeats, fn):
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--models", nargs="+", default=["pointshell", "pointshell-linear", "vps"])
    parser.add_argument("-n", type=int, default=10000, help="poses per batch")
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    scene = contactlab.Scene.load("scenes/sphere-on-plate.yaml")
    poses_A = path_poses(scene.A.pose, args.n)
    for name in args.models:
        model = scene.model(name)
        batch = best_of(args.repeats, lambda: model.query_many(poses_A, scene.B.pose))
        loop = best_of(1, lambda: [model.query(p, scene.B.pose) for p in poses_A])
        print(f"{name:18s} query_many: {batch * 1e3:9.2f} ms ({batch / args.n * 1e6:7.2f} us/query)   "
              f"python loop of query: {loop * 1e3:9.2f} ms ({loop / args.n * 1e6:7.2f} us/query)")


if __name__ == "__main__":
    main()
