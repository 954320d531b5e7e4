"""The one way the project's Python scripts write a file (issue 45; docs/RELIABILITY.md, "Scripts").

replace_file(path, data) writes `data` into a fresh file beside `path` (mkstemp: O_CREAT|O_EXCL,
never an existing name, never through a link), gives it the mode of the file it replaces (a new
file: 0666 less the umask, as the shell would), then renames it over `path` in one step. So:
  - a planted link or other non-plain file at `path` is refused up front (Refused), and one planted
    after that check is replaced by the rename, never written through;
  - a reader sees the old file or the new one, never half of one;
  - the file keeps its permissions (a doc is not turned into mode 0600).
A symbolic link at `path` is refused, not followed: write its target by name if that is meant.

check_replaceable(path) makes the same checks without writing, so a script can refuse before it
does any work. Used by scripts/bench-report and scripts/results-tables (imported from scripts/lib;
the device kit carries this file in tools/lib beside tools/bench-report).
"""
import os
import stat
import tempfile


class Refused(Exception):
    """A file the script will not write, with the reason in the message."""


def check_replaceable(path):
    """The os.stat_result of the plain file at `path`, None when there is none; Refused otherwise."""
    try:
        st = os.lstat(path)
    except FileNotFoundError:
        return None
    if stat.S_ISLNK(st.st_mode):
        raise Refused(f"{path} is a symbolic link: not written through (remove it, or name its target)")
    if not stat.S_ISREG(st.st_mode):
        raise Refused(f"{path} exists and is not a plain file: not replaced")
    return st


def read_head(path, size=4096):
    """The first `size` bytes of the plain file at `path` (no link followed, never blocks on a FIFO)."""
    fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            raise Refused(f"{path} is not a plain file: not read")
        return os.read(fd, size)
    finally:
        os.close(fd)


def _umask():
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def fresh_name_beside(path):
    """A new empty file of our own beside `path` (mkstemp: O_EXCL), for a program that writes by
    name (gnuplot's `set output`); rename_over() then puts it in place. Refused as check_replaceable."""
    check_replaceable(path)
    folder, name = os.path.split(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(dir=folder, prefix=f".{name}.", suffix=".tmp")
    os.close(fd)
    return tmp


def rename_over(tmp, path, mode=None):
    """Renames our file `tmp` over `path` in one step (a link at `path` is replaced, never followed).
    mode: as for replace_file."""
    try:
        st = check_replaceable(path)
        if mode is None:
            mode = stat.S_IMODE(st.st_mode) if st is not None else 0o666 & ~_umask()
        os.chmod(tmp, mode)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise


def replace_file(path, data, mode=None):
    """Writes `data` (str: UTF-8, or bytes) as `path` by a fresh file renamed over it (see above).
    mode: the new file's permissions; default: those of the file replaced, else 0666 & ~umask."""
    if isinstance(data, str):
        data = data.encode("utf-8")
    check_replaceable(path)
    folder, name = os.path.split(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(dir=folder, prefix=f".{name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
    except BaseException:
        os.unlink(tmp)
        raise
    rename_over(tmp, path, mode)
