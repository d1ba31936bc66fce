"""Scenes (whirl/scene.h): one configured run of the N-link chain from an INI file, the same file
``whirl simulate`` runs, with the same overrides, returned as numpy arrays instead of CSV.

Units: the scene's own ([units] system = dimensionless or SI; SceneRun.units says which)."""
from __future__ import annotations

import os
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

from ._lazy import numpy as np
from . import _lib, _progress
from ._lib import ffi, lib, check


class SceneRun(_lib.Result):
    """The output of run_scene.

    ``columns``: the names of the scene's [output] columns, in order ("t" first);
    ``data``: a dict of one array per column over the output rows (``run["tip_x"]`` is
    ``run.data["tip_x"]``); ``trace_t`` and ``trace_x`` (shape (frames, N + 1, 3): the pivot, then
    masses 1..N, in the inertial frame) when the run was asked for its trace, else None;
    ``t`` the time reached; ``stopped`` (and ``deviation``) when [run] stop_deviation ended it;
    ``stats`` the integrator's counters; ``units`` a dict: physical (bool), length, mass,
    gravity (the chain's, in the scene's units)."""

    def __init__(self, columns: List[str], rows: List[float], trace_t: Optional[np.ndarray],
                 trace_x: Optional[np.ndarray], res: Any, units: Dict[str, Any]) -> None:
        self.columns = columns
        table = np.array(rows, dtype=np.float64).reshape(-1, len(columns))
        self.data = {name: table[:, k].copy() for k, name in enumerate(columns)}
        self.trace_t = trace_t
        self.trace_x = trace_x
        self.t = res.t
        self.stopped = bool(res.stopped)
        self.deviation = res.deviation if res.stopped else None
        self.stats = {k: getattr(res.stats, k)
                      for k in ("steps", "rejected", "rhs_evals", "iterations")}
        self.units = units

    def _columns(self) -> Tuple[Dict[str, Any], Dict[str, Any]]:
        # the scene's columns, as whirl simulate writes them
        return ({name: self.data[name] for name in self.columns},
                {"t": self.t, "stopped": self.stopped, "deviation": self.deviation})

    def __getitem__(self, name: str) -> np.ndarray:
        return self.data[name]

    def __repr__(self) -> str:
        return "SceneRun(%d rows of %s, t = %g%s)" % (
            len(self.data["t"]), ", ".join(self.columns), self.t,
            ", stopped" if self.stopped else "")


def _overrides(set: Union[None, str, Dict[str, Any], Sequence[str]]) -> List[str]:
    if set is None:
        return []
    if isinstance(set, dict):
        items = ["%s=%s" % (k, v) for k, v in set.items()]
    elif isinstance(set, str):
        items = [set]
    else:
        items = list(set)
    for item in items:
        if not isinstance(item, str) or "=" not in item:
            raise ValueError("an override is 'section.key=value', got %r" % (item,))
    return items


def run_scene(path: Union[str, "os.PathLike[str]"],
              set: Union[None, str, Dict[str, Any], Sequence[str]] = None,
              trace: Union[bool, float] = False, progress: Any = None) -> SceneRun:
    """Runs the scene file ``path`` (see include/whirl/scene.h and the README for its keys) and
    returns a SceneRun.

    set: overrides applied after the file, as ``whirl simulate --set`` takes them: a dict
      {"run.t_end": 5, "start.omega": "4Hz"}, a list of "section.key=value" strings, or one
      ({"run.pivot": "vertical:0.02"} is ``whirl simulate --pivot vertical:0.02``: the pivot on
      that path at [run] omega);
    trace: True to collect every mass's position every [output] trace_every (default: at
      every output row), or a number: the interval between frames in the scene's time unit;
      no file is written (the scene's [output] trace names none here).
    A bad scene raises whirl.Error with the library's message ("FILE:LINE: [section] key:
    problem"); a failed run raises whirl.Error too; Ctrl-C raises KeyboardInterrupt.
    progress: the scene's time reached out of its t_end (see whirl's progress=)."""
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError("path must be a file name, got %r" % (path,))
    path = os.fspath(path)
    items = _overrides(set)
    every = None
    if trace is not True and trace is not False:
        every = _lib.as_float(trace, "trace", positive=True)
    keep = [ffi.new("char[]", s.encode()) for s in items]
    over = ffi.new("char *[]", keep) if keep else ffi.NULL
    scene = ffi.new("whirl_scene *")
    pivot = ffi.new("whirl_scene_pivot *")  # [run] pivot: read beside the scene (whirl/scene.h)
    check(lib.whirl_scene_parse_with_pivot(path.encode(), over, len(keep), scene, pivot),
          "run_scene")
    work = ffi.NULL
    try:
        if every is not None:
            scene.trace_every = every
        work = _lib.check_ptr(lib.whirl_scene_work_alloc_with_pivot(scene, pivot))
        columns = [ffi.string(lib.whirl_column_name(scene.columns[c])).decode()
                   for c in range(scene.n_columns)]
        index = [scene.columns[c] for c in range(scene.n_columns)]
        rows: List[float] = []
        frames_t: List[float] = []
        frames_x: List[np.ndarray] = []

        @ffi.callback("int(void *, const double *)")
        def on_row(ctx: Any, value: Any) -> int:
            rows.extend(value[i] for i in index)
            return 0

        @ffi.callback("int(void *, double, const double *, const double *, size_t)")
        def on_frame(ctx: Any, t: float, pivot: Any, x: Any, n: int) -> int:
            frame = np.empty((n + 1, 3))
            frame[0] = ffi.unpack(pivot, 3)
            frame[1:] = np.frombuffer(ffi.buffer(x, 3 * n * 8), dtype=np.float64).reshape(n, 3)
            frames_t.append(t)
            frames_x.append(frame)
            return 0

        out = ffi.new("whirl_scene_output *")
        out.row = on_row
        out.frame = on_frame if trace is not False else ffi.NULL
        rep = _progress.report(progress, "run_scene", scene.t_end,
                               "s" if scene.physical else "T")
        if _progress.active(progress):
            @ffi.callback("int(void *, double)")
            def on_progress(ctx: Any, t: float) -> int:
                rep.c_update(t)
                return lib.WHIRL_EINTERRUPTED if rep.error is not None else 0
            out.progress = on_progress
        res = ffi.new("whirl_scene_result *")
        with rep:
            with _lib.interruptible("run_scene"):
                status = lib.whirl_scene_work_run(work, out, res)
                rep.reraise()
            check(status, "run_scene")
            rep.finish()
        units = {"physical": bool(scene.physical), "length": scene.chain_length,
                 "mass": scene.chain_mass, "gravity": scene.gravity}
        trace_t = np.array(frames_t) if trace is not False else None
        trace_x = np.array(frames_x) if trace is not False else None
        return SceneRun(columns, rows, trace_t, trace_x, res, units)
    finally:
        lib.whirl_scene_work_free(work)  # the work refers to the scene: freed first
        lib.whirl_scene_free(scene)
