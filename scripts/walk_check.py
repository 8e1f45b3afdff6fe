#!/usr/bin/env python3
"""The walk of ``check``: which of urdf-lint's rooms and modules a request visits, in order.

Runs ``urdf-lint check descriptions/ --no-cache`` (or the arguments given) in this process under
``sys.setprofile`` and follows where execution is: on each call of a function of ours, the
callee's module; on each return, the module of the nearest caller of ours. Code that is not
urdf-lint's (the standard library, lxml, xacro) is transparent, and so is a module's import-time
code (``<module>``): the walk is the request's, not the imports'. Only this process is
followed; the sandboxed workers that lint each model are other processes.

The room stack of a moment is the rooms of the frames of ours from the outermost (cli first),
consecutive repeats merged; the walk is its element ``--depth`` deep (default 2: the CLI and
the rooms it calls, each with what it calls directly), consecutive repeats collapsed (one
"stay" per visit). Then counts: stays, distinct rooms, room changes, climbs (a call from a room
into a higher one in the layers of ``[tool.importlinter]``, each listed; the engine calling a
rule is by design and not counted) and how often the CLI room is entered again after the
request left it. ``--modules``: the same walk by module.

    python scripts/walk_check.py [--modules] [--depth N] [-- CHECK-ARGS...]
"""
from __future__ import annotations

import contextlib
import io
import os
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))   # this checkout's code


def layers() -> dict[str, int]:
    """{room: its layer's index (0 is the top)} from pyproject.toml's layers contract."""
    try:
        import tomllib
    except ModuleNotFoundError:        # Python 3.10
        import tomli as tomllib
    conf = tomllib.loads((REPO / "pyproject.toml").read_text(encoding="utf-8"))
    contract = next(c for c in conf["tool"]["importlinter"]["contracts"]
                    if c["type"] == "layers")
    return {m.strip().strip("()").removeprefix("urdf_lint."): i
            for i, layer in enumerate(contract["layers"]) for m in layer.split("|")}


def module_of(filename: str, roots: tuple[tuple[str, str], ...]) -> str | None:
    """``urdf_lint.x.y`` for a file of ours (urdf_lint/ or rules/), else None."""
    for root, prefix in roots:
        if filename.startswith(root):
            rel = filename[len(root):].removesuffix(".py").replace(os.sep, ".")
            return prefix + rel.removesuffix(".__init__")
    return None


class Walk:
    """What a profiled run saw: ``rooms``, the walk at each depth of the room stack (the
    rooms of the frames of ours from the outermost, consecutive repeats merged), collapsed;
    ``modules``, the same by module; ``climbs``, each call from a room into a higher one (not
    the registry calling a rule's ``check``: rules are above the engine by design), as
    ``caller module -> callee module.function``; ``rc``, the exit code."""

    def __init__(self, depth: int) -> None:
        self.depth = depth
        self.rooms: list[str] = []
        self.modules: list[str] = []
        self.climbs: list[str] = []
        self.rc = 0


def _merged(names: list[str]) -> list[str]:
    return [n for i, n in enumerate(names) if i == 0 or names[i - 1] != n]


def walk(argv: list[str], depth: int = 2) -> Walk:
    """Run ``urdf-lint ARGV`` in this process and record its walk to ``depth`` rooms deep."""
    import urdf_lint
    import urdf_lint.rules as rules
    roots = ((str(Path(urdf_lint.__file__).parent) + os.sep, "urdf_lint."),
             (str(Path(rules.__file__).parent) + os.sep, "urdf_lint.rules."))
    from urdf_lint.cli.main import main
    rank = layers()
    w = Walk(depth)
    known: dict[object, str | None] = {}

    def ours(frame) -> str | None:
        code = frame.f_code
        if code not in known:
            mod = module_of(code.co_filename, roots)
            known[code] = None if code.co_name == "<module>" else mod
        return known[code]

    def stack(frame) -> list[str]:
        mods = []
        while frame is not None:
            mod = ours(frame)
            if mod:
                mods.append(mod)
            frame = frame.f_back
        return mods[::-1]

    def note(mods: list[str]) -> None:
        """The room ``depth`` deep in the room stack of ``mods``, and the module by which
        execution entered it."""
        groups: list[list[str]] = []
        for m in mods:
            if groups and groups[-1][0].split(".")[1] == m.split(".")[1]:
                groups[-1].append(m)
            else:
                groups.append([m])
        if not groups:
            return
        entry = groups[:w.depth][-1][0]
        room = entry.split(".")[1]
        if not w.rooms or w.rooms[-1] != room:
            w.rooms.append(room)
        if not w.modules or w.modules[-1] != entry:
            w.modules.append(entry)

    def profile(frame, event, arg):
        if event == "call":
            callee = ours(frame)
            if callee is None:
                return
            mods = stack(frame)
            caller = next((m for m in reversed(mods[:-1])), None)
            if caller:
                a, b = caller.split(".")[1], callee.split(".")[1]
                if rank.get(b, 99) < rank.get(a, 99) and (a, b) != ("engine", "rules"):
                    w.climbs.append(f"{caller} -> {callee}.{frame.f_code.co_name}")
        elif event == "return":
            mods = stack(frame.f_back)
        else:
            return
        note(mods)

    out = io.StringIO()
    sys.setprofile(profile)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(out):
            try:
                w.rc = main(argv)
            except SystemExit as e:
                w.rc = e.code if isinstance(e.code, int) else 1
    finally:
        sys.setprofile(None)
    return w


def excursions(names: list[str], home: str) -> list[str]:
    """A walk that keeps coming back to ``home`` (``cli > config > cli > config > cli > run``)
    written as its runs of excursions (``cli > config x2 > run``); a name in ``home``'s room
    (``cli.check`` for ``cli``) is home too."""
    out: list[tuple[str, int]] = []
    for n in names:
        if n == home or n.startswith(home + "."):
            continue
        if out and out[-1][0] == n:
            out[-1] = (n, out[-1][1] + 1)
        else:
            out.append((n, 1))
    return [home] + [f"{n} x{k}" if k > 1 else n for n, k in out]


def counts(w: Walk) -> dict[str, int]:
    """Stays, distinct rooms, room changes, climbs (and distinct ones) and how often the CLI
    room is entered again."""
    cli = w.rooms.count("cli")
    return {"stays": len(w.rooms), "rooms": len(set(w.rooms)),
            "room changes": max(len(w.rooms) - 1, 0), "climbs": len(w.climbs),
            "distinct climbs": len(set(w.climbs)), "cli re-entries": max(cli - 1, 0),
            "runs of excursions from cli": len(excursions(w.rooms, "cli")) - 1}


def main(argv: list[str]) -> int:
    show_modules = "--modules" in argv
    depth = int(argv[argv.index("--depth") + 1]) if "--depth" in argv else 2
    check = argv[argv.index("--") + 1:] if "--" in argv else ["descriptions/", "--no-cache"]
    os.chdir(REPO)
    os.environ.setdefault("NO_COLOR", "1")
    w = walk(["check", *check], depth)
    print(f"urdf-lint check {' '.join(check)}: exit {w.rc}; the walk {depth} rooms deep")
    if show_modules:
        print(f"modules entered ({len(w.modules)} stays):")
        short = [m.removeprefix("urdf_lint.") for m in w.modules]
        print("  " + " > ".join(excursions(short, "cli")))
    print(f"rooms ({len(w.rooms)} stays), as runs of excursions from cli:")
    print("  " + " > ".join(excursions(w.rooms, "cli")))
    if w.climbs:
        print("climbs (a call into a higher room), each once:")
        for c in dict.fromkeys(w.climbs):
            print(f"  {c.replace('urdf_lint.', '')}")
    for name, n in counts(w).items():
        print(f"{name}: {n}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
