"""contactlab.load_results: a results folder written by `contactlab run` (or contactlab.run)."""

import json
from dataclasses import dataclass, field
from pathlib import Path

from . import _core


@dataclass
class Results:
    """A run's results: its CSV tables as pandas DataFrames, by file stem, and its meta.json."""

    folder: Path
    tables: dict = field(default_factory=dict)
    meta: dict = field(default_factory=dict)

    @property
    def cycles(self):
        """cycles.csv: one row per cycle per model (the contact study)."""
        return self._table("cycles")

    @property
    def summary(self):
        """summary.csv: one row per model per sweep point (the contact study)."""
        return self._table("summary")

    def _table(self, name):
        if name not in self.tables:
            raise _core.Error(f"{self.folder}: no {name}.csv (the run's study wrote {', '.join(sorted(self.tables))})")
        return self.tables[name]

    def __getitem__(self, name):
        return self._table(name)


def load_results(folder):
    """Reads the results FOLDER: every CSV table (cycles.csv, summary.csv, convergence.csv, ...) as
    a pandas DataFrame and meta.json as a dict. Raises contactlab.Error when the folder or its
    meta.json is missing or unreadable."""
    import pandas

    folder = Path(folder)
    meta_file = folder / "meta.json"
    if not folder.is_dir():
        raise _core.Error(f"{folder}: no such results folder")
    try:
        meta = json.loads(meta_file.read_text())
    except FileNotFoundError:
        raise _core.Error(f"{meta_file}: missing (not a results folder of contactlab run)") from None
    except (OSError, ValueError) as e:
        raise _core.Error(f"{meta_file}: cannot read: {e}") from None
    tables = {}
    for csv in sorted(folder.glob("*.csv")):
        try:
            tables[csv.stem] = pandas.read_csv(csv)
        except (OSError, ValueError) as e:
            raise _core.Error(f"{csv}: cannot read: {e}") from None
    return Results(folder=folder, tables=tables, meta=meta)
