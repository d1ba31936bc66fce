"""The stability atlas of the continuous chain, as ``whirl windows --atlas``: libwhirl's atlas
(whirl/atlas.h; docs/guide/atlas.md), chunk by chunk: every window of instability of each mode
from its birth to omega_max, with the Krein signatures of the colliding pair at each closed
edge, the range cut into chunks at the multiples of 5 in omega.

The file is the library's text, the command line's byte for byte: after each chunk it is
rewritten atomically (a temporary file beside it, renamed over it) with the windows so far and
one line "# done mode K omega A B" per chunk finished, and it is locked (flock) for the whole run,
so that a run of the command line and one of Python refuse each other while one writes it.
resume=True keeps the chunks of a file written by either and computes the rest; the library
checks the file (whirl_atlas_read: its options, every line) as for the command line."""
from __future__ import annotations

import os
from typing import Any, Iterable, List, Optional, Union

from ._lazy import numpy as np
from . import _lib, _progress
from ._lib import ffi, lib, as_int, as_float
from .steady import Units, units_of

OMEGA_MAX = 5000.0      # WHIRL_CONTINUUM_OMEGA_MAX

ATLAS_DTYPE = [("mode", "i4"), ("from", "f8"), ("to", "f8"), ("open_from", "?"),
               ("open_to", "?"), ("freq_from", "f8"), ("freq_to", "f8"),
               ("sig_from", "i4"), ("sig_to", "i4"), ("max_growth", "f8"),
               ("at", "f8"), ("err_from", "f8"), ("err_to", "f8")]
_RATES = ("from", "to", "freq_from", "freq_to", "max_growth", "at", "err_from", "err_to")


class _File:
    """The atlas's file, locked for the whole run: the library's whirl_atlas_file (the command
    line's lock too: flock on the file the path names, passed to each file renamed over it)."""

    def __init__(self, path: str, make: bool) -> None:
        self.path = path
        folder = os.path.dirname(os.path.abspath(path))
        if not os.path.isdir(folder):
            raise FileNotFoundError(2, "no such folder for the atlas's file", folder)
        f = lib.whirl_atlas_file_alloc(os.fsencode(path), 1 if make else 0)
        if f == ffi.NULL:
            raise _lib.error(lib.whirl_last_status() or _lib.GSL_EFAILED,
                             "atlas: " + _lib.last_error())
        self.file: Any = f

    def read(self) -> bytes:
        fd = lib.whirl_atlas_file_fd(self.file)
        os.lseek(fd, 0, os.SEEK_SET)
        chunks: List[bytes] = []
        while True:
            b = os.read(fd, 1 << 16)
            if not b:
                return b"".join(chunks)
            chunks.append(b)

    def commit(self, data: bytes) -> None:
        """The file rewritten with data (whirl_atlas_file_commit: a file beside it, its mode
        kept, locked, renamed over it)."""
        if lib.whirl_atlas_file_commit(self.file, data, len(data)) != _lib.GSL_SUCCESS:
            raise _lib.error(lib.whirl_last_status() or _lib.GSL_EFAILED,
                             "atlas: " + _lib.last_error())

    def close(self) -> None:
        if self.file is not None:
            lib.whirl_atlas_file_free(self.file)
            self.file = None


def _text(a: Any) -> bytes:
    """The atlas's file as it stands (whirl_atlas_text)."""
    n = lib.whirl_atlas_text(a, ffi.NULL, 0)
    buf = ffi.new("char[]", n + 1)
    lib.whirl_atlas_text(a, buf, n + 1)
    return ffi.unpack(buf, n)


def _array(a: Any, u: Units) -> np.ndarray:
    """The atlas's windows (whirl_atlas_rows), rates in the caller's units."""
    count = ffi.new("size_t *")
    rows = lib.whirl_atlas_rows(a, count)
    out = np.zeros(count[0], dtype=ATLAS_DTYPE)
    for i in range(count[0]):
        r, w = rows[i], rows[i].w
        out[i] = (r.mode, getattr(w, "from"), w.to, w.open_from, w.open_to, w.freq_from,
                  w.freq_to, r.sig_from, r.sig_to, w.max_growth, w.at, w.err_from, w.err_to)
    for name in _RATES:
        out[name] *= u.rate
    return out


def _modes(modes: Union[int, Iterable[int]]) -> List[int]:
    seq = [modes] if isinstance(modes, (int, np.integer)) else list(modes)
    if not seq:
        raise ValueError("modes must not be empty")
    out = [as_int(k, "mode", minimum=1, maximum=lib.WHIRL_MODE_MAX) for k in seq]
    if len(set(out)) != len(out):
        raise ValueError("modes must not repeat a mode, got %s" % out)
    return out


def atlas(modes: Union[int, Iterable[int]] = range(2, 9), omega_max: Any = None,
          output: Optional[Union[str, "os.PathLike[str]"]] = None, resume: bool = False,
          degree: int = 16, tol: Any = None, scan_step: Any = None,
          memory_mb: Optional[float] = None, progress: Any = None,
          length: Optional[float] = None, mass: Optional[float] = None,
          gravity: Optional[float] = None, units: Optional[Units] = None) -> np.ndarray:
    """The stability atlas of the continuous chain, as
    ``whirl windows --atlas --modes LIST --omega-max B [--degree P --tol T --scan-step H]``
    ``[--memory MB] -o FILE [--resume]``: every
    window of instability of each of ``modes`` (default 2..8) from its birth to ``omega_max``
    (at most 5000 sqrt(g/L)) (whirl.stability_windows with links=None, chunk by chunk), with
    the Krein signature of the slower mode of the colliding pair just outside each closed edge.
    Rates (omega_max, tol, scan_step and the result's) in the caller's units (see whirl.Units);
    the defaults (None), as the command line's, are dimensionless: omega_max 40, tol 1e-9,
    scan_step 0.25 sqrt(g/L). The file is dimensionless, as the command line's.

    output: the file, rewritten after every chunk of 5 in omega with the windows so far and
    the chunks done (the command line's file, byte for byte; locked while the call runs).
    resume=True: the chunks already in ``output`` (written by this function or by the command
    line with the same options; other options are refused with the first difference) are kept
    and only the rest computed. ``progress``: chunks done (see whirl's progress=).

    Returns a structured array, one row per window in increasing mode and omega, with fields
    mode, from, to, open_from, open_to (True: that end is the end of the range), freq_from,
    freq_to (|Im lambda| where the pair meets [1/T]), sig_from, sig_to (-1, 0, +1), max_growth
    [1/T], at, err_from, err_to (each edge's discretisation error estimate). Ctrl-C raises
    KeyboardInterrupt("whirl: atlas interrupted: ...") naming the chunks kept in the file; its
    attribute ``partial`` holds the windows of the chunks finished."""
    u = units_of(length, mass, gravity, units)
    ks = _modes(modes)
    def rate(value: Any, name: str, default: float) -> float:
        if value is None:
            return default
        return as_float(value, name, positive=True, kind="rate", units=u) / u.rate
    p = ffi.new("whirl_atlas_params *", lib.whirl_atlas_defaults())
    p.omega_max = rate(omega_max, "omega_max", 40.0)
    if not p.omega_max <= OMEGA_MAX:
        raise ValueError("omega_max must be in (0, %g] sqrt(g/L) for the atlas, got %g"
                         % (OMEGA_MAX, p.omega_max))
    p.tol = rate(tol, "tol", 1e-9)
    p.scan_step = rate(scan_step, "scan_step", 0.25)
    if not p.tol >= 1e-13:
        raise ValueError("tol must be >= 1e-13 sqrt(g/L), got %g" % p.tol)
    if not p.tol < p.scan_step:
        raise ValueError("tol must be smaller than scan_step")
    p.degree = as_int(degree, "degree", minimum=6, maximum=64)
    p.n_modes = len(ks)
    for i, k in enumerate(ks):
        p.modes[i] = k
    if memory_mb is not None:
        from .stability import _memory_mb
        p.memory_mb = _memory_mb(memory_mb)
    if resume and output is None:
        raise ValueError("resume=True needs output (the file to resume)")
    path = None if output is None else os.fspath(output)
    if path is not None and (not isinstance(path, str) or not path or path == "-"):
        raise ValueError("output must be a file name (the atlas is rewritten after every "
                         "chunk), got %r" % (output,))
    a = _lib.check_ptr(lib.whirl_atlas_alloc(p), lib.whirl_atlas_free)
    f = None if path is None else _File(path, make=not resume)
    try:
        if resume and f is not None:
            data = f.read()
            status = lib.whirl_atlas_read_text(a, data, len(data), os.fsencode(f.path))
            if status:
                raise _lib.error(status, "atlas: resume: " + _lib.last_error())
        nchunks = lib.whirl_atlas_chunks(a)
        total = len(ks) * nchunks
        finished = lib.whirl_atlas_done_count(a)
        computed = ffi.new("int *")
        with _progress.report(progress, "atlas", total, "chunks") as rep:
            rep.update(finished)
            with _lib.interruptible("atlas"):
                for k in range(len(ks)):
                    for j in range(nchunks):
                        if lib.whirl_atlas_done(a, k, j):
                            continue
                        status = lib.whirl_atlas_compute(a, k, j, computed)
                        if status == lib.WHIRL_EINTERRUPTED:
                            lib.whirl_stop_clear()
                            raise _stopped(a, finished, total, path, u)
                        if status:
                            raise _lib.error(status, "atlas: " + _lib.last_error_in(u))
                        if computed[0] and f is not None:
                            f.commit(_text(a))
                        finished += 1
                        rep.update(finished)
                if lib.whirl_stop_requested():  # Ctrl-C after the last chunk
                    lib.whirl_stop_clear()
                    raise _stopped(a, finished, total, path, u)
                if f is not None:  # all chunks
                    f.commit(_text(a))
            rep.finish()
    finally:
        if f is not None:
            f.close()
    return _array(a, u)


def _stopped(a: Any, finished: int, total: int, path: Optional[str],
             u: Units) -> KeyboardInterrupt:
    where = (" in '%s' (continue with resume=True)" % path) if path else ""
    e = KeyboardInterrupt("whirl: atlas interrupted: %d of %d chunks%s" % (finished, total,
                                                                          where))
    e.partial = _array(a, u)  # type: ignore[attr-defined]
    return e
