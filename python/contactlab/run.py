"""contactlab.run: an experiment config run as `contactlab run CONFIG --out DIR --set k=v` runs it."""

import json
import os
from pathlib import Path

from . import _core


def _override(key, value):
    """KEY=VALUE as the command line's --set takes it: strings as written (YAML), the rest as JSON."""
    if isinstance(value, str):
        text = value
    else:
        try:
            text = json.dumps(value)
        except TypeError as e:
            raise _core.Error(f"run: set[{key!r}]: {e}") from None
    return f"{key}={text}"


def run(config, out=None, set=None, *, profile="", jobs=(), parallel=0, cache=None, use_cache=True,
        progress=False):
    """Runs the experiment CONFIG (a YAML file, found through the data search path) like
    `contactlab run`, and returns the results folder as a Path.

    out       results folder (default results/NAME, as the command)
    set       overrides of config values: {"key.path": value} or ["key.path=value", ...], as --set;
              string values are YAML text, other values are written as JSON (lists, numbers, booleans)
    profile   a named set of overrides from the config's `profiles`
    jobs      run only these sweep points
    parallel  jobs run at once (0: all cores, or 1 when the config measures timing)
    cache     cache folder for fields and pointshells; use_cache=False neither reads nor writes it

    Raises contactlab.Error naming the config file and key when the config or an override is wrong.
    """
    if set is None:
        overrides = []
    elif isinstance(set, dict):
        overrides = [_override(k, v) for k, v in set.items()]
    elif isinstance(set, str):
        overrides = [set]
    else:
        overrides = [str(s) for s in set]
    return Path(_core._run(os.fspath(config), None if out is None else os.fspath(out), overrides, profile,
                           [int(j) for j in jobs], int(parallel), None if cache is None else os.fspath(cache),
                           bool(use_cache), bool(progress)))
