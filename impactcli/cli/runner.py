"""How a command ends: exit status, one line on stderr, nothing left behind.

:func:`run` calls the Typer app inside an :func:`impactcli.output.output_transaction` (all
the files of a run are committed together, or none) and maps every way a run can end to an
exit status:

- 0: success; also stdout closed by its reader (``impact tables | head -1``).
- 2: bad input or an output that cannot be written, as one line ``impact: error: ...``
  (usage errors as ``impact CMD: error: ...``). A NumPy RuntimeWarning (overflow, invalid
  value) never reaches stderr: the run fails with one line naming it, its files are not
  written.
- 128 + signal number: SIGINT (130), SIGTERM (143), SIGHUP (129). Each raises
  :class:`Terminated` in the main thread, so the temporary output files are removed exactly
  as for Ctrl-C; the child processes the run started (Dask ``--scheduler processes``
  workers, a LocalCluster's nannies and workers) are terminated at once, and any still
  alive at the end are killed. The cleanup has :data:`CLEANUP_SECONDS`: past them the
  process kills what is left below it and exits with the same status, whatever a
  library's threads still wait for.
"""

from __future__ import annotations

import contextlib
import errno
import os
import signal
import sys
import warnings
from collections.abc import Callable, Iterator
from functools import partial

from impactcli import output
from impactcli.errors import InputError, StdoutClosed
from impactcli.output import describe_os_error, output_transaction

#: Signals that end a run as Ctrl-C does, with exit status 128 + the signal number.
HANDLED_SIGNALS: tuple[str, ...] = ("SIGINT", "SIGTERM", "SIGHUP")


class Terminated(BaseException):
    """A run stopped by a signal (not an Exception: nothing may swallow it)."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


_stopping = False
#: The signal that stopped the run (None: none): whatever exception its cleanup ends with
#: (a BrokenPipeError of a worker's pipe, say), the run exits with that signal's status.
_signalled: int | None = None

#: Seconds a run stopped by a signal has to clean up and exit (remove its temporary files,
#: end its worker processes and threads); past them it exits at once with the status of
#: the signal (:func:`_exit_by_deadline`).
CLEANUP_SECONDS = 20.0


def _on_signal(signum: int, frame) -> None:  # noqa: ARG001 (the handler's signature)
    global _stopping, _signalled
    if _stopping:  # a second signal during the cleanup: let the cleanup finish
        return
    _stopping, _signalled = True, signum
    _exit_by_deadline(CLEANUP_SECONDS, 128 + signum)
    end_children(kill=False)  # workers stop now, not when their tasks finish
    raise Terminated(signum)


def _exit_by_deadline(seconds: float, status: int) -> None:
    """In ``seconds``, unless the process has ended: kill every process below this one and
    exit with ``status`` at once (``os._exit``: no thread is waited for). A run stopped by a
    signal thus ends even if a library waits for ever at its cleanup or at the
    interpreter's exit (e.g. for the manager thread of a process pool whose worker was
    killed while sending a result)."""
    import threading

    def stop() -> None:
        with contextlib.suppress(Exception):
            sys.stderr.flush()
        end_children(kill=True)
        os._exit(status)

    timer = threading.Timer(seconds, stop)
    timer.daemon = True
    timer.start()


@contextlib.contextmanager
def signal_handlers() -> Iterator[None]:
    """SIGINT, SIGTERM and SIGHUP raise :class:`Terminated` in the main thread (no-op in
    another thread); the previous handlers are restored at the end."""
    global _stopping, _signalled
    _stopping, _signalled = False, None
    previous = {}
    for name in HANDLED_SIGNALS:
        number = getattr(signal, name, None)
        if number is None:
            continue
        with contextlib.suppress(ValueError, OSError):  # not the main thread
            previous[number] = signal.signal(number, _on_signal)
    try:
        yield
    finally:
        for number, handler in previous.items():
            with contextlib.suppress(ValueError, OSError, TypeError):
                signal.signal(number, handler)


def _descendants(pid: int) -> list[int]:
    """Process ids under ``pid`` (children, grandchildren...), from /proc (Linux); empty
    where /proc is missing."""
    parents: dict[int, list[int]] = {}
    try:
        entries = os.listdir("/proc")
    except OSError:
        return []
    for entry in entries:
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat", "rb") as handle:
                fields = handle.read().rsplit(b")", 1)[1].split()
        except (OSError, IndexError):
            continue
        parents.setdefault(int(fields[1]), []).append(int(entry))
    found, todo = [], [pid]
    while todo:
        for child in parents.get(todo.pop(), []):
            found.append(child)
            todo.append(child)
    return found


def end_children(kill: bool = True) -> None:
    """``kill=False``: terminate (SIGTERM) the worker processes this one started with
    multiprocessing (Dask's process pool, a LocalCluster's nannies), so the run's cleanup
    does not wait for their tasks. ``kill=True``: also kill (SIGKILL) every process left
    below this one (grandchildren, multiprocessing's resource tracker), once the cleanup
    is done."""
    import multiprocessing

    managed: set[int] = set()
    with contextlib.suppress(Exception):
        for child in multiprocessing.active_children():
            managed.add(child.pid)
            with contextlib.suppress(Exception):
                child.kill() if kill else child.terminate()
    if kill:
        killed = []
        for pid in _descendants(os.getpid()):
            with contextlib.suppress(OSError):
                os.kill(pid, signal.SIGKILL)
                killed.append(pid)
        # reap the killed children no multiprocessing.Process owns (its resource tracker),
        # so that none stays defunct; the others are reaped by multiprocessing
        _reap([pid for pid in killed if pid not in managed], seconds=1.0)


def _reap(pids: list[int], seconds: float) -> None:
    """Wait (at most ``seconds``) for those of ``pids`` that are children of this process
    to end, and collect their exit status."""
    import time

    pending, deadline = set(pids), time.monotonic() + seconds
    while pending:
        for pid in list(pending):
            try:
                if os.waitpid(pid, os.WNOHANG)[0]:
                    pending.discard(pid)
            except OSError:  # not a child of this process, or already collected
                pending.discard(pid)
        if not pending or time.monotonic() > deadline:
            return
        time.sleep(0.01)


class _ClosedStdout:
    """sys.stdout when file descriptor 1 was closed (``impact tables >&-``): writing to
    it fails like writing to a closed descriptor."""

    encoding = "utf-8"
    errors = "strict"

    def write(self, data) -> int:
        raise OSError(errno.EBADF, "stdout is closed")

    def flush(self) -> None:
        pass

    def isatty(self) -> bool:
        return False

    def fileno(self) -> int:
        raise OSError(errno.EBADF, "stdout is closed")

    @property
    def buffer(self) -> _ClosedStdout:
        return self


def _guard_stdio() -> None:
    """Descriptors 0-2 closed at start are held on /dev/null (so no file the run opens
    takes their number); a closed stdout fails on the first write, a closed stderr is
    silent."""
    for fd in (0, 1, 2):
        try:
            os.fstat(fd)
        except OSError:
            with contextlib.suppress(OSError):
                held = os.open(os.devnull, os.O_RDWR)
                if held != fd:
                    os.dup2(held, fd)
                    os.close(held)
    if sys.stdout is None:
        sys.stdout = _ClosedStdout()  # type: ignore[assignment]
    if sys.stderr is None:
        sys.stderr = open(os.devnull, "w")  # noqa: SIM115 (for the life of the process)


def _quiet_stdout() -> None:
    """Point descriptor 1 at /dev/null so the interpreter's final flush of stdout cannot
    fail again (a closed pipe, a full disk)."""
    with contextlib.suppress(OSError, ValueError, AttributeError):
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)


def _error(message: str) -> None:
    with contextlib.suppress(Exception):
        print(" ".join(str(message).split()), file=sys.stderr)


def _refuse_numeric_warnings(caught: list[warnings.WarningMessage]) -> None:
    """A NumPy RuntimeWarning (overflow, division by zero, invalid value) means some input
    is outside the range the model can compute: the run fails with one line (before its
    files are committed) instead of writing infinities or NaN."""
    numeric = [w for w in caught if _is_numeric(w)]
    if numeric:
        raise InputError(
            f"the computation failed ({' '.join(str(numeric[0].message).split())}): an input "
            "is too large or too small for the model; check the values and their units"
        )


def run(call: Callable[[], object], usage_error: Callable[[BaseException], int | None]) -> int:
    """Run ``call`` (the Typer app) and return the exit status; print the one error line.

    ``usage_error`` handles the Typer/Click exceptions (it prints and returns a status, or
    returns None for an exception it does not know).
    """
    from impactcli.cli import common

    _guard_stdio()
    status = 0
    common.pending_messages = []
    caught: list[warnings.WarningMessage] = []
    try:
        with signal_handlers():
            try:
                with warnings.catch_warnings(record=True) as caught:
                    warnings.simplefilter("always", RuntimeWarning)
                    output.before_stdout = partial(_refuse_numeric_warnings, caught)
                    with output_transaction():
                        result = call()
                        _flush_stdout()
                        _refuse_numeric_warnings(caught)
                status = result if isinstance(result, int) else 0
                for line in common.pending_messages:
                    _error(line)
                for item in caught:
                    if not _is_numeric(item):
                        warnings.showwarning(
                            item.message, item.category, item.filename, item.lineno
                        )
            except Terminated as exc:
                status = 128 + exc.signum
                end_children(kill=True)
            except KeyboardInterrupt:
                status = 128 + signal.SIGINT
                end_children(kill=True)
            except (BrokenPipeError, StdoutClosed):
                # stdout's reader stopped reading (e.g. head): not an error.
                _quiet_stdout()
                status = 0
            except InputError as exc:
                _error(f"impact: error: {exc}")
                status = 2
            except UnicodeEncodeError as exc:
                encoding = getattr(sys.stdout, "encoding", None) or exc.encoding
                _error(
                    f"impact: error: cannot write {exc.object[exc.start : exc.end]!r} in the "
                    f"output encoding {encoding}: use -f csv or json, or set "
                    "PYTHONIOENCODING=utf-8"
                )
                status = 2
            except OSError as exc:
                where = f" {exc.filename!r}" if exc.filename else ""
                _error(f"impact: error: cannot write or read{where}: {describe_os_error(exc)}")
                status = 2
            except SystemExit as exc:
                if exc.code == 1 and _click_saw_broken_pipe():
                    _quiet_stdout()
                    status = 0
                else:
                    raise
            except Exception as exc:
                handled = usage_error(exc)
                if handled is None and _signalled is None:
                    raise
                status = 2 if handled is None else handled
    except Terminated as exc:  # a signal between the handlers' install and the try
        status = 128 + exc.signum
        end_children(kill=True)
    finally:
        common.pending_messages = None
        output.before_stdout = None
    if _signalled is not None:  # stopped by a signal, whatever its cleanup raised
        status = 128 + _signalled
        end_children(kill=True)
    if status != 0:
        _quiet_stdout_if_broken()
    return status


def _is_numeric(item: warnings.WarningMessage) -> bool:
    return issubclass(item.category, RuntimeWarning)


def _flush_stdout() -> None:
    """Flush stdout inside the run, so a closed pipe or a full disk is reported here and
    not by the interpreter at exit."""
    try:
        sys.stdout.flush()
    except BrokenPipeError:
        raise StdoutClosed() from None
    except OSError as exc:
        raise InputError(f"cannot write to stdout: {describe_os_error(exc)}") from None


def _quiet_stdout_if_broken() -> None:
    """After a failed run, drop what stdout still buffers if it cannot be written."""
    try:
        sys.stdout.flush()
    except (OSError, ValueError):
        _quiet_stdout()


def _click_saw_broken_pipe() -> bool:
    """Click ends a run whose stdout pipe closed with exit status 1, after wrapping stdout
    in its PacifyFlushWrapper."""
    return type(sys.stdout).__name__ == "PacifyFlushWrapper"
