"""``urdf-lint generate``: rewrite every stale generated URDF."""
from __future__ import annotations

import os

from urdf_lint.cli.common import (ConfigOptions, expand_in_workers, load_cfg, parse_package_paths,
                                  safe_text, write_base)
from urdf_lint.cli.parser import add_inputs
from urdf_lint.core.emit import say, tell
from urdf_lint.core.errors import UsageError


NAME = "generate"


def add_parser(sub, raw):
    g = sub.add_parser("generate", help="rewrite every stale generated URDF (the 'output' of a "
                       "models entry, or a .urdf whose header names its xacro)",
                       description="Rewrite every generated URDF that no longer equals what its "
                                   "xacro expands to (atomically); exit 1 when one was stale.")
    g.add_argument("paths", nargs="*", default=["."], metavar="PATH",
                   help="files or folders (default: .)")
    g.add_argument("--check", action="store_true",
                   help="only report stale outputs (exit 1), write nothing")
    add_inputs(g)


def run(args) -> int:
    """Regenerate stale outputs in place (atomically); exit 1 when a file was (or, with
    --check, would be) rewritten or a xacro did not expand, like a formatter hook. Each xacro
    is expanded in a sandboxed worker with the run's limits, like ``check`` and ``expand``:
    the worker returns the XML, the parent compares and writes it (inside the repository
    only, anywhere the user trusts with --trust-config)."""
    import dataclasses

    from urdf_lint.config import trust
    from urdf_lint.core import fsbound
    from urdf_lint.discovery.discover import build_resolver, discover_models, start_dir
    from urdf_lint.core.emit import report_internal
    from urdf_lint.discovery.generated import (header_source, read_output, stale_at,
                                               write_output)
    from urdf_lint.core.jobs import Status
    from urdf_lint.core.locations import display_path
    from urdf_lint.discovery.vcs import repo_root
    for p in args.paths:
        if not os.path.exists(p):
            raise UsageError(f"no such file or directory: {p}")
    cfg = load_cfg(ConfigOptions.from_args(args), args.paths)
    resolver = build_resolver(args.paths, cfg, parse_package_paths(args.package_path))
    # (what the header names: xacro opens this path)
    jobs = [dataclasses.replace(job, kind="expand", display_name=os.path.relpath(job.entry))
            for job in discover_models(args.paths, cfg, resolver).jobs if job.output]
    status = 0
    stale = failed = 0
    for job, res in zip(jobs, expand_in_workers(jobs, resolver, cfg), strict=True):
        assert job.output is not None and job.display_name is not None
        if report_internal(res.internal):
            status = 2
            continue
        shown = job.display_name
        xml = res.kept_model.xml if res.kept_model is not None else None
        if res.status is Status.FAILED or xml is None:
            for e in res.problems[-1:]:   # (before it: the expansion's notes)
                say(f"{safe_text(display_path(e.file))}:{e.line}:{e.col}: {e.code} "
                    f"{safe_text(e.message)}")
            status = max(status, 1)
            failed += 1
            continue
        old = read_output(job.output)    # what a rewrite expects to find there
        if stale_at(job.output, xml) is None:
            continue
        status = max(status, 1)
        stale += 1
        named = header_source(job.output, resolver.roots) if os.path.exists(job.output) else None
        if named and xml:   # keep the header's own name for the source: no churn
            head, rest = xml[:1024], xml[1024:]
            xml = head.replace(f"from {shown} ", f"from {named} ", 1) + rest
        if args.check:
            tell(f"would regenerate {safe_text(display_path(job.output))} from "
                 f"{safe_text(display_path(job.entry))}")
        else:
            try:   # inside the repository only (anywhere the user trusts with --trust-config)
                write_output(job.output, xml, write_base(job.output, args.paths)
                             if args.trust_config else
                             trust.config_root(cfg, repo_root(start_dir(args.paths))), old)
            except fsbound.ChangedError:
                say(f"{safe_text(display_path(job.output))}: skipped: it changed while "
                    "urdf-lint regenerated it; the newer content is kept (run generate again)")
                continue
            except OSError as e:
                say(f"urdf-lint: error: cannot write {display_path(job.output)}: "
                    f"{getattr(e, 'why', None) or e.strerror or e}")
                status = 2
                continue
            tell(f"regenerated {safe_text(display_path(job.output))} from "
                 f"{safe_text(display_path(job.entry))}")
    tell(_generate_summary(len(jobs), stale, failed, args.check))
    return status


def _generate_summary(outputs, stale, failed, check) -> str:
    """``generate``: one line, also when everything was up to date."""
    if not outputs:
        return ("urdf-lint generate: no generated URDF found (a models entry with 'output', or a "
                ".urdf whose header names its xacro)")
    done = "would be regenerated" if check else "regenerated"
    parts = [f"{stale} {done}" if stale else "all up to date" if not failed else ""]
    if failed:
        parts.append(f"{failed} xacro(s) did not expand")
    return (f"urdf-lint generate: {outputs} generated URDF(s) checked, "
            + ", ".join(p for p in parts if p) + ".")
