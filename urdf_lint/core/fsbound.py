"""The file-system boundary: every read, listing and write of repository data goes through here.

A repository is untrusted (SECURITY.md): its files may be symlinks to anywhere, FIFOs,
devices, or huge. Code outside this module does not ``open``, ``glob``, ``walk`` or parse a
path itself (``tests/test_boundary.py`` walks the AST of ``urdf_lint/`` and ``rules/`` to
keep it so); it calls:

* **reads** -- :func:`read_bytes`, :func:`read_text`, :func:`read_head`, :func:`parse_xml`:
  inside the run's roots after symlinks (when ``roots`` is given), regular files only (opened
  with ``O_NONBLOCK``, then ``fstat`` must say ``S_ISREG``: a FIFO or ``/dev/stdout`` never
  blocks), at most ``max_bytes`` (a clean :class:`BoundaryError` naming the file when over);
* **listings** -- :func:`walk_files`, :func:`list_dir`, :func:`scan_dir`: symlinked folders are
  never entered;
* **writes** -- :func:`write_bytes`, :func:`write_text`, :func:`rewrite`, :func:`temp_path`,
  :func:`remove`: only below an allowed ``base`` (the repository, or a folder the user named
  on the command line), every component from the base down opened with ``O_NOFOLLOW``
  (a symlinked folder anywhere below the base is refused, ``check_no_symlink``), the data
  written to a random name opened ``O_CREAT|O_EXCL|O_NOFOLLOW`` in the target folder and
  renamed over the target (``os.replace``, relative to the folder's descriptor), so a
  committed symlink can neither receive the data nor replace the file. A repository file is
  rewritten only by :func:`rewrite` (format, ``--fix``, generate): resolved before it is
  judged inside, compared with the bytes the caller read right before the rename
  (:class:`ChangedError`), owner, group and mode kept.

:class:`BoundaryError` is an ``OSError``: callers that already handle a failed read or write
keep doing so, with a message that says why.
"""
from __future__ import annotations

import contextlib
import errno
import os
import stat as _st
from typing import IO, TYPE_CHECKING, Any, Callable, Iterable, Iterator, TextIO

if TYPE_CHECKING:  # pragma: no cover
    from pathlib import Path

# a path as the callers hold it (a string or a pathlib.Path)
StrPath = str | os.PathLike[str]
Roots = Iterable[StrPath] | None

MAX_SOURCE_BYTES = 256 << 20   # an XML or YAML source file read in the parent
MAX_CONFIG_BYTES = 4 << 20     # a config file, a baseline's folder's config
MAX_DATA_BYTES = 256 << 20     # a baseline, a report, a memo

_RD = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0)
_NOFOLLOW = getattr(os, "O_NOFOLLOW", 0)
_DIR = os.O_RDONLY | getattr(os, "O_DIRECTORY", 0) | _NOFOLLOW | getattr(os, "O_CLOEXEC", 0)


class BoundaryError(OSError):
    """A read or write the boundary refused (outside the roots, not a regular file, too large,
    a symlinked component); ``str()`` is one sentence naming the path."""

    def __init__(self, path: StrPath, why: str, code: int = errno.EACCES) -> None:
        super().__init__(code, why, os.fspath(path))
        self.why = why

    def __str__(self) -> str:
        return f"{self.filename}: {self.why}"


def inside(f: str, p: str) -> bool:
    """Is path ``f`` the folder ``p`` or below it? (strings, as written: resolve first)"""
    return f == p or f.startswith(p.rstrip(os.sep) + os.sep)


def within(path: StrPath, roots: Iterable[StrPath], resolved: bool = False) -> bool:
    """Does ``path`` resolve (after symlinks) inside one of ``roots``? ``resolved``: the
    caller made ``path`` with ``os.path.realpath`` (only its last component may be a
    symlink since, e.g. a discovered file that is a link): one ``lstat`` instead of one per
    component (discovery asks for every file)."""
    path = os.fspath(path)
    real = os.path.realpath(path) if not resolved or os.path.islink(path) else path
    return any(inside(real, os.fspath(r)) for r in roots)


# -- reads ------------------------------------------------------------------------------------
@contextlib.contextmanager
def _named(path: StrPath) -> Iterator[None]:
    """An error of a read (or write) of ``path`` names it: a read's own names no file (EIO on a
    failing disk), and must not pass for standard output's (:func:`urdf_lint.core.emit.
    stdout_failed`)."""
    try:
        yield
    except OSError as e:
        if e.filename is None:
            e.filename = os.fspath(path)
        raise


def _open_regular(path: StrPath, roots: Roots, nofollow: bool,
                  resolved: bool = False) -> tuple[IO[bytes], os.stat_result]:
    """(a file object of a regular file, its stat); raises BoundaryError / OSError."""
    path = os.fspath(path)
    if roots is not None and not within(path, roots, resolved):
        raise BoundaryError(path, "resolves outside the package roots and the linted "
                            "repository; it was not read")
    fd = os.open(path, _RD | (_NOFOLLOW if nofollow else 0))
    try:
        st = os.fstat(fd)
        if not _st.S_ISREG(st.st_mode):
            raise BoundaryError(path, "is not a regular file (a folder, device, FIFO or "
                                "socket); it was not read",
                                errno.EISDIR if _st.S_ISDIR(st.st_mode) else errno.EACCES)
    except BaseException:
        os.close(fd)
        raise
    return os.fdopen(fd, "rb"), st


@contextlib.contextmanager
def open_regular(path: StrPath, roots: Roots = None,
                 nofollow: bool = False) -> Iterator[tuple[IO[bytes], os.stat_result]]:
    """(a binary file object, its ``fstat``) of a regular file (inside ``roots`` when given),
    opened without blocking; for readers that stream (hashes, meshes in chunks)."""
    f, st = _open_regular(path, roots, nofollow)
    with f, _named(path):
        yield f, st


def read_bytes(path: StrPath, roots: Roots = None, max_bytes: int = MAX_SOURCE_BYTES,
               nofollow: bool = False, resolved: bool = False) -> bytes:
    """The bytes of a regular file of at most ``max_bytes`` (inside ``roots`` after symlinks
    when given; ``resolved`` as for :func:`within`); raises :class:`BoundaryError` (or the
    ``OSError`` of the open). An unsaved editor buffer standing for the file
    (``urdf-lint server``, :mod:`urdf_lint.core.overlay`) is returned instead of its bytes, once
    the path passed the same roots check."""
    from urdf_lint.core import overlay
    buffer = overlay.get(path) if overlay.active() else None
    if buffer is not None:
        if roots is not None and not within(path, roots, resolved):
            raise BoundaryError(path, "resolves outside the package roots and the linted "
                                "repository; it was not read")
        if len(buffer) > max_bytes:
            raise BoundaryError(path, f"is larger than {_size(max_bytes)}; it was not read",
                                errno.EFBIG)
        return buffer
    f, st = _open_regular(path, roots, nofollow, resolved)
    with f, _named(path):
        if st.st_size > max_bytes:
            raise BoundaryError(path, f"is larger than {_size(max_bytes)}; it was not read",
                                errno.EFBIG)
        # the size fstat gave, plus one byte to see a file that grew (read(n) allocates n)
        data = f.read(st.st_size + 1)
        while len(data) <= max_bytes and len(data) > st.st_size:   # it grew: read the rest
            more = f.read(max_bytes + 1 - len(data))
            if not more:
                break
            data += more
    if len(data) > max_bytes:
        raise BoundaryError(path, f"is larger than {_size(max_bytes)}; it was not read",
                            errno.EFBIG)
    return data


def read_head(path: StrPath, n: int, roots: Roots = None, resolved: bool = False) -> bytes:
    """At most the first ``n`` bytes of a regular file (inside ``roots`` when given;
    ``resolved`` as for :func:`within`)."""
    f, _ = _open_regular(path, roots, False, resolved)
    with f, _named(path):
        return f.read(n)


def read_text(path: StrPath, roots: Roots = None, max_bytes: int = MAX_SOURCE_BYTES,
              errors: str = "strict") -> str:
    """:func:`read_bytes` decoded as UTF-8 (``UnicodeDecodeError`` with ``errors='strict'``)."""
    return read_bytes(path, roots, max_bytes).decode("utf-8", errors)


def read_regular(path: StrPath, max_bytes: int, roots: Roots = None,
                 nofollow: bool = False) -> bytes | None:
    """:func:`read_bytes`, or None when it cannot or may not be read."""
    try:
        return read_bytes(path, roots, max_bytes, nofollow)
    except OSError:
        return None


def parse_xml(path: StrPath, parser: Any, roots: Roots = None,
              max_bytes: int = MAX_SOURCE_BYTES, resolved: bool = False) -> Any:
    """The lxml root element of a file read by :func:`read_bytes` (never lxml's own open,
    which would follow a FIFO or a device); lxml's errors are raised as they are."""
    from lxml import etree
    data = read_bytes(path, roots, max_bytes, resolved=resolved)
    return etree.fromstring(data, parser, base_url=xml_base_url(path))


def xml_base_url(path: StrPath) -> str:
    """``path`` as lxml can take it for a document's URL (UTF-8 text): a name that is not
    UTF-8 on disk (a folder named in Latin-1) has its undecodable bytes written ``\\xff``
    (lxml would raise; the URL is only shown)."""
    text = os.fspath(path)
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:
        return os.fsencode(text).decode("utf-8", "backslashreplace")
    return text


def _size(n: int) -> str:
    return f"{n >> 20} MiB" if n >= 1 << 20 else f"{n} bytes"


# -- listings ---------------------------------------------------------------------------------
def scan_dir(path: StrPath) -> list[os.DirEntry[str]]:
    """The ``os.DirEntry`` of a folder, sorted by name; [] when it cannot be listed."""
    try:
        with os.scandir(path) as it:
            return sorted(it, key=lambda e: e.name)
    except OSError:
        return []


def list_dir(path: StrPath) -> list[str]:
    """The names in a folder, in the order the file system gives them (raises OSError)."""
    return os.listdir(path)


def has_entries(path: StrPath) -> bool:
    """Does the folder hold anything? (False when it cannot be listed)"""
    try:
        with os.scandir(path) as it:
            return any(True for _ in it)
    except OSError:
        return False


def walk(top: StrPath, skip: Callable[[str], bool] = lambda d: False
         ) -> Iterator[tuple[str, list[str]]]:
    """(folder, file names) for every folder below ``top``, symlinked folders not entered
    and folders for which ``skip(name)`` is true left out."""
    for dirpath, dirnames, filenames in os.walk(top):
        dirnames[:] = [d for d in dirnames if not skip(d)]
        yield dirpath, filenames


def walk_files(top: StrPath, suffixes: tuple[str, ...] | None = None,
               names: set[str] | None = None, skip: Callable[[str], bool] = lambda d: False,
               folders: list[Any] | None = None) -> Iterator[str]:
    """Every file below ``top`` whose name ends with one of ``suffixes`` or is in ``names``,
    in sorted order; folders for which ``skip(name)`` is true are not entered, nor symlinked
    folders (``os.walk`` does not follow them). Each folder looked into is added to
    ``folders`` when given. A file ``top`` is yielded itself."""
    top = os.fspath(top)
    if os.path.isfile(top):
        yield top
        return
    for dirpath, dirnames, filenames in os.walk(top):
        if folders is not None:
            folders.append(dirpath)
        dirnames[:] = sorted(d for d in dirnames if not skip(d))
        for fn in sorted(filenames):
            if (names and fn in names) or (suffixes and fn.endswith(suffixes)):
                yield os.path.join(dirpath, fn)


def stat_files(top: StrPath, suffix: str) -> list[tuple[str, int, int]]:
    """(path below ``top``, size, mtime in ns) of every file ending with ``suffix`` below
    ``top``, sorted; folders are read with ``scandir``, symlinks not followed."""
    out: list[tuple[str, int, int]] = []
    todo = [os.fspath(top)]
    while todo:
        folder = todo.pop()
        for e in scan_dir(folder):
            if e.is_dir(follow_symlinks=False):
                if e.name != "__pycache__":
                    todo.append(e.path)
            elif e.name.endswith(suffix):
                st = e.stat(follow_symlinks=False)
                out.append((os.path.relpath(e.path, top), st.st_size, st.st_mtime_ns))
    return sorted(out)


MAX_GLOB_ENTRIES = 20_000


def bounded_glob(pattern: str, limit: int = MAX_GLOB_ENTRIES) -> list[str] | None:
    """What ``glob.glob(pattern)`` gives (no ``**`` recursion; names starting with ``.``
    only for a pattern part starting with ``.``), or None when matching it would look at
    more than ``limit`` folder entries or candidate paths: a pattern from a repository
    (``*/*/*/...`` through ``l -> .`` symlinks) can never make the run walk without end."""
    import fnmatch
    import re
    magic = re.compile(r"[*?[]")
    pattern = os.path.normpath(pattern)
    parts = pattern.split(os.sep)
    paths = [os.sep if pattern.startswith(os.sep) else ""]
    if paths[0]:
        parts = parts[1:]
    seen = 0
    for i, part in enumerate(parts):
        last = i == len(parts) - 1
        nxt = []
        if not magic.search(part):
            for p in paths:
                q = os.path.join(p, part) if p else part
                if (os.path.lexists(q) if last else os.path.isdir(q)):
                    nxt.append(q)
        else:
            for p in paths:
                try:
                    names = os.listdir(p or os.curdir)
                except OSError:
                    continue
                seen += len(names)
                if seen > limit:
                    return None
                for n in names:
                    if (n.startswith(".") and not part.startswith(".")) or \
                            not fnmatch.fnmatchcase(n, part):
                        continue
                    q = os.path.join(p, n) if p else n
                    if last or os.path.isdir(q):
                        nxt.append(q)
        if len(nxt) > limit:
            return None
        paths = nxt
    return paths


def glob_paths(root: StrPath, pattern: str) -> "list[Path]":
    """``Path(root).glob(pattern)`` for the user's own install layouts (``*/share``), sorted;
    patterns here are the code's own, never a repository's."""
    from pathlib import Path
    return sorted(Path(root).glob(pattern))


# -- writes -----------------------------------------------------------------------------------
def output_base(path: StrPath, repos: Iterable[StrPath | None]) -> str:
    """The folder a write to ``path`` (named on the command line) is checked from: the
    repository when ``path`` is in it (then no component below the repository may be a
    symlink: a committed ``build -> /elsewhere`` cannot redirect it), else the nearest
    existing folder above it, as the user named it."""
    a = os.path.abspath(path)
    for repo in repos:
        if not repo:
            continue
        for r in dict.fromkeys([os.path.abspath(repo), os.path.realpath(repo)]):
            if inside(a, r):
                return r
    d = os.path.dirname(a)
    while not os.path.isdir(d) and os.path.dirname(d) != d:
        d = os.path.dirname(d)
    return d


def _parts(path: StrPath, base: StrPath) -> tuple[str, list[str]]:
    a, b = os.path.abspath(path), os.path.abspath(base)
    if not inside(a, b) or a == b:
        raise BoundaryError(path, f"is outside {b}, the folder urdf-lint may write to; "
                            "it was not written")
    return b, a[len(b.rstrip(os.sep)) + 1:].split(os.sep)


def _open_dirs(base: str, comps: list[str], make: bool) -> int:
    """A descriptor of the folder ``base/comps...``, every component opened with
    ``O_NOFOLLOW`` (created when ``make``); raises BoundaryError on a symlinked component."""
    fd = os.open(base, _DIR & ~_NOFOLLOW)
    try:
        for i, c in enumerate(comps):
            if c in ("", ".", ".."):
                raise BoundaryError(os.path.join(base, *comps), "has a '.' or '..' component")
            try:
                nfd = os.open(c, _DIR, dir_fd=fd)
            except FileNotFoundError:
                if not make:
                    raise
                with contextlib.suppress(FileExistsError):
                    os.mkdir(c, 0o777, dir_fd=fd)
                nfd = os.open(c, _DIR, dir_fd=fd)
            except OSError as e:
                if e.errno in (errno.ELOOP, errno.ENOTDIR):
                    raise BoundaryError(os.path.join(base, *comps[:i + 1]),
                                        "is a symlink or not a folder; refusing to write "
                                        "through it", errno.ELOOP) from None
                raise
            os.close(fd)
            fd = nfd
    except BaseException:
        os.close(fd)
        raise
    return fd


def _components(path: StrPath, base: StrPath) -> Iterator[tuple[str, os.stat_result]]:
    """(path, lstat) of each existing component of ``path`` below ``base``, down to the
    first missing one."""
    b, comps = _parts(path, base) if os.path.abspath(path) != os.path.abspath(base) \
        else (os.path.abspath(base), [])
    cur = b
    for c in comps:
        cur = os.path.join(cur, c)
        try:
            yield cur, os.lstat(cur)
        except FileNotFoundError:
            return


def first_symlink(path: StrPath, base: StrPath) -> str | None:
    """The first component of ``path`` below ``base`` (the last one included) that is a
    symlink, or None."""
    return next((p for p, st in _components(path, base) if _st.S_ISLNK(st.st_mode)), None)


def check_no_symlink(path: StrPath, base: StrPath) -> None:
    """Raise :class:`BoundaryError` when a component of ``path`` below ``base`` (the last one
    included) is a symlink or not a folder; missing components are fine (they will be made)."""
    for cur, st in _components(path, base):
        if _st.S_ISLNK(st.st_mode) or not _st.S_ISDIR(st.st_mode):
            raise BoundaryError(cur, "is a symlink or not a folder; refusing to write "
                                "through it", errno.ELOOP)


class _Unchecked:
    """The ``old`` of a write that does not compare (a file urdf-lint owns: a report, the
    cache)."""


UNCHECKED = _Unchecked()
# what a compare-and-swap write expects to find: the bytes read, None for "not there"
Old = bytes | None | _Unchecked


class ChangedError(BoundaryError):
    """A rewrite whose file no longer holds the bytes urdf-lint read (someone saved it while
    urdf-lint worked on it): nothing was written, the newer content stays."""

    def __init__(self, path: StrPath) -> None:
        super().__init__(path, "changed while urdf-lint worked on it; it was not written "
                         "(the newer content is kept: run again)", errno.EAGAIN)


def _holds(target: str, old: bytes | None) -> bool:
    """Does ``target`` hold exactly ``old`` now (None: is it absent)? Read without following
    a symlink, without blocking, at most one byte more than ``old``."""
    try:
        fd = os.open(target, _RD | _NOFOLLOW)
    except FileNotFoundError:
        return old is None
    except OSError:
        return False
    with os.fdopen(fd, "rb") as f:
        st = os.fstat(fd)
        if old is None or not _st.S_ISREG(st.st_mode) or st.st_size != len(old):
            return False
        return f.read(len(old) + 1) == old


def _keep_owner(fd: int, keep: os.stat_result) -> None:
    """Give the temp file ``fd`` the owner, group and mode of ``keep`` (the file it replaces):
    root hands another user's file back to that user; a user keeps the group where they may;
    the mode last (a chown clears set-id bits)."""
    now = os.fstat(fd)
    if (now.st_uid, now.st_gid) != (keep.st_uid, keep.st_gid):
        try:
            os.fchown(fd, keep.st_uid, keep.st_gid)
        except OSError:
            with contextlib.suppress(OSError):
                os.fchown(fd, -1, keep.st_gid)
    os.fchmod(fd, _st.S_IMODE(keep.st_mode))


@contextlib.contextmanager
def _temp_in(path: StrPath, base: StrPath, make_dirs: bool, suffix: str = "",
             old: Old = UNCHECKED) -> Iterator[tuple[str, int]]:
    """(temp path, its descriptor) in the target's folder, once every folder from ``base``
    down has been opened without following a symlink; on success the temp is renamed over
    the target (a symlink there is replaced, never followed), else removed. With ``old``
    (bytes, or None for no file) the target is read again right before the rename and must
    still hold it, else :class:`ChangedError` (compare-and-swap: an edit saved meanwhile is
    never lost). Full paths are used after the check, so a worker's audit hook sees what is
    written where."""
    b, comps = _parts(path, base)
    os.close(_open_dirs(b, comps[:-1], make_dirs))
    folder = os.path.join(b, *comps[:-1])
    target = os.path.join(folder, comps[-1])
    tmp = os.path.join(folder, f".{comps[-1][:80]}.{os.urandom(8).hex()}.tmp{suffix}")
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | _NOFOLLOW |
                 getattr(os, "O_CLOEXEC", 0), 0o666)
    try:
        yield tmp, fd
        if not isinstance(old, _Unchecked) and not _holds(target, old):
            raise ChangedError(target)
        os.replace(tmp, target)
    except BaseException as e:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        if isinstance(e, OSError) and e.filename is None:
            e.filename = target     # (a write's error names no file: a full disk names this one)
        raise


def write_bytes(path: StrPath, data: bytes | str, base: StrPath, make_dirs: bool = False,
                mode: int | None = None, old: Old = UNCHECKED,
                keep: os.stat_result | None = None) -> None:
    """Write ``data`` to ``path`` (below ``base``) atomically, through a random temporary
    name opened ``O_CREAT|O_EXCL|O_NOFOLLOW`` beside it; text is written as UTF-8. With
    ``make_dirs``, missing folders below ``base`` are created (never through a symlink).
    ``old``: see :func:`_temp_in`; ``keep``: the stat of the file replaced, whose owner,
    group and mode the new file gets."""
    if isinstance(data, str):
        data = data.encode("utf-8")
    with _temp_in(path, base, make_dirs, old=old) as (_, fd):
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            if keep is not None:
                _keep_owner(f.fileno(), keep)
            if mode is not None:
                os.fchmod(f.fileno(), mode)


def write_text(path: StrPath, text: str, base: StrPath, make_dirs: bool = False) -> None:
    write_bytes(path, text.encode("utf-8"), base, make_dirs)


@contextlib.contextmanager
def open_write(path: StrPath, base: StrPath, make_dirs: bool = False) -> Iterator[TextIO]:
    """A text stream whose content appears at ``path`` only when the block succeeds."""
    import io
    with _temp_in(path, base, make_dirs) as (_, fd):
        with io.open(fd, "w", encoding="utf-8") as f:
            yield f


@contextlib.contextmanager
def temp_path(path: StrPath, base: StrPath, suffix: str = "",
              make_dirs: bool = False) -> Iterator[str]:
    """A path to a new, empty, unpredictably named file beside ``path`` (created exclusively,
    so no committed symlink can stand in for it) for writers that want a file name (Pillow,
    rerun); on success it replaces ``path``, on an exception it is removed."""
    with _temp_in(path, base, make_dirs, suffix) as (tmp, fd):
        os.close(fd)
        yield tmp


def named_root(path: StrPath, repo: StrPath | None) -> str | None:
    """The real path a path the user named stands for when urdf-lint rewrites files below it:
    the path resolved after symlinks; None when it is a symlink, or is in the repository
    ``repo`` as written, and resolves outside the repository (a committed ``robot.xacro ->
    ~/.bashrc`` handed over by a hook or a shell glob). ``repo`` None: resolved as it is."""
    a = os.path.normpath(os.path.abspath(path))
    real = os.path.realpath(a)
    if repo is None:
        return real
    r = os.path.normpath(os.path.abspath(repo))
    rr = os.path.realpath(r)
    if (os.path.islink(a) or inside(a, r) or inside(a, rr)) and not inside(real, rr):
        return None
    return real


def write_roots(paths: Iterable[StrPath], repo: StrPath | None) -> list[str]:
    """The real paths of the named ``paths`` (:func:`named_root`) that a rewrite may land
    below; those that resolve outside the repository are left out."""
    roots = (named_root(p, repo) for p in paths)
    return list(dict.fromkeys(r for r in roots if r is not None))


def rewrite(path: StrPath, data: bytes, bases: Iterable[StrPath], old: Old,
            repo: StrPath | None = None, make_dirs: bool = False) -> None:
    """The one rewrite of a repository file (``format``, ``check --fix``,
    ``--add-suppressions``, ``generate``): the path is resolved first, then must lie inside
    one of the ``bases`` the user named (:func:`write_roots`: a named symlink whose target is
    outside the repository ``repo`` counts for nothing), so a symlink is followed (the link
    stays a link, its target gets the bytes) only to a target inside them. ``old`` is what
    the caller read (None: there was no file): the file must still hold it right before the
    rename, else :class:`ChangedError` and nothing is written. The file keeps its owner,
    group (where the user may set them: root always) and mode."""
    real = os.path.realpath(path)
    for rb in write_roots(bases, repo):
        base = rb if os.path.isdir(rb) else os.path.dirname(rb)
        if inside(real, rb) and real != base:
            try:
                keep: os.stat_result | None = os.stat(real)
            except OSError:
                keep = None
            if keep is not None and not _st.S_ISREG(keep.st_mode):
                raise BoundaryError(path, "is not a regular file; it was not written")
            write_bytes(real, data, base, make_dirs, old=old, keep=keep)
            return
    raise BoundaryError(path, "resolves outside the paths named on the command line or the "
                        "repository (a symlink?); it was not written")


def null_onto(fd: int, write: bool) -> None:
    """Point descriptor ``fd`` at the null device (``os.devnull``): a worker's stdin, so that
    it never reads the parent's, or standard output whose reader has gone (nothing from a
    repository is opened)."""
    null = os.open(os.devnull, os.O_WRONLY if write else os.O_RDONLY)
    try:
        if null != fd:
            os.dup2(null, fd)
    finally:
        if null != fd:
            os.close(null)


def remove(path: StrPath, base: StrPath) -> bool:
    """Remove the regular file ``path`` below ``base`` (no component a symlink); False when it
    is not there or is not a regular file."""
    try:
        b, comps = _parts(path, base)
        os.close(_open_dirs(b, comps[:-1], False))
        target = os.path.join(b, *comps)
        if not _st.S_ISREG(os.lstat(target).st_mode):
            return False
        os.unlink(target)
        return True
    except OSError:
        return False


def make_own_dirs(path: StrPath) -> None:
    """Create a folder urdf-lint itself chose or the user named and the CLI checked (a
    temporary folder, the cache, ``--out`` after :func:`check_no_symlink`), with parents."""
    os.makedirs(path, exist_ok=True)


def remove_tree(path: StrPath) -> None:
    """Remove a folder urdf-lint made (the cache: ``urdf-lint clean``); symlinks inside are
    removed, never followed (``shutil.rmtree``'s descriptor-based walk)."""
    import shutil
    shutil.rmtree(path, ignore_errors=True)


def make_dirs(path: StrPath, base: StrPath) -> None:
    """Create ``path`` and its missing parents below ``base``, never through a symlink."""
    b, comps = _parts(path, base)
    os.close(_open_dirs(b, comps, True))
