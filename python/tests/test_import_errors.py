"""An interpreter that cannot use the package is told why on `import contactlab`: which Python
the package was built for and what is missing (NumPy, or an extension module for its version)."""

import os
import pathlib
import shutil
import subprocess
import sys

import contactlab

PACKAGE = pathlib.Path(contactlab.__file__).parent
RUNNING = f"{sys.version_info.major}.{sys.version_info.minor}"


def import_contactlab(path, cwd):
    """Exit code and stderr of `import contactlab` in a fresh interpreter with PATH first on
    sys.path, run in CWD (`-c` puts the working folder first: not one holding a contactlab/)."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(str(p) for p in path))
    run = subprocess.run([sys.executable, "-c", "import contactlab"], capture_output=True, text=True, env=env,
                         cwd=cwd, timeout=60)
    return run.returncode, run.stderr


def test_missing_numpy_names_the_interpreter_built_for(tmp_path):
    # A numpy that cannot be imported, first on the path, as in an interpreter without it.
    (tmp_path / "hidden" / "numpy").mkdir(parents=True)
    (tmp_path / "hidden" / "numpy" / "__init__.py").write_text(
        "raise ModuleNotFoundError(\"No module named 'numpy'\", name='numpy')\n")
    code, err = import_contactlab([tmp_path / "hidden", PACKAGE.parent], tmp_path)
    assert code != 0
    # The tests run under the interpreter the module was built for (Python_EXECUTABLE).
    assert f"ImportError: contactlab was built for Python {RUNNING} ({sys.executable}) and needs numpy" in err, err
    assert "apt install python3-numpy" in err, err


def test_another_python_is_told_which_one_the_package_is_for(tmp_path):
    # The package as another interpreter sees it: its Python files, no extension module it can
    # load, built (says _build.py) for a Python that is not this one.
    copy = tmp_path / "site" / "contactlab"
    copy.mkdir(parents=True)
    for f in PACKAGE.glob("*.py"):
        shutil.copy(f, copy)
    (copy / "_build.py").write_text('PYTHON = "/opt/python3.99/bin/python3"\nPYTHON_VERSION = "3.99"\n')
    code, err = import_contactlab([copy.parent], tmp_path)
    assert code != 0
    assert "contactlab was built for Python 3.99 (/opt/python3.99/bin/python3)" in err, err
    assert f"this is Python {RUNNING} ({sys.executable})" in err, err
    assert "run /opt/python3.99/bin/python3" in err, err
