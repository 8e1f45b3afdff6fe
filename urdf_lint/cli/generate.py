"""``urdf-lint generate``: rewrite every stale generated URDF."""
from __future__ import annotations

import os
from typing import TYPE_CHECKING

from urdf_lint.cli.common import (ConfigOptions, expand_in_workers, load_cfg, parse_package_paths,
                                  safe_text, write_base)
from urdf_lint.cli.parser import add_inputs
from urdf_lint.core.emit import say, tell
from urdf_lint.core.errors import UsageError
from urdf_lint.core.jobs import model_key

if TYPE_CHECKING:  # pragma: no cover
    from argparse import Namespace

    from urdf_lint.cli.parser import Formatter, SubParsers
    from urdf_lint.config.schema import Config
    from urdf_lint.core.jobs import JobKey, LintJob, ModelReport
    from urdf_lint.discovery.packages import PackageResolver


NAME = "generate"


def add_parser(sub: SubParsers, raw: Formatter) -> None:
    g = sub.add_parser("generate", help="rewrite every stale generated URDF (the 'output' of a "
                       "models entry, or a .urdf whose header names its xacro)",
                       description="Rewrite every generated URDF that no longer equals what its "
                                   "xacro expands to (atomically); exit 1 when one was stale.")
    g.add_argument("paths", nargs="*", default=["."], metavar="PATH",
                   help="files or folders (default: .)")
    g.add_argument("--check", action="store_true",
                   help="only report stale outputs (exit 1), write nothing")
    add_inputs(g)


def run(args: Namespace) -> int:
    """Regenerate stale outputs in place (atomically); exit 1 when a file was (or, with
    --check, would be) rewritten, was refused or a xacro did not expand, like a formatter
    hook. Each xacro is expanded in a sandboxed worker with the run's limits, like ``check``
    and ``expand``: the worker returns the XML, the parent compares and writes it (inside the
    repository only, anywhere the user trusts with --trust-config). A file is rewritten only
    with the args that made it (a models entry's ``output``, or the args this command recorded
    in its header); one whose header records none is refused unless a variant gives it."""
    import dataclasses

    from urdf_lint.discovery.discover import build_resolver, discover_models
    from urdf_lint.core.emit import report_internal
    from urdf_lint.core.jobs import Status
    from urdf_lint.core.locations import display_path
    for p in args.paths:
        if not os.path.exists(p):
            raise UsageError(f"no such file or directory: {p}")
    cfg = load_cfg(ConfigOptions.from_args(args), args.paths)
    resolver = build_resolver(args.paths, cfg, parse_package_paths(args.package_path))
    jobs = [job for job in discover_models(args.paths, cfg, resolver).jobs if job.output]
    # every variant an output is compared with, expanded once (xacro opens the path the
    # header names)
    wanted: dict[JobKey, LintJob] = {}
    for job in jobs:
        for a in (job.args, *(dict(v) for v in job.variants)):
            wanted.setdefault(model_key(job.entry, a), dataclasses.replace(
                job, args=dict(a), kind="expand", display_name=os.path.relpath(job.entry),
                output=None, outputs=(), untied=(), variants=()))
    todo = list(wanted.values())
    done = dict(zip(wanted, expand_in_workers(todo, resolver, cfg), strict=True))
    tally = {"stale": 0, "failed": 0, "refused": 0, "outputs": 0}
    status = 0
    for job in jobs:
        res = done[model_key(job.entry, job.args)]
        if report_internal(res.internal):
            status = 2
            continue
        xml = res.kept_model.xml if res.kept_model is not None else None
        if res.status is Status.FAILED or xml is None:
            for e in res.problems[-1:]:   # (before it: the expansion's notes)
                say(f"{safe_text(display_path(e.file))}:{e.line}:{e.col}: {e.code} "
                    f"{safe_text(e.message)}")
            status = max(status, 1)
            tally["failed"] += 1
            continue
        others = [(dict(v), _xml_of(done[model_key(job.entry, dict(v))])) for v in job.variants]
        variants = [(job.args, xml)] + [(a, x) for a, x in others if x is not None]
        assert job.output is not None   # (jobs with an output only, above)
        for output in (job.output, *job.outputs):
            tally["outputs"] += 1
            status = max(status, _one_output(args, cfg, job, output, variants, tally, resolver))
    tell(_generate_summary(tally, args.check))
    return status


def _xml_of(res: ModelReport) -> str | None:
    from urdf_lint.core.jobs import Status
    if res.status is Status.FAILED or res.kept_model is None:
        return None
    return res.kept_model.xml


def _one_output(args: Namespace, cfg: Config, job: LintJob, output: str,
                variants: list[tuple[dict[str, str], str]], tally: dict[str, int],
                resolver: PackageResolver) -> int:
    """Compare one output with its variant and rewrite it when stale; the exit status."""
    from urdf_lint.config import trust
    from urdf_lint.core.locations import display_path
    from urdf_lint.discovery.discover import start_dir
    from urdf_lint.core import fsbound
    from urdf_lint.discovery.generated import (closest_variant, describe_args, header_source,
                                               read_output, stale_at, with_header, write_output)
    from urdf_lint.discovery.vcs import repo_root
    shown = safe_text(display_path(output))
    source = safe_text(display_path(job.entry))
    xml = variants[0][1]
    if output in job.untied:
        made, got = closest_variant(output, variants)
        if got is None:
            return 0
        tally["refused"] += 1
        line, _col, what = got
        say(f"urdf-lint generate: {shown}:{line}: not rewritten: it is stale, or made with "
            f"args urdf-lint does not know (its header records none; closest: "
            f"{safe_text(describe_args(made))} of {source}, {safe_text(what)}); add a "
            "[[tool.urdf-lint.models]] entry with its output and args")
        return 1
    old = read_output(output)    # what a rewrite expects to find there
    if stale_at(output, xml) is None:
        return 0
    tally["stale"] += 1
    named = header_source(output, resolver.roots) if os.path.exists(output) else None
    # the header's own name for the source (no churn), and the args that made it
    xml = with_header(xml, named, job.args)
    with_args = safe_text(f" with {describe_args(job.args)}") if job.args else ""
    if args.check:
        tell(f"would regenerate {shown} from {source}{with_args}")
        return 1
    try:   # inside the repository only (anywhere the user trusts with --trust-config)
        write_output(output, xml, write_base(output, args.paths) if args.trust_config else
                     trust.config_root(cfg, repo_root(start_dir(args.paths))), old)
    except fsbound.ChangedError:
        say(f"{shown}: skipped: it changed while urdf-lint regenerated it; the newer content "
            "is kept (run generate again)")
        return 1
    except OSError as e:
        say(f"urdf-lint: error: cannot write {display_path(output)}: "
            f"{getattr(e, 'why', None) or e.strerror or e}")
        return 2
    tell(f"regenerated {shown} from {source}{with_args}")
    return 1


def _generate_summary(tally: dict[str, int], check: bool) -> str:
    """``generate``: one line, also when everything was up to date."""
    if not tally["outputs"] and not tally["failed"]:
        return ("urdf-lint generate: no generated URDF found (a models entry with 'output', or a "
                ".urdf whose header names its xacro)")
    done = "would be regenerated" if check else "regenerated"
    stale, failed, refused = tally["stale"], tally["failed"], tally["refused"]
    parts = [f"{stale} {done}" if stale else "all up to date" if not (failed or refused)
             else ""]
    if refused:
        parts.append(f"{refused} refused (args unknown)")
    if failed:
        parts.append(f"{failed} xacro(s) did not expand")
    return (f"urdf-lint generate: {tally['outputs']} generated URDF(s) checked, "
            + ", ".join(p for p in parts if p) + ".")
