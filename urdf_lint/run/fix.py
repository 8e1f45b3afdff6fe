"""``urdf-lint check --fix``: apply the fixes of a run, verify them, roll back the wrong ones.

1. Lint every model, keeping each expanded robot.
2. Take the applicable fixes (safe ones; unsafe ones too with ``--unsafe-fixes``); two fixes that
   edit overlapping bytes: the first one wins, the other waits for the next run.
3. Write the edited sources (atomically) and lint again in the same run. A fix is rolled back
   (and reported) when its finding is still there, when a finding appears that was not there
   before in a model whose files it edited, or when the expanded robot of a model it touches is
   not exactly the robot before with the fix's attribute values applied: this is what makes a
   fix right "for every model and arg set that uses that source line" (a macro line or property
   shared by a model without the finding changes that model, so the fix is refused).
4. Repeat with the remaining fixes until the run verifies (at most a few rounds).
"""
from __future__ import annotations

import difflib
import os
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, Callable

from lxml import etree

from urdf_lint.core import fsbound
from urdf_lint.fix.kinds import expectation
from urdf_lint.fix.kinds.add_dollar import ANY
from urdf_lint.fix.sourceedit import apply_edits, line_offset

if TYPE_CHECKING:  # pragma: no cover
    from collections.abc import Iterable, Sequence

    from urdf_lint.config.schema import Config
    from urdf_lint.core.edits import Edit, Fix
    from urdf_lint.core.findings import Problem
    from urdf_lint.core.jobs import ModelReport
    from urdf_lint.discovery.packages import PackageResolver
    from urdf_lint.fix.memo import FixMemo
    from urdf_lint.run.pipeline import CheckResult

    FKey = tuple[str, str, int, int, str]       # a finding's identity (_fkey)
    LineMaps = dict[str, Callable[[int], int]]  # file -> new line -> old line (line_maps)
    Snapshot = dict[str, tuple[ModelReport, Any]]   # label -> (report, robot tree) (_snapshot)

MAX_ROUNDS = 4


@dataclass
class FixOutcome:
    """What ``--fix`` did: the fixes written, those rolled back or refused, and the run after."""
    result: "CheckResult"                            # the CheckResult after fixing
    applied: list[Problem] = field(default_factory=list)   # Problems whose fix was written
    rolled_back: list[tuple[Problem, str]] = field(default_factory=list)  # (Problem, reason)
    changed_files: list[str] = field(default_factory=list)
    diff: str = ""
    refused: list[tuple[Problem, str]] = field(default_factory=list)  # never written


def _fkey(p: "Problem") -> "FKey":
    return (p.code, p.file, p.line, p.col, p.message)


def _fix(p: "Problem") -> "Fix":
    assert p.fix is not None   # (only findings with a fix get here: candidates())
    return p.fix


def _lkey(p: "Problem", line_maps: "LineMaps | None" = None) -> tuple[str, str, int, str]:
    """A finding's identity across an edit: code, file, line (in the numbering before the
    edits, through ``line_maps``) and message (columns move when a line is edited)."""
    m = (line_maps or {}).get(p.file)
    return (p.code, p.file, m(p.line) if m else p.line, p.message)


def line_maps(fixed: "Iterable[Problem]", originals: dict[str, bytes]) -> "LineMaps":
    """{file: new line -> old line} for the edits of ``fixed``: the old line of the first byte
    of the new line (a line made by an edit maps to where the edit starts)."""
    out: LineMaps = {}
    for f, edits in _edits_by_file(fixed).items():
        old = originals[f]
        new = apply_edits(old, edits)
        spans: list[tuple[int, int, int, int]] = []   # (new start, new end, old start, old end) of each edit
        shift = 0
        for e in sorted(edits, key=lambda e: (e.start, e.end)):
            n = len(e.text.encode("utf-8"))
            spans.append((e.start + shift, e.start + shift + n, e.start, e.end))
            shift += n - (e.end - e.start)

        def back(line: int, old: bytes = old, new: bytes = new,
                 spans: list[tuple[int, int, int, int]] = spans) -> int:
            x = line_offset(new, line)
            if x is None:
                return line
            total = 0
            for ns, ne, os_, oe in spans:
                if x < ns:
                    break
                if x < ne:            # inside an edit's new text: where the edit starts
                    return old.count(b"\n", 0, os_) + 1
                total += (ne - ns) - (oe - os_)
            o = x - total
            return old.count(b"\n", 0, o) + 1
        out[f] = back
    return out


def candidates(findings: "Iterable[Problem]", unsafe: bool
               ) -> "tuple[list[Problem], list[Problem], list[tuple[Problem, str]]]":
    """(chosen, deferred, refused): applicable fixes without overlapping edits, in finding
    order; a fix that overlaps an earlier one waits for the next run (deferred), and two fixes
    that want different text on the same bytes (one macro line, several models or instances
    that need different values) are both refused, with the reason; so is a fix the run's
    scope took back (a file outside the linted paths, a generated URDF: fix.scope)."""
    from urdf_lint.core.locations import display_path
    from urdf_lint.fix.scope import scope_refusal
    chosen: list[Problem] = []
    deferred: list[Problem] = []
    refused: list[tuple[Problem, str]] = []
    # file -> [(start, end, text, finding)]
    taken: dict[str, list[tuple[int, int, str, Problem]]] = {}
    for p in findings:
        fx = p.fix
        if fx is None or (not fx.safe and not unsafe):
            continue
        if not fx.applicable:
            why = scope_refusal(fx)
            if why:
                refused.append((p, why))
            continue
        clash, rival = False, None
        for e in fx.edits:
            for (s, t, text, q) in taken.get(e.file, ()):
                if s == e.start and t == e.end:
                    if text != e.text:
                        rival = (q, e, text)
                elif e.start < t and s < e.end:
                    clash = True
        if rival is not None:
            q, e, text = rival
            line = e.file and f"{display_path(e.file)}"
            reason = (f"the models or macro calls that use {line} need different values there "
                      f"({text!r} for {', '.join(q.models) or 'one'}, {e.text!r} for "
                      f"{', '.join(p.models) or 'another'})")
            refused.append((p, reason))
            if q in chosen:
                chosen.remove(q)
                refused.append((q, reason))
            continue
        if clash:
            deferred.append(p)
            continue
        for e in fx.edits:
            taken.setdefault(e.file, []).append((e.start, e.end, e.text, p))
        chosen.append(p)
    return chosen, deferred, refused


def _edits_by_file(fixed: "Iterable[Problem]") -> "dict[str, set[Edit]]":
    """{file: {Edit}} of the fixes of ``fixed`` (an edit two findings share, once)."""
    per_file: dict[str, set[Edit]] = {}
    for p in fixed:
        for e in _fix(p).edits:
            per_file.setdefault(e.file, set()).add(e)
    return per_file


def edited_sources(fixed: "Iterable[Problem]", originals: dict[str, bytes]) -> dict[str, bytes]:
    """{file: new bytes} for the fixes of ``fixed`` (each edit once)."""
    out = {}
    for f, edits in _edits_by_file(fixed).items():
        if f not in originals:
            originals[f] = fsbound.read_bytes(f)
        out[f] = apply_edits(originals[f], edits)
    return out


def unified_diff(new: dict[str, bytes], originals: dict[str, bytes]) -> str:
    from urdf_lint.core.locations import display_path
    from urdf_lint.core.escape import escape_text
    out: list[str] = []
    for f in sorted(new):
        if new[f] == originals[f]:
            continue
        a = originals[f].decode("utf-8", "replace").splitlines(keepends=True)
        b = new[f].decode("utf-8", "replace").splitlines(keepends=True)
        name = escape_text(display_path(f))   # one line: no name adds a line to the patch
        out.extend(difflib.unified_diff(a, b, f"a/{name}", f"b/{name}"))
    return "".join(x if x.endswith("\n") else x + "\n\\ No newline at end of file\n"
                   for x in out)


# -- verification --------------------------------------------------------------------------------
def _tree(report: "ModelReport", xml_or_none: str | None) -> Any:
    if report.kept_model is None:
        return None
    xml = report.kept_model.xml if xml_or_none is None else xml_or_none
    parser = etree.XMLParser(remove_blank_text=True, resolve_entities=False, no_network=True,
                             load_dtd=False, remove_comments=True)
    try:
        if xml is None:
            return etree.fromstring(fsbound.read_bytes(report.entry), parser)
        return etree.fromstring(xml.encode("utf-8"), parser)
    except (OSError, etree.XMLSyntaxError):
        return None




def _values_equal(a: str | None, b: str | None) -> bool:
    if a == b or a == ANY:
        return True
    if a is None or b is None:
        return False
    x, y = a.split(), b.split()
    try:
        return len(x) == len(y) and all(abs(float(p) - float(q)) <= 1e-9 * max(1, abs(float(p)))
                                        for p, q in zip(x, y, strict=True))
    except ValueError:
        return False


def _same_robot(a: Any, b: Any) -> bool:
    ea = list(a.iter(tag=etree.Element))
    eb = list(b.iter(tag=etree.Element))
    if len(ea) != len(eb):
        return False
    for x, y in zip(ea, eb, strict=True):
        if x.tag != y.tag or set(x.attrib) != set(y.attrib):
            return False
        if (x.text or "").strip() != (y.text or "").strip():
            return False
        if not all(_values_equal(x.get(k), y.get(k)) for k in x.attrib):
            return False
    return True


def _snapshot(result: "CheckResult") -> Snapshot:
    """{label: (report, tree)} of the models of a run, with their robots parsed now (a plain
    .urdf is read from disk, so this runs before anything is written)."""
    return {r.label: (r, _tree(r, None)) for r in result.models}


def verify(before: Snapshot, before_findings: "Iterable[Problem]", after: "CheckResult",
           fixed: "Sequence[Problem]", maps: "LineMaps | None" = None) -> "dict[FKey, str]":
    """{finding key: reason} for the fixes of ``fixed`` that must be rolled back (``maps``:
    :func:`line_maps` of the edits, to compare findings on lines that moved)."""
    from urdf_lint.core.locations import display_path
    bad: dict[FKey, str] = {}
    fixed_keys = {_fkey(p): p for p in fixed}

    def touches(p: "Problem", report: "ModelReport") -> bool:
        deps = {os.path.realpath(d) for d in report.deps}
        return any(os.path.realpath(e.file) in deps for e in _fix(p).edits)

    # 1. the finding must be gone
    after_keys = {_lkey(f, maps) for f in after.findings}
    for k, p in fixed_keys.items():
        if _lkey(p) in after_keys:
            bad[k] = "the fix did not remove its finding"
    # 2. no finding may appear
    before_keys = {_lkey(f) for f in before_findings}
    after_models = {r.label: r for r in after.models}
    for f in after.findings:
        if _lkey(f, maps) in before_keys:
            continue
        where = f"{display_path(f.file)}:{f.line}"
        for label in f.models or tuple(before):
            rep = before.get(label, (None,))[0]
            for k, p in fixed_keys.items():
                if k not in bad and (rep is None or touches(p, rep)):
                    bad[k] = f"the fix adds {f.code} at {where} ({f.message})"
    # 3. every model's robot is exactly the old one with the fixes' values
    for label, (rep, tree) in before.items():
        arep = after_models.get(label)
        mine = [p for p in fixed if touches(p, rep)]
        if not mine:
            continue
        if arep is None or tree is None:
            for p in mine:
                bad.setdefault(_fkey(p), f"{label} no longer expands")
            continue
        new = _tree(arep, None)
        expected = _expected(tree, rep, fixed_keys)
        if expected is None:      # a structural (unsafe) fix: its findings decide alone
            continue
        if new is None or not _same_robot(expected, new):
            for p in mine:
                k = _fkey(p)
                if k in bad:
                    continue
                if label in p.models:
                    bad[k] = f"the fix changes more of {label} than the flagged element"
                else:
                    bad[k] = (f"the edited source is also used by {label}, where the fix is "
                              "wrong (it changes that robot)")
    return bad


def _expected(tree: Any, rep: "ModelReport", fixed_keys: "dict[FKey, Problem]") -> Any:
    """The robot of ``rep`` before fixing with the attribute values of its fixed findings (each
    fix's expected results replayed by its kind); None when a fix changes the structure."""
    import copy
    out = copy.deepcopy(tree)
    elements = list(out.iter(tag=etree.Element))
    for p in rep.problems:
        if p.fix is None or _fkey(p) not in fixed_keys:
            continue
        if not p.fix.expect:
            return None
        for name, i, a, b in p.fix.expect:
            if i >= len(elements):
                continue
            kind = expectation(name)     # the fix kind that recorded it (urdf_lint.fix.kinds)
            if kind is not None and not kind.apply(elements[i], a, b):
                return None              # a structural fix: its findings decide alone
    return out


def run_fix(paths: "Sequence[str]", cfg: "Config", resolver: "PackageResolver",
            jobs_n: int | None = None, unsafe: bool = False, diff_only: bool = False,
            in_process: bool = False, memo: "FixMemo | None" = None,
            note: Callable[[str], object] | None = None) -> FixOutcome:
    """``memo`` (a :class:`urdf_lint.fix.memo.FixMemo`): the fixes earlier runs rolled back,
    not tried again while nothing they depend on changed; this run's rollbacks are added.
    Every fix within ``paths`` is tried (a baselined finding's too); the findings that remain
    are reported as ``check`` reports them, without the baseline's (``note`` hears about an
    old baseline file)."""
    from urdf_lint.run.finish import Scope, scope
    from urdf_lint.run.pipeline import RunRequest, run_check
    request = RunRequest(paths, cfg, resolver, jobs_n=jobs_n, in_process=in_process)

    def check(keep_models: bool = False) -> "CheckResult":
        return run_check(replace(request, keep_models=keep_models))
    # the fixes check --fix may make: those editing only the linted paths (run.finish.scope)
    before_result = run_check(replace(request, keep_models=True,
                                      scope=Scope(tuple(str(p) for p in paths))))
    chosen, _, refused = candidates(before_result.findings, unsafe)
    keys: dict[FKey, str | None] = {}
    if memo is not None:
        chosen, keys = _skip_rolled_back(chosen, refused, memo, before_result.models)
    originals: dict[str, bytes] = {}
    if diff_only:
        new = edited_sources(chosen, originals)
        return FixOutcome(before_result, chosen, [], sorted(
            f for f in new if new[f] != originals[f]), unified_diff(new, originals), refused)
    result, chosen, rolled, written = _fix_rounds(check, paths, before_result, chosen,
                                                  originals)
    if memo is not None:
        for p, why in rolled:
            memo.remember(keys.get(_fkey(p)), why)
        memo.save()
    changed = sorted(f for f in written if originals.get(f) is not None)
    result.findings, result.baselined = scope(result.findings, Scope(None, cfg.baseline, note),
                                              result.generated)
    return FixOutcome(result, chosen, rolled, changed, "", refused)


def _skip_rolled_back(chosen: "list[Problem]", refused: "list[tuple[Problem, str]]",
                      memo: "FixMemo", models: "Iterable[ModelReport]"
                      ) -> "tuple[list[Problem], dict[FKey, str | None]]":
    """(the fixes to try, each fix's memo key): a fix an earlier run rolled back, while
    nothing it depends on changed, joins ``refused`` instead."""
    from urdf_lint.fix.memo import fix_key
    keys = {_fkey(p): fix_key(p, models, chosen) for p in chosen}
    earlier = [(p, memo.reason(keys[_fkey(p)])) for p in chosen]
    refused += [(p, f"rolled back on an earlier run ({why}); not tried again until a file "
                    "it depends on changes") for p, why in earlier if why]
    return [p for p, why in earlier if not why], keys


CHANGED = ("its file changed while urdf-lint worked on it; not written (the newer content "
           "is kept: run --fix again)")


def _fix_rounds(check: "Callable[..., CheckResult]", paths: "Sequence[str]",
                before_result: "CheckResult", chosen: "list[Problem]",
                originals: dict[str, bytes]
                ) -> "tuple[CheckResult, list[Problem], list[tuple[Problem, str]], set[str]]":
    """Write the fixes and check again, rolling back those that do not verify, until the
    rest do (at most ``MAX_ROUNDS``): (result, fixes kept, (fix, why) rolled back, files
    written). ``originals`` receives each edited file's text; a failure restores them. Every
    write is a compare-and-swap (:func:`urdf_lint.core.fsbound.rewrite`): a file saved by
    someone else since urdf-lint read or wrote it is left as they saved it, and its fixes
    are given up."""
    from urdf_lint.discovery.discover import repository_root
    before = _snapshot(before_result)
    rolled: list[tuple[Problem, str]] = []
    result = before_result
    out = _Writes(paths, repository_root(paths), originals)
    try:
        for _ in range(MAX_ROUNDS):
            chosen = out.write(chosen, rolled)
            if not chosen:
                break
            result = check(keep_models=True)
            bad = verify(before, before_result.findings, result, chosen,
                         line_maps(chosen, originals))
            if not bad:
                break
            rolled += [(p, bad[_fkey(p)]) for p in chosen if _fkey(p) in bad]
            chosen = [p for p in chosen if _fkey(p) not in bad]
        else:
            rolled += [(p, "the fixes did not verify") for p in chosen]
            chosen = []
        if not chosen:
            out.restore()
            if rolled:
                result = check()
    except BaseException:
        out.restore()     # never leave half-fixed sources behind
        raise
    return result, chosen, rolled, set(out.written)


class _Writes:
    """The sources --fix has written, and what each holds now (what the next write of it
    expects to find there)."""

    def __init__(self, paths: "Sequence[str]", repo: str, originals: dict[str, bytes]) -> None:
        self.paths, self.repo, self.originals = paths, repo, originals
        self.on_disk: dict[str, bytes] = {}  # real path -> the bytes it holds (as read or written)
        self.written: set[str] = set()
        self.skipped: set[str] = set()   # real paths someone else changed: never written again

    def put(self, f: str, data: bytes) -> bool:
        """Write one file if it still holds what urdf-lint last saw there; False (and said)
        when it changed meanwhile."""
        from urdf_lint.core.emit import say
        from urdf_lint.core.escape import escape_text
        from urdf_lint.core.locations import display_path
        real = os.path.realpath(f)    # (a file and a symlink to it are one file)
        old = self.on_disk.get(real, self.originals[f])
        try:
            fsbound.rewrite(f, data, self.paths, old=old, repo=self.repo)
        except fsbound.ChangedError:
            say(f"{escape_text(display_path(f))}: skipped: it changed while urdf-lint fixed "
                "it; the newer content is kept (run --fix again)")
            self.skipped.add(real)
            self.written.discard(f)
            return False
        except OSError as e:   # a full disk, a file size limit, a refused path: the run stops
            from urdf_lint.core.errors import UsageError
            why = getattr(e, "why", None) or e.strerror or e
            raise UsageError(f"cannot write {escape_text(display_path(f))}: {escape_text(why)}"
                             ) from None
        self.on_disk[real] = data
        return True

    def write(self, chosen: "list[Problem]", rolled: "list[tuple[Problem, str]]"
              ) -> "list[Problem]":
        """Write this round's sources (a file whose fixes were all rolled back is restored);
        the fixes kept, those that edit a file someone changed added to ``rolled``."""
        while True:
            new = edited_sources(chosen, self.originals)
            for f in sorted(set(self.written) - set(new)):
                if self.put(f, self.originals[f]):
                    self.written.discard(f)
            for f, data in sorted(new.items()):
                if os.path.realpath(f) not in self.skipped and self.put(f, data):
                    self.written.add(f)
            gone = [p for p in chosen
                    if any(os.path.realpath(e.file) in self.skipped for e in _fix(p).edits)]
            if not gone:
                return chosen
            rolled += [(p, CHANGED) for p in gone]
            chosen = [p for p in chosen if p not in gone]

    def restore(self) -> None:
        """Put every source written back as it was read: each is tried, whatever the others
        do (then the first failure is raised)."""
        from urdf_lint.core.errors import UsageError
        failed: UsageError | None = None
        for f in sorted(self.written):
            try:
                self.put(f, self.originals[f])
            except UsageError as e:
                failed = failed or e
        self.written = set()
        if failed is not None:
            raise failed
