"""ContactLab from Python: scenes, contact models and experiments of the C++ library.

    import contactlab
    scene = contactlab.Scene.load("scenes/sphere-on-plate.yaml")
    model = scene.model("pointshell", k_C=2000)
    r = model.query(scene.A.pose, scene.B.pose)        # r["wrench"], r["K_B"], r["stats"]
    batch = model.query_many(poses_A, poses_B)          # (N, 7) arrays -> (N, 6), (N, 6, 6)
    out = contactlab.run("experiments/continuity-models.yaml", out="/tmp/run", set={"models": ["pointshell"]})
    results = contactlab.load_results(out)              # results.summary, results.cycles: DataFrames
    world = contactlab.World.load("scenes/tool-among-parts.yaml")   # a tool among many bodies
    w = world.query(tool_pose)                          # w["force"], per pair w["pair_force"] (P, 3)

Units are SI (metres, newtons); poses are (x, y, z, qw, qx, qy, qz) 7-vectors or 4x4 matrices.
Errors raise contactlab.Error (a RuntimeError) with the library's message (file, line, key); a
bad argument (shape, a value that is not finite) raises contactlab.ArgumentError, which is both a
contactlab.Error and a ValueError.
"""


def _import_error(error):
    """The ImportError to raise when this interpreter cannot use the package: NumPy missing, or
    an extension module built for another Python (named by _build.py, written by the build)."""
    import sys

    try:
        from ._build import PYTHON, PYTHON_VERSION
    except ImportError:
        PYTHON, PYTHON_VERSION = "an unknown interpreter", "?"
    version = f"{sys.version_info.major}.{sys.version_info.minor}"
    built = f"contactlab was built for Python {PYTHON_VERSION} ({PYTHON})"
    running = f"Python {version} ({sys.executable})"
    try:
        import numpy  # noqa: F401
    except ImportError as e:
        return ImportError(f"{built} and needs numpy, which {running} cannot import ({e}): install numpy for it "
                           f"(Debian: apt install python3-numpy) or run {PYTHON}")
    if version != PYTHON_VERSION:
        return ImportError(f"{built}; this is {running}, which cannot load its extension module ({error}): "
                           f"run {PYTHON}, or build contactlab for this interpreter "
                           f"(cmake -DPython_EXECUTABLE={sys.executable})")
    return ImportError(f"{built}; {running} cannot load its extension module: {error}")


try:
    import numpy as _numpy  # noqa: F401  (every array in and out is NumPy's)
    from ._core import (  # noqa: F401
        ArgumentError,
        Body,
        Error,
        Mesh,
        Model,
        Pointshell,
        Scene,
        World,
        __version__,
        model_description,
        models,
        register_model,
    )
except ImportError as _error:
    raise _import_error(_error) from _error
from .results import Results, load_results  # noqa: F401
from . import _core as _core_module


def _find_installed_root():
    """share/contactlab above the package: PREFIX/share/contactlab when installed,
    build/share/contactlab in a build tree (its data/ links to the checkout's)."""
    from pathlib import Path

    for parent in Path(__file__).resolve().parents:
        if (parent / "share" / "contactlab" / "data").is_dir():
            return parent / "share" / "contactlab"
    return None


# The data search path's installed folder (util/data_path.h, step 5) is found from the package,
# not from the running program (python3).
_root = _find_installed_root()
if _root is not None:
    _core_module._set_installed_root(str(_root))
del _root
from .run import run  # noqa: F401

__all__ = [
    "Body", "Error", "Mesh", "Model", "Pointshell", "Results", "Scene", "load_results", "model_description",
    "models", "register_model", "run",
]
