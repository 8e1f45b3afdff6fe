"""``urdf-lint expand``: one xacro file to URDF, expanded in a sandboxed worker."""
from __future__ import annotations

import os
import sys
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from urdf_lint.cli.common import (ConfigOptions, apply_cli_values, apply_trust, expand_in_workers,
                                  options_from, parse_package_paths, safe_text, write_base)
from urdf_lint.cli.parser import add_inputs, add_key_flags
from urdf_lint.core.emit import say
from urdf_lint.core.errors import UsageError

if TYPE_CHECKING:  # pragma: no cover
    from argparse import Namespace
    from collections.abc import Iterable

    from urdf_lint.cli.parser import Formatter, SubParsers


NAME = "expand"


def add_parser(sub: SubParsers, raw: Formatter) -> None:
    e = sub.add_parser("expand", help="expand one xacro file to URDF (no ROS needed)",
                       description="Expand one xacro file to URDF, byte-identical to xacro 2.1.1.")
    e.add_argument("file", help="the .xacro file")
    e.add_argument("mappings", nargs="*", metavar="name:=value",
                   help="xacro args (default: the args' defaults)")
    e.add_argument("-o", "--output", metavar="FILE",
                   help="write the URDF to FILE, atomically (default: standard output)")
    add_inputs(e, config=False)
    add_key_flags(e, "limits")


def parse_mappings(items: Iterable[str]) -> tuple[dict[str, str], list[str]]:
    args: dict[str, str] = {}
    rest: list[str] = []
    for it in items:
        if ":=" in it:
            k, _, v = it.partition(":=")
            args[k] = v
        else:
            rest.append(it)
    return args, rest


@dataclass
class ExpandOptions:
    """What ``expand`` was asked to do (from the command line, or the MCP server's ``expand``
    tool: the same typed options, no command line in between)."""
    file: str
    mappings: dict[str, str] = field(default_factory=dict)     # xacro arg name -> value
    output: str | None = None
    package_path: list[str] | None = None
    config: ConfigOptions = field(default_factory=ConfigOptions)


def run(args: Namespace) -> int:
    mappings, rest = parse_mappings(args.mappings)
    if rest:
        raise UsageError(f"expected name:=value, got {' '.join(rest)}")
    return expand(options_from(ExpandOptions, args, mappings=mappings,
                               config=ConfigOptions.from_args(args)))


def expand(o: ExpandOptions) -> int:
    if not os.path.isfile(o.file):
        raise UsageError(f"no such file: {o.file}")
    from urdf_lint.run.worker import prestart
    prestart()   # (done already by main(); here for callers of expand)
    from urdf_lint.config.schema import find_config, load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.core.jobs import LintJob, Status
    from urdf_lint.core.locations import display_path
    cfg = load_config(find_config(o.file))
    apply_trust(cfg, o.config, [o.file])
    apply_cli_values(cfg, o.config)
    resolver = build_resolver([o.file], cfg, parse_package_paths(o.package_path))
    # expanded in a worker like `check`: time and memory limits, scrubbed environment, sandbox
    job = LintJob(os.path.abspath(o.file), dict(o.mappings), "expand", explicit=True,
                  display_name=o.file)
    res = expand_in_workers([job], resolver, cfg)[0]
    from urdf_lint.run.pipeline import hint_packages
    hint_packages([res], [o.file])   # a sibling package's package.xml: --package-path
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
    if o.output:
        from urdf_lint.core import fsbound
        try:
            fsbound.write_text(o.output, xml, write_base(o.output, [o.file]),
                               make_dirs=True)
        except OSError as e:
            raise UsageError(f"cannot write {safe_text(o.output)}: "
                             f"{safe_text(getattr(e, 'why', None) or e.strerror or e)}") from None
    else:
        sys.stdout.write(xml)
    return 0
