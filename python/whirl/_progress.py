"""The progress of whirl's long calls (their ``progress=`` argument).

progress=None or False: nothing. A callable: called as progress(done, total) with numbers that
never decrease, done <= total, the last call (total, total) when the call completes (not after a
failure or Ctrl-C); what done and total count is each call's (chunks, points, modes, time).
progress=True: a bar of tqdm (tqdm.auto: a widget in a notebook) where tqdm is importable, else a
line on standard error rewritten at most 5 times a second.

A callable may be called from a thread of the library's (the points of a stability map are
shared over OpenMP threads), one call at a time; an exception it raises stops the call, which
then raises that exception. Ctrl-C during a call goes to the library's stop request (see
_lib.interruptible), never into the callable's code: a callable cannot lose a Ctrl-C or turn
it into a bare KeyboardInterrupt."""
import sys
import time
from typing import Any, Callable, Optional

from ._lib import lib

_TEXT_EVERY = 0.2  # seconds between two rewrites of the text line


class _Text:
    """The text line on standard error: "whirl: WHAT: DONE/TOTAL UNIT (P%)"."""

    def __init__(self, what: str, unit: str) -> None:
        self.what, self.unit = what, unit
        self.shown = -1.0
        self.width = 0

    def __call__(self, done: float, total: float) -> None:
        now = time.monotonic()
        if done < total and now - self.shown < _TEXT_EVERY:
            return
        self.shown = now
        number = ("%d/%d" if isinstance(total, int) else "%.4g/%.4g") % (done, total)
        text = "whirl: %s: %s%s (%.0f%%)" % (self.what, number, " " + self.unit if self.unit
                                             else "", 100.0 * done / total if total else 100.0)
        sys.stderr.write("\r" + text.ljust(self.width))
        self.width = len(text)
        sys.stderr.flush()

    def close(self) -> None:
        if self.width:
            sys.stderr.write("\n")
            sys.stderr.flush()


class _Bar:
    """A tqdm bar."""

    def __init__(self, tqdm: Any, what: str, total: float, unit: str) -> None:
        self.bar = tqdm(total=total, desc="whirl: " + what, unit=" " + unit if unit else "it",
                        leave=True)
        self.at = 0.0

    def __call__(self, done: float, total: float) -> None:
        self.bar.update(done - self.at)
        self.at = done

    def close(self) -> None:
        self.bar.close()


def _tqdm() -> Optional[Any]:
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return None
    return tqdm


class Report:
    """One call's progress: update(done) from Python, c_update(done) from a library callback
    (an exception of the callable kept, and the library asked to stop, for reraise() after the
    library's call); finish() at completion; close() always."""

    def __init__(self, fn: Callable[[float, float], Any], total: float,
                 display: Any = None) -> None:
        self.fn = fn
        self.total = total
        self.done: float = -1
        self.display = display
        self.error: Optional[BaseException] = None

    def update(self, done: float) -> None:
        done = min(max(done, 0), self.total)
        if done <= self.done:
            return
        self.done = done
        self.fn(done, self.total)

    def set_total(self, total: float) -> None:
        """The total, once the call knows it (before the first update)."""
        if self.done < 0 and total > 0 and total != self.total:
            self.total = total
            if isinstance(self.display, _Bar):
                self.display.bar.total = total

    def c_update(self, done: float) -> None:
        if self.error is not None:
            return
        try:
            self.update(done)
        except BaseException as e:  # noqa: B036 - kept, raised on the caller's thread
            self.error = e
            lib.whirl_stop_request()

    def reraise(self) -> None:
        """Raises the callable's exception from a library callback (the stop it requested
        cleared)."""
        if self.error is not None:
            lib.whirl_stop_clear()
            e, self.error = self.error, None
            raise e

    def finish(self) -> None:
        self.reraise()
        self.update(self.total)

    def close(self) -> None:
        if self.display is not None:
            self.display.close()
            self.display = None

    def __enter__(self) -> "Report":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()


class _Nothing(Report):
    """No progress asked for: every method does nothing."""

    def __init__(self) -> None:
        super().__init__(lambda done, total: None, 1.0)

    def update(self, done: float) -> None:
        pass

    def finish(self) -> None:
        pass


def report(progress: Any, what: str, total: float, unit: str = "") -> Report:
    """The Report of a call named ``what`` for its argument ``progress`` (None, False, True or
    a callable) over ``total`` units named ``unit``. TypeError for anything else."""
    if progress is None or progress is False:
        return _Nothing()
    total = total if total > 0 else 1
    if progress is True:
        tqdm = _tqdm()
        display: Any = _Bar(tqdm, what, total, unit) if tqdm else _Text(what, unit)
        return Report(display, total, display)
    if callable(progress):
        return Report(progress, total)
    raise TypeError("progress must be None, True, False or a callable (done, total), got %r"
                    % (progress,))


def active(progress: Any) -> bool:
    """progress asks for a report (not None or False)."""
    return progress is not None and progress is not False
