"""contactlab.load_results: a results folder written by `contactlab run` (or contactlab.run)."""

import csv
import io
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
    for table in sorted(folder.glob("*.csv")):
        tables[table.stem] = _read_table(table, pandas)
    return Results(folder=folder, tables=tables, meta=meta)


def _read_table(path, pandas):
    """PATH as a DataFrame, read as contactlab writes it (RFC 4180: a cell holding a comma, quote
    or line break is quoted). Every row must have as many cells as the header: pandas alone would
    take a row one cell longer as an index column and shift every column by one, silently."""
    try:
        with open(path, newline="") as f:
            text = f.read()
    except (OSError, ValueError) as e:
        raise _core.Error(f"{path}: cannot read: {e}") from None
    reader = csv.reader(io.StringIO(text, newline=""), strict=True)
    try:
        header = next(reader, None)
        if header is None:
            raise _core.Error(f"{path}: is empty (no header line)")
        start = reader.line_num
        for row in reader:
            if row and len(row) != len(header):
                raise _core.Error(f"{path}:{start + 1}: {len(row)} cells, the header (line 1) has {len(header)}")
            start = reader.line_num
    except csv.Error as e:
        raise _core.Error(f"{path}:{reader.line_num}: not a well-formed CSV row: {e}") from None
    try:
        return pandas.read_csv(io.StringIO(text, newline=""), index_col=False)
    except (ValueError, pandas.errors.ParserError) as e:
        raise _core.Error(f"{path}: cannot read: {e}") from None
