"""The in-process lint of the language server's unit tests bypasses the sandbox: only code
constructs it (``Workspace(root, in_process=True)``); the server, the CLI and a repository's
config never reach it (SECURITY.md, "The language server")."""
from __future__ import annotations

import ast
import dataclasses
from pathlib import Path

PKG = Path(__file__).resolve().parents[2] / "urdf_lint"


def test_only_the_workspace_itself_names_the_in_process_lint():
    """No module of the package makes an ``InProcessLinter``, and none of the language
    server or the CLI passes or reads ``in_process``, but the one that defines them (the run
    pipeline's own ``RunRequest.in_process`` is another, older thing)."""
    named = set()
    for f in sorted(PKG.rglob("*.py")):
        rel = f.relative_to(PKG).as_posix()
        front = rel.startswith(("lsp/", "cli/"))
        for n in ast.walk(ast.parse(f.read_text(encoding="utf-8"))):
            if isinstance(n, ast.Name) and n.id == "InProcessLinter" or front and (
                    isinstance(n, ast.keyword) and n.arg == "in_process" or
                    isinstance(n, ast.Attribute) and n.attr == "in_process"):
                named.add(rel)
    assert named == {"lsp/state.py"}, named


def test_the_server_lints_in_the_sandboxed_pool_and_no_config_key_changes_it(tmp_path,
                                                                             monkeypatch):
    from urdf_lint.config.schema import KEYS
    from urdf_lint.lsp.state import Workspace
    from urdf_lint.runner.pool import WorkerPool
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    (tmp_path / "package.xml").write_text("<package><name>p</name></package>\n")
    field = {f.name: f for f in dataclasses.fields(Workspace)}["in_process"]
    assert field.kw_only and field.default is False
    assert not [k for k in KEYS if "process" in k or "sandbox" in k.replace("-", "")]
    ws = Workspace(str(tmp_path))   # (as methods/initialized.py makes it; no worker forked)
    try:
        assert type(ws.pool) is WorkerPool and ws.pool.persistent
    finally:
        ws.close()
