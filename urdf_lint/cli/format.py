"""``urdf-lint format``: lay out xacro and URDF sources (:mod:`urdf_lint.formatting.run`)."""
from __future__ import annotations

from dataclasses import dataclass, field

from urdf_lint.cli.common import ConfigOptions, load_cfg, options_from, parse_package_paths
from urdf_lint.cli.parser import add_inputs


NAME = "format"


def add_parser(sub, raw):
    from urdf_lint.formatting.run import add_parser as add
    add(sub, raw, add_inputs)


@dataclass(frozen=True)
class FormatOptions:
    """What ``format`` was asked to do (the formatter reads these by name)."""
    config: ConfigOptions = field(default_factory=ConfigOptions)
    paths: list = field(default_factory=lambda: ["."])
    package_path: list | None = None
    check: bool = False
    diff: bool = False
    quiet: bool = False
    indent: str | None = None
    line_length: str | None = None
    attribute_order: str | None = None


def run(args) -> int:
    from urdf_lint.formatting.run import cmd_format
    opts = options_from(FormatOptions, args, config=ConfigOptions.from_args(args))
    return cmd_format(opts, lambda o, paths: load_cfg(o.config, paths), parse_package_paths)
