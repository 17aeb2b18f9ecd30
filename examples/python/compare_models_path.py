#!/usr/bin/env python3
"""Two (or more) contact models along one straight path of body A, plotted to a PNG.

Body A moves in a straight line from START to END (offsets from its pose in the scene, metres,
world frame) while B stays at its scene pose; every model is queried at the same poses in one
batch (Model.query_many) and the magnitude of the force on B is plotted against the distance
travelled.

    PYTHONPATH=build/python python3 examples/python/compare_models_path.py \\
        --scene scenes/sphere-on-plate.yaml --models pointshell vps --out compare.png
"""

import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import contactlab  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default="scenes/sphere-on-plate.yaml", help="scene file (data search path)")
    parser.add_argument("--models", nargs="+", default=["pointshell", "vps"], help="registered model names")
    parser.add_argument("--start", type=float, nargs=3, default=[-0.01, 0.0, 0.001], help="offset of A, metres")
    parser.add_argument("--end", type=float, nargs=3, default=[0.01, 0.0, -0.001], help="offset of A, metres")
    parser.add_argument("--steps", type=int, default=400, help="poses along the path")
    parser.add_argument("--out", default="compare-models.png", help="PNG to write")
    args = parser.parse_args()

    scene = contactlab.Scene.load(args.scene)
    # The path: A's scene pose moved from START to END, orientation kept.
    s = np.linspace(0.0, 1.0, args.steps)
    poses_A = np.tile(scene.A.pose, (args.steps, 1))
    poses_A[:, :3] += np.outer(1 - s, args.start) + np.outer(s, args.end)
    travelled = s * np.linalg.norm(np.subtract(args.end, args.start))

    fig, ax = plt.subplots(figsize=(7, 4))
    for name in args.models:
        forces = scene.model(name).query_many(poses_A, scene.B.pose)["force"]
        magnitude = np.linalg.norm(forces, axis=1)
        ax.plot(travelled * 1000, magnitude, label=name)
        print(f"{name:20s} max |F| {magnitude.max():10.4g} N   mean |F| {magnitude.mean():10.4g} N")
    ax.set_xlabel(f"distance travelled by {scene.A.name} [mm]")
    ax.set_ylabel(f"|force on {scene.B.name}| [N]")
    ax.set_title(f"{scene.name}: {', '.join(args.models)}")
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
