"""``urdf-lint expand``: one xacro file to URDF, expanded in a sandboxed worker."""
from __future__ import annotations

import os
import sys

from urdf_lint.cli.common import (ConfigOptions, apply_cli_values, apply_trust, expand_in_workers,
                                  parse_package_paths, safe_text, write_base)
from urdf_lint.cli.parser import add_inputs, add_key_flags
from urdf_lint.core.emit import say
from urdf_lint.core.errors import UsageError


NAME = "expand"


def add_parser(sub, raw):
    e = sub.add_parser("expand", help="expand one xacro file to URDF (no ROS needed)",
                       description="Expand one xacro file to URDF, byte-identical to xacro 2.1.1.")
    e.add_argument("file", help="the .xacro file")
    e.add_argument("mappings", nargs="*", metavar="name:=value",
                   help="xacro args (default: the args' defaults)")
    e.add_argument("-o", "--output", metavar="FILE",
                   help="write the URDF to FILE, atomically (default: standard output)")
    add_inputs(e, config=False)
    add_key_flags(e, "limits")


def parse_mappings(items):
    args, rest = {}, []
    for it in items:
        if ":=" in it:
            k, _, v = it.partition(":=")
            args[k] = v
        else:
            rest.append(it)
    return args, rest


def run(args) -> int:
    if not os.path.isfile(args.file):
        raise UsageError(f"no such file: {args.file}")
    from urdf_lint.run.worker import prestart
    prestart()   # (done already by main(); here for callers of cmd_expand)
    from urdf_lint.config.schema import find_config, load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.core.jobs import LintJob, Status
    from urdf_lint.core.locations import display_path
    mappings, rest = parse_mappings(args.mappings)
    if rest:
        raise UsageError(f"expected name:=value, got {' '.join(rest)}")
    cfg = load_config(find_config(args.file))
    opts = ConfigOptions.from_args(args)
    apply_trust(cfg, opts, [args.file])
    apply_cli_values(cfg, opts)
    resolver = build_resolver([args.file], cfg, parse_package_paths(args.package_path))
    # expanded in a worker like `check`: time and memory limits, scrubbed environment, sandbox
    job = LintJob(os.path.abspath(args.file), mappings, "expand", explicit=True,
                  display_name=args.file)
    res = expand_in_workers([job], resolver, cfg)[0]
    from urdf_lint.run.pipeline import hint_packages
    hint_packages([res], [args.file])   # a sibling package's package.xml: --package-path
    from urdf_lint.core.emit import report_internal
    if report_internal(res.internal):
        return 2
    for n in res.problems:
        say(f"{safe_text(display_path(n.file))}:{n.line}:{n.col}: {n.code} "
            f"{safe_text(n.message)}")
    xml = res.kept_model.xml if res.kept_model is not None else None
    if res.status is Status.FAILED or xml is None:
        if not res.problems:
            from urdf_lint.rules import ul002_xacro_error
            say(f"{display_path(job.entry)}:1:1: {ul002_xacro_error.CODE} expansion failed")
        return 1
    if args.output:
        from urdf_lint.core import fsbound
        try:
            fsbound.write_text(args.output, xml, write_base(args.output, [args.file]),
                               make_dirs=True)
        except OSError as e:
            raise UsageError(f"cannot write {safe_text(args.output)}: "
                             f"{safe_text(getattr(e, 'why', None) or e.strerror or e)}") from None
    else:
        sys.stdout.write(xml)
    return 0
