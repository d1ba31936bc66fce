"""Reading whirl's own files back: every CSV the command line writes (a header line of column
names after "#" comment lines, one of them "# units: ...") and the traces (blocks "x y z t", one
per time). Numbers are read with Python's float (independent of the process locale)."""
from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple, Union

from ._lazy import numpy as np
from . import _lib
from .steady import Units

_UNITS_SI = re.compile(r"#\s*units:.*\bL=(\S+)\s+M=(\S+)\s+g=(\S+)")
_SUMMARY = re.compile(r"([A-Za-z_][A-Za-z_0-9]*)=(\S*)")


@dataclass(eq=False)  # _lib.Result's == (array-aware)
class Table(_lib.Result):
    """A whirl file read back: ``columns`` (names, in order), ``data`` (one array per column:
    float64, with NaN for an empty field; text columns such as ``verdict`` or ``state`` as
    arrays of str), ``units`` (the file's "# units:" line as a whirl.Units; dimensionless when
    it has none), ``comments`` (the "#" lines, without "# "), ``summary`` (the key=value pairs of
    the comment lines, the first of each key: e.g. a shape's omega, mode, node_count), and for a trace ``t``
    (frame times) and ``x`` (frames, pivot + N masses, 3) [inertial frame]. ``table["omega"]``
    is ``table.data["omega"]``."""

    columns: List[str]
    data: Dict[str, np.ndarray]
    units: Units = field(default_factory=Units)
    comments: List[str] = field(default_factory=list)
    summary: Dict[str, str] = field(default_factory=dict)
    t: Optional[np.ndarray] = None
    x: Optional[np.ndarray] = None

    def __getitem__(self, name: str) -> np.ndarray:
        return self.data[name]

    def _columns(self) -> Tuple[Dict[str, Any], Dict[str, Any]]:
        # the file's columns; the summary's values as the file has them (text)
        return {name: self.data[name] for name in self.columns}, dict(self.summary)

    def __len__(self) -> int:
        return len(next(iter(self.data.values()))) if self.data else 0

    def __repr__(self) -> str:
        trace = "" if self.t is None else ", trace of %d frames" % len(self.t)
        return "Table(%d rows of %s%s, %r)" % (len(self), ", ".join(self.columns) or "no columns",
                                              trace, self.units)


def _units(comments: List[str]) -> Units:
    for c in comments:
        m = _UNITS_SI.match("# " + c)
        if m:
            return Units(float(m.group(1)), float(m.group(2)), float(m.group(3)))
    return Units()


def _column(values: List[str]) -> np.ndarray:
    try:
        return np.array([float(v) if v.strip() else np.nan for v in values], dtype=np.float64)
    except ValueError:
        return np.array(values, dtype=str)


def _trace(path: str, comments: List[str], lines: List[str]) -> Table:
    times: List[float] = []
    frames: List[List[Tuple[float, float, float]]] = []
    for line in lines:
        s = line.strip()
        if s.startswith("# t ="):
            times.append(float(s.split("=", 1)[1]))
            frames.append([])
        elif s and not s.startswith("#"):
            if not frames:
                raise ValueError("%s: a trace row before its '# t =' line" % path)
            x, y, z = (float(v) for v in s.split()[:3])
            frames[-1].append((x, y, z))
    sizes = {len(f) for f in frames}
    if len(sizes) > 1:
        raise ValueError("%s: the trace's frames have different sizes %s" % (path, sorted(sizes)))
    t = np.array(times)
    positions = np.array(frames, dtype=np.float64).reshape(len(frames), -1, 3)
    return Table(columns=["t"], data={"t": t}, units=_units(comments), comments=comments,
                 summary={}, t=t, x=positions)


def read_csv(path: Union[str, "os.PathLike[str]"]) -> Table:
    """Reads any file whirl writes (shape, critical, sweep, equilibria, stability, driven,
    regime, fit, simulate, and traces) into a Table of arrays with its units. A file with no
    header line, or rows of the wrong length, raises ValueError naming the file and line."""
    path = os.fspath(path)
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    comments: List[str] = []
    i = 0
    while i < len(lines) and (lines[i].startswith("#") or not lines[i].strip()):
        if lines[i].startswith("#"):
            comments.append(lines[i][1:].strip())
        i += 1
    if comments and comments[0].startswith("trace:"):
        return _trace(path, comments, lines)
    if i == len(lines):
        raise ValueError("%s: no header line (column names)" % path)
    columns = [c.strip() for c in lines[i].split(",")]
    rows: List[List[str]] = []
    for number, line in enumerate(lines[i + 1:], start=i + 2):
        if not line.strip() or line.startswith("#"):
            continue
        fields = line.split(",")
        if len(fields) != len(columns):
            raise ValueError("%s:%d: %d fields, the header has %d" % (path, number, len(fields),
                                                                     len(columns)))
        rows.append(fields)
    data: Dict[str, np.ndarray] = {}
    for j, name in enumerate(columns):
        data[name] = _column([r[j] for r in rows])
    summary: Dict[str, Any] = {}
    for c in comments:  # the first of each key, the units line aside
        if not c.startswith("units:"):
            for key, value in _SUMMARY.findall(c):
                summary.setdefault(key, value)
    return Table(columns=columns, data=data, units=_units(comments), comments=comments,
                 summary=summary)
