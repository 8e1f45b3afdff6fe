"""Compatibility names for code written against the old ``check`` module.

The orchestration now lives in rooms named for what they do: :mod:`urdf_lint.discovery`
(candidate models, package roots), :mod:`urdf_lint.pipeline` (the run), :mod:`urdf_lint.policy`
(select / ignore / severity) and :mod:`urdf_lint.vcs` (git). Import from those in new code.
"""
from __future__ import annotations

from .discovery import build_resolver, discover
from .pipeline import CheckResult, exit_code, run_check, settings_for
from .vcs import git_root, repo_root

__all__ = ["CheckResult", "build_resolver", "discover", "exit_code", "git_root", "repo_root",
           "run_check", "settings_for"]
