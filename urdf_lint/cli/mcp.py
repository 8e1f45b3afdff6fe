"""``urdf-lint mcp``: a Model Context Protocol server on stdio for coding agents (issue 27).

Every tool runs the ``urdf-lint`` command line itself, as a subprocess of this interpreter
(``python -m urdf_lint ...``) in the server's root folder: the same sandboxed workers, roots,
limits and repository-config rules (``trust.py``) as a user's run, nothing less confined.
Every path an agent passes must resolve (symlinks followed) inside the root (the working
directory the server started in, or ``--root``); anything else is refused before a command
runs. Tools: ``check``, ``explain_rule``, ``expand``, ``fix`` (a dry run by default),
``diff`` and ``render``.

Needs the optional extra: ``pip install 'urdf-lint[mcp]'``.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys

TIMEOUT_S = 900


class OutsideRoot(ValueError):
    pass


def _inside(root: str, path: str) -> str:
    """``path`` (relative to the root) resolved; refused unless it is in the root."""
    real = os.path.realpath(os.path.join(root, path))
    if real != root and not real.startswith(root.rstrip(os.sep) + os.sep):
        raise OutsideRoot(f"{path!r} is outside the server's root {root}; refused")
    return os.path.relpath(real, root)


def _run(root: str, *args: str) -> dict:
    p = subprocess.run([sys.executable, "-m", "urdf_lint", *args], cwd=root,
                       capture_output=True, text=True, timeout=TIMEOUT_S,
                       stdin=subprocess.DEVNULL)
    return {"exit_code": p.returncode, "stdout": p.stdout, "stderr": p.stderr}


def _json(res: dict) -> dict:
    try:
        res["result"] = json.loads(res.pop("stdout") or "null")
    except ValueError:
        res["result"] = None
    return res


class Tools:
    """The tools, as plain functions of a root (what the server exposes; tested directly too)."""

    def __init__(self, root: str):
        self.root = os.path.realpath(root)

    def paths(self, paths) -> list[str]:
        return [_inside(self.root, p) for p in (paths or ["."])]

    def check(self, paths: list[str] | None = None, select: str | None = None,
              targets: list[str] | None = None) -> dict:
        args = ["check", *self.paths(paths), "--output-format", "json", "-q"]
        for opt, value in (("--select", select), *(("--target", t) for t in targets or ())):
            if value:
                if value.startswith("-"):
                    raise ValueError(f"{opt} cannot start with '-': {value!r}")
                args.append(f"{opt}={value}")
        return _json(_run(self.root, *args))

    def explain_rule(self, code: str) -> dict:
        return _run(self.root, "rule", code)

    def expand(self, file: str, args: dict | None = None) -> dict:
        maps = [f"{k}:={v}" for k, v in (args or {}).items()]
        return _run(self.root, "expand", _inside(self.root, file), *maps)

    def fix(self, paths: list[str] | None = None, apply: bool = False,
            unsafe: bool = False) -> dict:
        args = ["check", *self.paths(paths), "--fix" if apply else "--diff", "-q"]
        if unsafe:
            args.append("--unsafe-fixes")
        return _run(self.root, *args)

    def diff(self, base: str, head: str | None = None, paths: list[str] | None = None) -> dict:
        if base.startswith("-") or (head or "").startswith("-"):
            raise ValueError("a revision cannot start with '-'")
        args = ["diff", base, *([head] if head else []), "--format", "json"]
        for p in self.paths(paths) if paths else []:
            args += ["--path", p]
        return _json(_run(self.root, *args))

    def render(self, paths: list[str] | None = None, out: str = "snapshots") -> dict:
        res = _run(self.root, "render", *self.paths(paths), "--out", _inside(self.root, out),
                   "--no-rrd")
        res["pngs"] = [os.path.join(self.root, ln) for ln in res["stdout"].splitlines()
                       if ln.endswith(".png")]
        return res


def build_server(root: str):
    try:
        from mcp.server.mcpserver import MCPServer as Server   # mcp 2
        from mcp.server.mcpserver.exceptions import ToolError
    except ImportError:   # pragma: no cover - mcp 1
        from mcp.server.fastmcp import FastMCP as Server  # type: ignore
        from mcp.server.fastmcp.exceptions import ToolError  # type: ignore
    import functools
    plain = Tools(root)

    class _Refusing:
        """The tools, a refused path or argument reported to the agent as the tool's error."""

        def __getattr__(self, name):
            fn = getattr(plain, name)

            @functools.wraps(fn)
            def call(*a, **kw):
                try:
                    return fn(*a, **kw)
                except (ValueError, subprocess.TimeoutExpired) as e:
                    raise ToolError(str(e)) from None
            return call
    tools = _Refusing()
    server = Server("urdf-lint", instructions=(
        "Lint, fix, expand, diff and render URDF/xacro robot descriptions under "
        f"{plain.root} (paths are relative to it; nothing outside it is read)."))

    @server.tool()
    def check(paths: list[str] | None = None, select: str | None = None,
              targets: list[str] | None = None) -> dict:
        """Lint the robot models under the paths: findings as urdf-lint's JSON report
        (file, line, column, code, message, macro chain, fixes). select: rule codes or names,
        comma-separated (like --select); targets: the consumers the robot is for, as
        --target (ros, gazebo, mujoco, drake, ...: `urdf-lint rules` lists them), which set
        each finding's severity (severity_from names the target that raised it)."""
        return tools.check(paths, select, targets)

    @server.tool()
    def explain_rule(code: str) -> dict:
        """What a rule (UL302 or limit-order) checks, why, and how to fix it."""
        return tools.explain_rule(code)

    @server.tool()
    def expand(file: str, args: dict[str, str] | None = None) -> dict:
        """Expand one xacro file to URDF (xacro args as name -> value); stdout is the URDF."""
        return tools.expand(file, args)

    @server.tool()
    def fix(paths: list[str] | None = None, apply: bool = False, unsafe: bool = False) -> dict:
        """The safe fixes as a unified diff (stdout); apply=true writes them (then re-lints
        and rolls back any that did not work)."""
        return tools.fix(paths, apply, unsafe)

    @server.tool()
    def diff(base: str, head: str | None = None, paths: list[str] | None = None) -> dict:
        """What a change did to the robots between two git revisions (head: the working
        tree by default): the semantic change list as JSON."""
        return tools.diff(base, head, paths)

    @server.tool()
    def render(paths: list[str] | None = None, out: str = "snapshots") -> dict:
        """Draw a PNG snapshot of each model into the folder out; returns their paths."""
        return tools.render(paths, out)
    return server


def add_parser(sub, raw) -> None:
    p = sub.add_parser("mcp", help="a Model Context Protocol server on stdio (for coding agents)",
                       description="Serve check, explain_rule, expand, fix, diff and render to "
                                   "a coding agent over MCP on stdio. Every tool runs the "
                                   "urdf-lint command line (same sandbox and limits); paths "
                                   "outside the root are refused. Needs urdf-lint[mcp].")
    p.add_argument("--root", default=".", help="the folder the tools may reach (default: .)")


def cmd_mcp(args) -> int:
    from urdf_lint.core.errors import UsageError
    if not os.path.isdir(args.root):
        raise UsageError(f"no such folder: {args.root}")
    try:
        server = build_server(args.root)
    except ImportError:
        raise UsageError("urdf-lint mcp needs the MCP SDK: pip install 'urdf-lint[mcp]'") \
            from None
    server.run()
    return 0
