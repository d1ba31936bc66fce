"""The stability atlas of the continuous chain, as ``whirl windows --atlas``
(src/cli/stability_atlas.c; docs/guide/atlas.md): every window of instability of each mode from
its birth to omega_max (whirl_cstab_windows), with the Krein signatures of the colliding pair at
each closed edge, the range cut into chunks at the multiples of 5 in omega.

The file is the command line's, byte for byte: after each chunk it is rewritten atomically (a
temporary file beside it, renamed over it) with the windows so far and one line "# done mode K
omega A B" per chunk finished, and it is locked (flock) for the whole run, so that a run of the
command line and one of Python refuse each other while one writes it. resume=True keeps the
chunks of a file written by either and computes the rest; the file must begin with the lines
this atlas writes (its options), and every line after them is checked as the command line
checks it."""
import fcntl
import math
import os
import stat
import tempfile
from typing import Any, Iterable, List, Optional, Tuple, Union

import numpy as np

from . import _lib, _progress
from ._lib import ffi, lib, as_int, as_float
from .steady import Units, units_of

CHUNK = 5.0             # chunk ends at the multiples of this rate [sqrt(g/L)] (ATLAS_CHUNK)
WINDOWS_MAX = 4096      # windows of all modes at most (ATLAS_WINDOWS)
CHUNK_WINDOWS = 256     # windows of one chunk at most (ATLAS_CHUNK_WINDOWS)
SIDE = 1e-6             # the signatures are taken this far outside each edge (ATLAS_SIDE)
LINE_MAX = 1024         # characters of a line of the file (ATLAS_LINE_MAX)
OMEGA_MAX = 5000.0      # WHIRL_CONTINUUM_OMEGA_MAX
COLUMNS = ("mode,from,to,open_from,open_to,freq_from,freq_to,sig_from,sig_to,max_growth,at,"
           "err_from,err_to")
_KINDS = "iddiiddiidddd"  # the columns: i an integer, d a number

ATLAS_DTYPE = np.dtype([("mode", "i4"), ("from", "f8"), ("to", "f8"), ("open_from", "?"),
                        ("open_to", "?"), ("freq_from", "f8"), ("freq_to", "f8"),
                        ("sig_from", "i4"), ("sig_to", "i4"), ("max_growth", "f8"),
                        ("at", "f8"), ("err_from", "f8"), ("err_to", "f8")])
_RATES = ("from", "to", "freq_from", "freq_to", "max_growth", "at", "err_from", "err_to")


def _num(x: float) -> str:
    """x as the command line writes it (whirl_format_double: the shortest exact of %.15g,
    %.16g, %.17g)."""
    buf = ffi.new("char[]", lib.WHIRL_FORMAT_MAX)
    return ffi.string(lib.whirl_format_double(buf, x)).decode()


class _Options:
    """The options that change a row (all in the file's header)."""

    def __init__(self, modes: List[int], omega_max: float, degree: int, tol: float,
                 scan_step: float) -> None:
        self.modes, self.omega_max, self.degree = modes, omega_max, degree
        self.tol, self.scan_step = tol, scan_step
        self.nchunks = int(math.ceil(omega_max / CHUNK - 1e-12))

    def chunk(self, j: int) -> Tuple[float, float]:
        """The chunk j of the rates: [j, j + 1) CHUNK, the last ending at omega_max."""
        return j * CHUNK, min(self.omega_max, (j + 1) * CHUNK)

    def head(self, done: Optional[List[List[bool]]]) -> str:
        """The lines before the rows (stability_atlas.c, write_head): the title, the options,
        the signatures' note, the chunks done, the columns."""
        modes = ",".join(str(k) for k in self.modes)
        lines = ["# whirl stability --atlas: continuous chain (Chebyshev collocation of degree "
                 "%d on elements), modes %s, from each mode's birth to omega %s; dimensionless "
                 "(rates sqrt(g/L))" % (self.degree, modes.replace(",", ",", -1),
                                        _num(self.omega_max)),
                 "# atlas: modes=%s omega_max=%s degree=%d tol=%s scan_step=%s"
                 % (modes, _num(self.omega_max), self.degree, _num(self.tol),
                    _num(self.scan_step)),
                 "# sig_from, sig_to: Krein signature of the slower mode of the colliding pair "
                 "on the stable side of the edge; err: discretisation error estimate of the "
                 "edge (a refined discretisation)"]
        for k, mode in enumerate(self.modes if done else []):
            for j in range(self.nchunks):
                if done is not None and done[k][j]:
                    lo, hi = self.chunk(j)
                    lines.append("# done mode %d omega %s %s" % (mode, _num(lo), _num(hi)))
        lines.append(COLUMNS)
        return "\n".join(lines) + "\n"


def _row_text(r: List[Any]) -> str:
    return "%d,%s,%s,%d,%d,%s,%s,%d,%d,%s,%s,%s,%s\n" % (
        r[0], _num(r[1]), _num(r[2]), r[3], r[4], _num(r[5]), _num(r[6]), r[7], r[8],
        _num(r[9]), _num(r[10]), _num(r[11]), _num(r[12]))


class _File:
    """The atlas's file, locked for the whole run (as the command line's cli_lock: flock on
    the file the path names, taken again on each file renamed over it)."""

    def __init__(self, path: str, make: bool) -> None:
        self.path = path
        self.fd = -1
        self.made = False
        for _ in range(8):  # the path may change between the tries (another run)
            try:
                st = os.stat(path)
            except FileNotFoundError:
                st = None
            try:
                if st is not None:
                    if not stat.S_ISREG(st.st_mode):
                        raise ValueError("atlas: output %r is not a regular file (it is "
                                         "rewritten after every chunk)" % path)
                    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_NOCTTY)
                elif not make:
                    raise ValueError("atlas: resume: cannot read %r: no such regular file"
                                     % path)
                else:
                    try:
                        fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_EXCL | os.O_NOCTTY,
                                     0o666)
                    except FileExistsError:  # made by another run meanwhile: try again
                        continue
                    self.made = True
            except FileNotFoundError:
                if st is None:  # no such folder
                    raise
                continue  # removed by another run meanwhile: try again
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                os.close(fd)
                raise _lib.Error(_lib.GSL_EFAILED, "atlas: '%s' is being written by another "
                                 "run (locked): wait for it or write another file" % path)
            now = os.stat(path)
            mine = os.fstat(fd)
            if (mine.st_dev, mine.st_ino) != (now.st_dev, now.st_ino):
                os.close(fd)
                raise _lib.Error(_lib.GSL_EFAILED, "atlas: '%s' was replaced by another run "
                                 "while this one started" % path)
            self.fd = fd
            return
        raise _lib.Error(_lib.GSL_EFAILED, "atlas: cannot lock '%s': other runs keep making "
                         "and removing it" % path)

    def read(self) -> bytes:
        os.lseek(self.fd, 0, os.SEEK_SET)
        chunks: List[bytes] = []
        while True:
            b = os.read(self.fd, 1 << 16)
            if not b:
                return b"".join(chunks)
            chunks.append(b)

    def commit(self, text: str) -> None:
        """The file rewritten with text: a temporary file beside it (its mode kept), locked,
        renamed over it."""
        target = os.path.realpath(self.path)
        fd, tmp = tempfile.mkstemp(prefix=os.path.basename(target) + ".tmp.",
                                   dir=os.path.dirname(target))
        try:
            st = os.fstat(self.fd)
            os.fchmod(fd, stat.S_IMODE(st.st_mode))
            data = text.encode()
            while data:
                data = data[os.write(fd, data):]
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            os.replace(tmp, target)
        except BaseException:
            os.close(fd)
            try:
                os.unlink(tmp)
            except FileNotFoundError:
                pass
            raise
        os.close(self.fd)  # the old file's lock: it was replaced
        self.fd, self.made = fd, False

    def close(self) -> None:
        if self.fd < 0:
            return
        try:  # the empty file made to hold the lock, when the run wrote nothing in its place
            mine, now = os.fstat(self.fd), os.stat(self.path)
            if (self.made and mine.st_size == 0
                    and (mine.st_dev, mine.st_ino) == (now.st_dev, now.st_ino)):
                os.unlink(self.path)
        except OSError:
            pass
        os.close(self.fd)
        self.fd = -1


def _difference(want: str, have: str) -> str:
    """The first differing word of two header lines with the word before it
    (cli_resume_difference)."""
    a, b = want.split(), have.split()
    prev = ""
    for i in range(max(len(a), len(b))):
        x = a[i][:60] if i < len(a) else "(the end of the line)"
        y = b[i][:60] if i < len(b) else "(the end of the line)"
        if x != y:
            p = prev + " " if prev else ""
            return "'%s%s' where these options write '%s%s'" % (p, y, p, x)
        prev = x
    return "other spacing than these options write"


def _parse_row(line: str, o: _Options) -> List[Any]:
    """The 13 fields of a row (stability_atlas.c, cli_row_check and parse_row), or ValueError
    with the reason."""
    fields = line.rstrip("\n").split(",")
    if len(fields) != len(_KINDS):
        raise ValueError("%d columns, the header has %d (a row cut short or run together)"
                         % (len(fields), len(_KINDS)))
    row: List[Any] = []
    for c, (kind, text) in enumerate(zip(_KINDS, fields)):
        try:
            v: Any = int(text) if kind == "i" else float(text)
        except ValueError:
            raise ValueError("column %d is not %s" % (c + 1, "an integer" if kind == "i"
                                                     else "a number")) from None
        if kind == "d" and not math.isfinite(v):
            raise ValueError("column %d holds '%s', not a finite number" % (c + 1, text[:40]))
        row.append(v)
    if row[0] not in o.modes:
        raise ValueError("mode %d was not asked for (modes)" % row[0])
    if row[3] not in (0, 1) or row[4] not in (0, 1):
        raise ValueError("open_from and open_to must be 0 or 1")
    if abs(row[7]) > 1 or abs(row[8]) > 1:
        raise ValueError("a signature must be -1, 0 or 1")
    if not row[1] <= row[2]:
        raise ValueError("from is beyond to")
    return row


def _read(data: bytes, path: str, o: _Options, done: List[List[bool]]) -> List[List[Any]]:
    """resume: the chunks done (into done) and the rows of the file, every line checked as
    the command line checks it (resume.c, stability_atlas.c's read_atlas)."""
    def refuse(lineno: int, why: str) -> _lib.Error:
        return _lib.error(4, "atlas: resume: %s:%d: %s: the file cannot be trusted (remove the "
                          "row, or start the atlas afresh)" % (path, lineno, why))
    want = o.head(None).splitlines(keepends=True)
    lines = data.split(b"\n")
    complete = lines[:-1]  # the last piece has no newline: an unfinished line, or nothing
    rows: List[List[Any]] = []
    h = 0
    for lineno, raw in enumerate(complete, 1):
        if b"\0" in raw or len(raw) + 1 > LINE_MAX + 1:
            raise refuse(lineno, "%s (the limit is %d characters)"
                         % ("a NUL byte" if b"\0" in raw else "a line too long", LINE_MAX))
        line = raw.decode("utf-8", "replace") + "\n"
        if h < len(want):  # the header, line by line
            if line.startswith("# done "):
                _read_done(line, o, done, lambda why, n=lineno: refuse(n, why))
                continue
            if line != want[h]:
                raise _lib.error(4, "atlas: resume: '%s' was not written by an atlas with these "
                                 "options: line %d has %s" % (path, lineno,
                                                              _difference(want[h], line)))
            h += 1
            continue
        if line.startswith("#"):
            if line.startswith("# done ") and not rows:
                _read_done(line, o, done, lambda why, n=lineno: refuse(n, why))
                continue
            raise refuse(lineno, "a comment among the rows")
        try:
            row = _parse_row(line, o)
        except ValueError as e:
            raise refuse(lineno, str(e)) from None
        k = o.modes.index(row[0])
        if not any(done[k][j] and o.chunk(j)[0] <= row[1] <= o.chunk(j)[1]
                   for j in range(o.nchunks)):
            raise refuse(lineno, "a window of mode %d at omega %s, in no chunk done"
                         % (row[0], _num(row[1])))
        if len(rows) == WINDOWS_MAX:
            raise refuse(lineno, "more than %d windows" % WINDOWS_MAX)
        rows.append(row)
    if h < len(want):
        raise _lib.error(4, "atlas: resume: '%s' holds no atlas of these options" % path)
    return rows


def _read_done(line: str, o: _Options, done: List[List[bool]], refuse: Any) -> None:
    """A "# done mode K omega A B" line: its chunk marked done (read_done)."""
    words = line.split()
    mode = None
    if len(words) == 7 and words[2] == "mode" and words[4] == "omega":
        try:
            mode = int(words[3])
        except ValueError:
            pass
    if mode is None or mode not in o.modes:
        raise refuse("'%s' names no chunk of a mode asked for" % line.rstrip("\n"))
    k = o.modes.index(mode)
    for j in range(o.nchunks):
        lo, hi = o.chunk(j)
        if (_num(lo), _num(hi)) == (words[5], words[6]):
            if done[k][j]:
                raise refuse("chunk %s %s of mode %d listed twice" % (words[5], words[6], mode))
            done[k][j] = True
            return
    raise refuse("omega %s %s is no chunk of this atlas (they end at the multiples of %g and "
                 "at omega_max)" % (words[5], words[6], CHUNK))


def _edge_signature(w: Any, mode: int, omega: float, freq: float) -> Tuple[int, int]:
    """(status, the signature of the slower mode of the neutral pair nearest the collision
    frequency freq at omega; 0 if none of opposite signs is found) (edge_signature)."""
    status = lib.whirl_cstab_linearise(w, omega, mode, 0, ffi.NULL)
    sp = ffi.new("whirl_spectrum *")
    if not status:
        status = lib.whirl_cstab_spectrum(w, 1, sp)
    if status:
        return status, 0
    target = -freq * freq
    n = int(sp.count)
    a = b = n  # the two neutral mu nearest -freq^2
    for i in range(n):
        if sp.signature[i] == 0:
            continue
        d = abs(sp.re[i] - target)
        if a == n or d < abs(sp.re[a] - target):
            b, a = a, i
        elif b == n or d < abs(sp.re[b] - target):
            b = i
    if b == n or sp.signature[a] == sp.signature[b]:
        return 0, 0
    slow = a if sp.re[a] > sp.re[b] else b  # mu = -f^2: the larger mu is slower
    return 0, int(sp.signature[slow])


def _chunk(w: Any, o: _Options, mode: int, lo: float, hi: float,
           win: Any) -> Tuple[int, List[List[Any]]]:
    """(status, the windows of mode in the chunk (lo, hi] with the Krein signatures of their
    closed edges) (chunk_windows)."""
    p = ffi.new("whirl_windows_params *", lib.whirl_windows_defaults())
    p.omega_min = max(lo, 1e-3)
    p.omega_max = hi
    p.tol = o.tol
    p.scan_step = o.scan_step
    st = ffi.new("whirl_windows_stats *")
    count = ffi.new("size_t *")
    status = lib.whirl_cstab_windows(w, mode, p, win, CHUNK_WINDOWS, count, st)
    out = []
    for i in range(count[0] if not status else 0):
        x = win[i]
        sig = [0, 0]
        if not x.open_from and x.freq_from > 0:
            status, sig[0] = _edge_signature(w, mode, getattr(x, "from") - SIDE, x.freq_from)
        if not status and not x.open_to and x.freq_to > 0:
            status, sig[1] = _edge_signature(w, mode, x.to + SIDE, x.freq_to)
        if status:
            break
        out.append([mode, getattr(x, "from"), x.to, int(x.open_from), int(x.open_to),
                    x.freq_from, x.freq_to, sig[0], sig[1], x.max_growth, x.at, x.err_from,
                    x.err_to])
    return status, out


def _add(rows: List[List[Any]], new: List[List[Any]]) -> None:
    """Adds the windows of one chunk, joining one that continues a window open at the chunk's
    start (add_rows)."""
    for r in new:
        prev = None
        for q in rows:
            if (q[0] == r[0] and q[4] and r[3]
                    and abs(q[2] - r[1]) <= 1e-12 * max(1.0, r[1])):
                prev = q
        if prev is not None:
            prev[2], prev[4], prev[6], prev[12], prev[8] = r[2], r[4], r[6], r[12], r[8]
            if r[9] > prev[9]:
                prev[9], prev[10] = r[9], r[10]
            continue
        if len(rows) == WINDOWS_MAX:
            raise _lib.Error(_lib.GSL_EFAILED, "atlas: more than %d windows" % WINDOWS_MAX)
        rows.append(list(r))


def _array(rows: List[List[Any]], u: Units) -> np.ndarray:
    out = np.array([tuple(r) for r in rows], dtype=ATLAS_DTYPE)
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
    """The stability atlas of the continuous chain, as ``whirl windows --atlas --modes LIST
    --omega-max B [--degree P --tol T --scan-step H --memory MB] -o FILE [--resume]``: every
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
    wmax = rate(omega_max, "omega_max", 40.0)
    if not wmax <= OMEGA_MAX:
        raise ValueError("omega_max must be in (0, %g] sqrt(g/L) for the atlas, got %g"
                         % (OMEGA_MAX, wmax))
    t = rate(tol, "tol", 1e-9)
    h = rate(scan_step, "scan_step", 0.25)
    if not t >= 1e-13:
        raise ValueError("tol must be >= 1e-13 sqrt(g/L), got %g" % t)
    if not t < h:
        raise ValueError("tol must be smaller than scan_step")
    o = _Options(ks, wmax, as_int(degree, "degree", minimum=6, maximum=64), t, h)
    cp = ffi.new("whirl_cstab_params *", lib.whirl_cstab_defaults())
    cp.degree = o.degree
    if memory_mb is not None:
        from .stability import _memory_mb
        cp.memory_mb = _memory_mb(memory_mb)
    if resume and output is None:
        raise ValueError("resume=True needs output (the file to resume)")
    path = None if output is None else os.fspath(output)
    if path is not None and (not isinstance(path, str) or not path or path == "-"):
        raise ValueError("output must be a file name (the atlas is rewritten after every "
                         "chunk), got %r" % (output,))
    done = [[False] * o.nchunks for _ in ks]
    w = _lib.check_ptr(lib.whirl_cstab_alloc(cp), lib.whirl_cstab_free)
    win = ffi.new("whirl_window[]", CHUNK_WINDOWS)
    births = ffi.new("double *")
    f = None if path is None else _File(path, make=not resume)
    try:
        rows = _read(f.read(), f.path, o, done) if resume and f is not None else []
        total = len(ks) * o.nchunks
        finished = sum(map(sum, done))
        with _progress.report(progress, "atlas", total, "chunks") as rep:
            rep.update(finished)
            with _lib.interruptible("atlas"):
                for k, mode in enumerate(ks):
                    _lib.check(lib.whirl_continuum_critical(mode, 0.0, births), "atlas")
                    birth = births[0]
                    for j in range(o.nchunks):
                        if done[k][j]:
                            continue
                        lo, hi = o.chunk(j)
                        if hi > birth * (1 + 1e-6):  # else the mode does not exist yet
                            status, new = _chunk(w, o, mode, lo, hi, win)
                            if status == lib.WHIRL_EINTERRUPTED:
                                lib.whirl_stop_clear()
                                raise _stopped(rows, finished, total, path, u)
                            if status:
                                _fail(status, mode, p_lo=max(lo, 1e-3), hi=hi, u=u)
                            _add(rows, new)
                            done[k][j] = True
                            rows.sort(key=lambda r: (r[0], r[1]))
                            if f is not None:
                                f.commit(o.head(done) + "".join(map(_row_text, rows)))
                        done[k][j] = True
                        finished += 1
                        rep.update(finished)
                        if lib.whirl_stop_requested():  # Ctrl-C between two chunks
                            lib.whirl_stop_clear()
                            raise _stopped(rows, finished, total, path, u)
                if f is not None:  # all chunks
                    f.commit(o.head(done) + "".join(map(_row_text, rows)))
            rep.finish()
    finally:
        if f is not None:
            f.close()
    return _array(rows, u)


def _stopped(rows: List[List[Any]], finished: int, total: int, path: Optional[str],
             u: Units) -> KeyboardInterrupt:
    where = (" in '%s' (continue with resume=True)" % path) if path else ""
    e = KeyboardInterrupt("whirl: atlas interrupted: %d of %d chunks%s" % (finished, total,
                                                                          where))
    e.partial = _array(rows, u)  # type: ignore[attr-defined]
    return e


def _fail(status: int, mode: int, p_lo: float, hi: float, u: Units) -> None:
    msg = _lib.last_error()
    if status == 11 and "raise the memory bound" in msg:  # GSL_EMAXITER
        msg += " (memory_mb)"
    raise _lib.error(status, "atlas: mode %d, omega %s..%s: %s" % (mode, _num(p_lo), _num(hi),
                                                                     msg))
