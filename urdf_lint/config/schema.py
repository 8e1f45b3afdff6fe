"""The configuration schema: ``[tool.urdf-lint]`` in pyproject.toml, ``urdf-lint.toml``, and the
command line, all validated by the same table.

:data:`SCHEMA` lists every key with its type, default and help. A config file and the CLI are two
sources of values for the same keys; every value goes through its key's type, so a bad value is
one :class:`ConfigError` (exit 2) naming the key, the value and what was expected. Rule options
(``[tool.urdf-lint.rule-options.UL307]``) are typed from each rule's ``OPTIONS`` defaults: a
float default accepts any number, an int default an integer, and a rule may declare other
types with ``OPTION_TYPES = {"name": (int, float)}``.
"""
from __future__ import annotations

import copy
import fnmatch
import json
import os
import re
from dataclasses import dataclass, field, make_dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Mapping

from urdf_lint.config.policy import code_matches
from urdf_lint.core.suggest import close_matches, did_you_mean

from urdf_lint.core.jobs import DEFAULT_ENV_ALLOW as DEFAULT_ENV_ALLOW  # noqa: E402 - a run's setting; config shows it
from urdf_lint.core.jobs import DEFAULT_MEMORY_MB, DEFAULT_TIMEOUT  # noqa: E402 - the workers' limits

TABLE = "tool.urdf-lint"
SEVERITY_NAMES = ("error", "warning", "info")
FAIL_ON = ("error", "warning", "info", "never")


class ConfigError(Exception):
    pass


class _Bad(Exception):
    """A value does not fit its type; ``expected`` says what would have."""

    def __init__(self, expected: str, value: Any = None, where: str = ""):
        super().__init__(expected)
        self.expected, self.value, self.where = expected, value, where


def show(value: Any) -> str:
    """A value as the user wrote it in TOML (strings in double quotes)."""
    try:
        return json.dumps(value, ensure_ascii=False)
    except (TypeError, ValueError):
        return repr(value)


# -- value types ------------------------------------------------------------------------------
class Type:
    expected = "a value"
    annotation = "Any"      # the Config field's type (its default None adds "| None")

    def check(self, v: Any) -> Any:
        raise NotImplementedError

    def from_cli(self, s: str) -> Any:
        """The value of a command-line string (then checked like a config value)."""
        return s


class Str(Type):
    expected = "a string"
    annotation = "str"

    def check(self, v: Any) -> Any:
        if not isinstance(v, str):
            raise _Bad(self.expected)
        return v


class StrList(Type):
    annotation = "list[str]"

    def __init__(self, what: str = "strings"):
        self.expected = f"a list of {what}"

    def check(self, v: Any) -> Any:
        if isinstance(v, str):
            raise _Bad(f"{self.expected}, like [{show(v)}]")
        if not isinstance(v, list) or not all(isinstance(x, str) for x in v):
            raise _Bad(self.expected)
        return list(v)

    def from_cli(self, s: str) -> Any:
        return [c.strip() for c in s.split(",") if c.strip()]


class Choice(Type):
    annotation = "str"

    def __init__(self, choices: tuple[str, ...] | Callable[[], tuple[str, ...]]):
        self._choices = choices

    @property
    def choices(self) -> tuple[Any, ...]:
        return tuple(self._choices() if callable(self._choices) else self._choices)

    @property
    def expected(self) -> str:  # type: ignore[override]  # (computed: the choices may be lazy)
        return "one of " + ", ".join(self.choices)

    def check(self, v: Any) -> Any:
        if not isinstance(v, str) or v not in self.choices:
            close = close_matches(v, self.choices, n=1, cutoff=0.6) \
                if isinstance(v, str) else []
            raise _Bad(self.expected + (f"; did you mean {show(close[0])}?" if close else ""))
        return v


class ChoiceList(StrList):
    """A non-empty list of values from ``choices`` (each as :class:`Choice` checks it)."""

    def __init__(self, choices: tuple[Any, ...], what: str):
        super().__init__(what)
        self.choice = Choice(choices)
        self.expected = f"a list of {what} ({', '.join(choices)})"

    def check(self, v: Any) -> Any:
        v = super().check(v)
        if not v:
            raise _Bad(f"{self.expected}, not empty")
        for x in v:
            try:
                self.choice.check(x)
            except _Bad as e:
                raise _Bad(f"{self.expected}: {show(x)} is not {e.expected}") from None
        return list(dict.fromkeys(v))


class Number(Type):
    """A number (int or float; booleans are not numbers) above ``minimum``."""

    def __init__(self, kind: type = float, minimum: float | None = None, unit: str = ""):
        self.kind, self.minimum = kind, minimum
        self.annotation = "int" if kind is int else "float"
        noun = "an integer" if kind is int else "a number"
        self.expected = noun + (f" of {unit}" if unit else "") + \
            (f" > {minimum:g}" if minimum is not None else "")

    def check(self, v: Any) -> Any:
        ok_types = (int,) if self.kind is int else (int, float)
        if isinstance(v, bool) or not isinstance(v, ok_types):
            raise _Bad(self.expected)
        if self.minimum is not None and not v > self.minimum:
            raise _Bad(self.expected)
        return self.kind(v)

    def from_cli(self, s: str) -> Any:
        try:
            return int(s) if self.kind is int else float(s)
        except ValueError:
            raise _Bad(self.expected) from None


class Bool(Type):
    expected = "true or false"
    annotation = "bool"

    def check(self, v: Any) -> Any:
        if not isinstance(v, bool):
            raise _Bad(self.expected)
        return v

    def from_cli(self, s: str) -> Any:
        if s.lower() in ("true", "false"):
            return s.lower() == "true"
        raise _Bad(self.expected)


class Table(Type):
    """A table of string keys to values of one type."""
    annotation = "dict[str, Any]"

    def __init__(self, value: Type, what: str):
        self.value, self.expected = value, what

    def check(self, v: Any) -> Any:
        if not isinstance(v, dict):
            raise _Bad(self.expected)
        out = {}
        for k, x in v.items():
            try:
                out[k] = self.value.check(x)
            except _Bad as e:
                raise _Bad(e.expected, x, k) from None
        return out


class ArgValues(Table):
    """``explore-args``: arg -> the values exploration may give it (``[]``: never changed).
    On the command line ``NAME=V1|V2`` (``NAME=``: never changed), repeatable."""

    def __init__(self) -> None:
        super().__init__(StrList("values"), 'a table of arg = ["value", ...] ([]: never '
                                            'changed)')

    def from_cli(self, s: str) -> Any:
        out: dict[str, list[str]] = {}
        for part in s.split(","):
            name, eq, values = part.partition("=")
            if not eq or not name.strip():
                raise _Bad("NAME=V1|V2 (NAME=: never changed)")
            out[name.strip()] = [v for v in values.split("|") if v]
        return out


class Models(Type):
    expected = "an array of tables [[models]] with 'path' and optional 'args'"
    annotation = "list[Any]"

    def check(self, v: Any) -> Any:
        if not isinstance(v, list):
            raise _Bad(self.expected)
        out = []
        for m in v:
            if not isinstance(m, dict) or not isinstance(m.get("path"), str):
                raise _Bad("each [[models]] entry to have a string 'path'", m)
            fields = ("path", "args", "output", "mesh-base", "srdf", "controllers", "joint-limits",
                      "explore", "explore-args")
            extra = set(m) - set(fields)
            if extra:
                raise _Bad("only 'path', 'args', 'output', 'mesh-base', 'srdf', 'controllers', "
                           "'joint-limits', 'explore' and 'explore-args' in a [[models]] entry"
                           + did_you_mean(sorted(extra)[0], fields), m)
            if not isinstance(m.get("explore", True), bool):
                raise _Bad("'explore' to be true or false", m)
            try:
                explore_args = ArgValues().check(m.get("explore-args", {}))
            except _Bad as e:
                raise _Bad(f"'explore-args' to be {e.expected}", m) from None
            for k in ("output", "mesh-base", "srdf", "joint-limits"):
                if k in m and (not isinstance(m[k], str) or not m[k]):
                    raise _Bad(f"'{k}' to be a path", m)
            ctl = m.get("controllers", [])
            ctl = [ctl] if isinstance(ctl, str) else ctl
            if not isinstance(ctl, list) or not all(isinstance(c, str) and c for c in ctl):
                raise _Bad("'controllers' to be a path or a list of paths", m)
            args = m.get("args", [{}])
            if isinstance(args, dict):
                args = [args]
            if not isinstance(args, list) or not all(
                    isinstance(a, dict) and all(isinstance(x, (str, int, float, bool)) for x in a.values())
                    for a in args):
                raise _Bad("'args' to be a table (or a list of tables) of xacro arg = value", args)
            out.append({"path": m["path"], "args": [{k: str(x) for k, x in a.items()} for a in args],
                        "output": m.get("output"), "mesh-base": m.get("mesh-base"),
                        "srdf": m.get("srdf"), "controllers": ctl,
                        "joint-limits": m.get("joint-limits"), "explore": m.get("explore"),
                        "explore-args": explore_args})
        return out


class RuleOptions(Type):
    expected = "a table of tables: [rule-options.CODE] option = value"
    annotation = "dict[str, Any]"

    def check(self, v: Any) -> Any:
        if not isinstance(v, dict) or not all(isinstance(x, dict) for x in v.values()):
            raise _Bad(self.expected)
        return {k: dict(x) for k, x in v.items()}


class FormatKey(Type):
    """``format``: the table ``[format]`` of ``urdf-lint format`` (its keys in
    :data:`FORMAT_SCHEMA`). A string is the output format's old spelling (now
    ``output-format``): still accepted, with a deprecation note (:func:`_set`)."""

    annotation = "dict[str, Any]"

    def __init__(self, output: Choice):
        self.output = output

    @property
    def expected(self) -> str:  # type: ignore[override]  # (computed from the format keys)
        return (f"a table [format] of {', '.join(k.name for k in FORMAT_SCHEMA)} (a string: "
                f"the deprecated spelling of output-format)")

    def check(self, v: Any) -> Any:
        if not isinstance(v, dict):
            return self.output.check(v)
        out = {}
        for k, x in v.items():
            key = FORMAT_KEYS.get(k)
            if key is None:
                raise _Bad(f"one of {', '.join(FORMAT_KEYS)} in [format]"
                           f"{did_you_mean(str(k), FORMAT_KEYS)}", x, k)
            try:
                out[k] = key.type.check(x)
            except _Bad as e:
                raise _Bad(e.expected, x, k) from None
        return out


@dataclass(frozen=True)
class Flag:
    """How a key is given on the command line. The CLI adds the flags of a ``group`` together
    (:func:`urdf_lint.cli.common.add_key_flags`): a key with a flag is on every command that
    takes its group, and its value goes through :func:`apply_cli`."""
    flags: tuple[str, ...]          # ("-j", "--jobs")
    group: str                      # selection, jobs, trust, limits, cache, views, output, baseline
    metavar: str = ""               # (default: a Choice's {a,b,c})
    help: str = ""                  # (default: the key's help)
    repeat: bool = False            # --env-allow A --env-allow B (also comma-separated)
    path: bool = False              # a path, made absolute where the user typed it
    dest: str = ""                  # (default: the key's attribute)

    def shown(self, name: str) -> str:
        """The flag as an error message names it: ``--name``, with its aliases when the key's
        own name is one of them (``--output-format/--format``)."""
        longs = [f for f in self.flags if f.startswith("--")]
        return "/".join(longs) if f"--{name}" in longs else f"--{name}"


@dataclass(frozen=True)
class Trust:
    """What a repository's own config may do with a key (:mod:`urdf_lint.config.trust`).

    ``rule``: ``ignore`` (the repository's value is dropped, with ``why`` in the note),
    ``at-most-default`` (may only tighten the default; ``unit`` after the value in the note),
    ``inside-repo`` (table entries pointing outside the repository are dropped), ``confine``
    (a path, or the ``fields`` of each entry, must stay inside the repository, else a config
    error). ``loosens``: how ``--trust-config``'s help names what it lets the config do."""
    rule: str
    loosens: str = ""
    why: str = ""
    unit: str = ""
    fields: tuple[str, ...] = ()


TRUST_RULES = ("ignore", "at-most-default", "inside-repo", "confine")


@dataclass(frozen=True)
class Key:
    """One configuration key: its name, type, default and help; how the command line sets it
    (``flag``), what a repository's own config may do with it (``trust``) and the range a
    number is clamped to wherever it came from (``clamp``)."""
    name: str
    type: Type
    default: Any
    help: str
    cli_merge: str = "replace"      # "replace" or "extend" when given on the command line
    flag: Flag | None = None
    trust: Trust | None = None
    clamp: tuple[float, float] | None = None      # (low, high)
    shown_default: str = ""         # what None means, for the help and docs/configuration.md
    attr_name: str = ""             # the Config attribute (default: the name, with underscores)

    def __post_init__(self) -> None:
        """A trust rule that cannot hold for the key's default is the schema's mistake: said
        when the schema is loaded, not as an internal error once a repository sets the key."""
        rule = self.trust.rule if self.trust is not None else None
        if rule is not None and rule not in TRUST_RULES:
            raise ValueError(f"config key {self.name!r}: unknown trust rule {rule!r} "
                             f"(one of {', '.join(TRUST_RULES)})")
        number = isinstance(self.default, (int, float)) and not isinstance(self.default, bool)
        if rule == "at-most-default" and not number:
            raise TypeError(f"config key {self.name!r}: trust 'at-most-default' compares with a "
                            f"number default, and the default is {self.default!r} (use "
                            "'ignore' for a key a repository may not set)")
        if rule == "inside-repo" and not isinstance(self.default, dict):
            raise TypeError(f"config key {self.name!r}: trust 'inside-repo' checks a table of "
                            f"paths, and the default is {self.default!r}")

    @property
    def attr(self) -> str:
        return self.attr_name or self.name.replace("-", "_")

    @property
    def annotation(self) -> str:
        """The type of its :class:`Config` field: its value type's, ``| None`` when the
        default is None."""
        return self.type.annotation + (" | None" if self.default is None else "")

    @property
    def default_text(self) -> str:
        d = self.default
        if d is None:
            return self.shown_default or "none"
        if isinstance(d, list):
            return ",".join(d) if d else "none"
        if isinstance(d, float) and d.is_integer():
            return str(int(d))
        return str(d) if not isinstance(d, dict) else "none"

    def cli_help(self) -> str:
        """The flag's help: what it does, the default and the config key."""
        text = (self.flag.help if self.flag else "") or self.help
        return f"{text} (default: {self.default_text}; config key '{self.name}')"

    def metavar(self) -> str:
        if self.flag and self.flag.metavar:
            return self.flag.metavar
        t = self.type
        return "{" + ",".join(t.choices) + "}" if isinstance(t, Choice) else self.name.upper()


def _targets() -> tuple[Any, ...]:
    from urdf_lint.core.targets import NAMES
    return NAMES


def _formats() -> tuple[Any, ...]:
    from urdf_lint.report.registry import names
    return names()


_SEVERITIES = "{" + ",".join(FAIL_ON) + "}"
SCHEMA: tuple[Key, ...] = (
    Key("select", StrList("rule codes or prefixes"), ["UL"],
        'rule codes, prefixes or names to enable ("ALL" for every rule)',
        flag=Flag(("--select",), "selection", "CODES", "comma-separated rule codes, prefixes "
                  "or names to enable; replaces the config's")),
    Key("extend-select", StrList("rule codes or prefixes"), [],
        "codes or prefixes to enable on top of select", cli_merge="extend",
        flag=Flag(("--extend-select",), "selection", "CODES",
                  "comma-separated codes or prefixes to enable on top of select")),
    Key("ignore", StrList("rule codes or prefixes"), [],
        "codes or prefixes to disable", cli_merge="extend",
        flag=Flag(("--ignore",), "selection", "CODES",
                  "comma-separated codes or prefixes to disable")),
    Key("per-file-ignores", Table(StrList("rule codes or prefixes"),
                                  'a table of glob = ["CODE", ...]'), {},
        "codes to ignore in files matching a glob"),
    Key("severity", Table(Choice(SEVERITY_NAMES), "a table of CODE = error|warning|info"), {},
        "override default severities"),
    Key("fail-on", Choice(FAIL_ON), "error",
        "lowest severity that makes the exit code 1",
        flag=Flag(("--fail-on",), "selection")),
    Key("targets", ChoiceList(_targets(), "consumer targets"), ["ros"],
        "the programs the descriptions are for; a finding takes the highest severity any of "
        "them gives it (see 'urdf-lint rules')",
        flag=Flag(("--target",), "selection", "TARGET", "a consumer the descriptions are for ("
                  + ", ".join(_targets()) + "); repeatable or comma-separated, replaces the "
                  "config's", repeat=True, dest="targets")),
    Key("package-paths", Table(Str(), 'a table of package = "folder"'), {},
        "where packages that have no package.xml under the linted paths are",
        trust=Trust("inside-repo", "package-paths outside it")),
    Key("models", Models(), [], "entry models and the xacro args to expand them with",
        trust=Trust("confine", fields=("output", "mesh-base", "srdf", "controllers",
                                               "joint-limits"))),
    Key("exclude", StrList("globs"), [], "paths (globs) not to lint"),
    Key("env-allow", StrList("environment variable names"), [],
        "environment variables $(env)/$(optenv) may read", cli_merge="extend",
        flag=Flag(("--env-allow",), "trust", "VAR",
                  "an environment variable $(env)/$(optenv) may read; repeatable", repeat=True),
        trust=Trust("ignore", "env-allow", "it lets descriptions read environment variables")),
    Key("timeout", Number(float, 0, "seconds"), DEFAULT_TIMEOUT, "time limit per model, in seconds",
        flag=Flag(("--timeout",), "limits", "SECONDS"),
        trust=Trust("at-most-default", "looser timeout", unit="s"), clamp=(0.5, 600.0)),
    Key("memory-mb", Number(int, 0, "MiB"), DEFAULT_MEMORY_MB, "memory limit per model, in MiB",
        flag=Flag(("--memory-mb",), "limits", "MIB"),
        trust=Trust("at-most-default", "looser memory-mb", unit="MiB"), clamp=(128, 65536)),
    Key("rule-options", RuleOptions(), {}, "options of single rules"),
    Key("jobs", Number(int, 0), None, "parallel workers",
        flag=Flag(("-j", "--jobs"), "jobs", "N"),
        trust=Trust("ignore", "jobs", "it sets how many processes a run starts"), clamp=(1, 64),
        shown_default="from the work, at most all cores"),
    Key("cache-dir", Str(), None, "folder of the result cache",
        flag=Flag(("--cache-dir",), "cache", "DIR", path=True),
        trust=Trust("ignore", "cache-dir", "it moves where results are written and read"),
        shown_default=".urdf_lint_cache"),
    Key("output-format", Choice(_formats), None,
        "output format (see 'urdf-lint check --help')",
        flag=Flag(("--output-format", "--format"), "output", "FORMAT",
                  "output format: one of the formats listed below"),
        shown_default="text, or github on GitHub Actions"),
    Key("format", FormatKey(Choice(_formats)), {},
        "the settings of urdf-lint format, as the table [tool.urdf-lint.format] "
        "(see docs/formatter.md)",
        attr_name="format_options"),
    Key("baseline", Str(), None, "ignore the findings recorded in this file",
        flag=Flag(("--baseline",), "baseline", "FILE", "ignore the findings recorded in FILE "
                  "(make it with --write-baseline)", path=True),
        trust=Trust("confine")),
    Key("discover", Bool(), True, "false: lint only the models listed under [[models]]"),
    Key("explore", Bool(), True,
        "lint the variants that take the xacro:if/unless branches and arg-chosen files the "
        "default args leave out (docs/coverage.md)",
        flag=Flag(("--explore",), "explore", "{true,false}")),
    Key("explore-budget", Number(float, 0, "times the models"), 1.0,
        "the variants explored in a run, at most this many times the models linted",
        flag=Flag(("--explore-budget",), "explore", "N"),
        trust=Trust("at-most-default", "larger explore-budget"), clamp=(0.0, 20.0)),
    Key("explore-args", ArgValues(), {},
        "the values exploration may give an arg; [] keeps the arg at its default",
        cli_merge="replace",
        flag=Flag(("--explore-arg",), "explore", "NAME=V1|V2",
                  "the values exploration may give arg NAME (NAME=: never changed); "
                  "repeatable", repeat=True)),
    Key("explore-exclude", StrList("globs"), [], "models (globs) not explored",
        flag=Flag(("--explore-exclude",), "explore", "GLOB",
                  "a model (glob) not explored; repeatable", repeat=True)),
    Key("views", Choice(("single", "sheet")), None,
        "snapshot pictures: one 3/4 view, or a 2x2 sheet of front, side, top and 3/4 views",
        flag=Flag(("--views",), "views"), shown_default="single for render, sheet for diff"),
    Key("forward-axis", Choice(("+x", "-x", "+y", "-y")), "+x",
        "the robot's forward axis in its base frame, for the snapshot views",
        flag=Flag(("--forward-axis",), "views", "",
                  "the robot's forward axis, for the front/side views")),
)
KEYS = {k.name: k for k in SCHEMA}

# [tool.urdf-lint.format]: the settings of `urdf-lint format` (urdf_lint/formatting/layout.py)
FORMAT_SCHEMA: tuple[Key, ...] = (
    Key("indent", Number(int, 0, "spaces"), 2, "spaces per level of nesting"),
    Key("line-length", Number(int, 0, "characters"), 100,
        "a start tag longer than this gets one attribute per line"),
    Key("attribute-order", Choice(("keep", "canonical")), "keep",
        "keep: attributes as written; canonical: name first, then the URDF/xacro schema order"),
    Key("self-closing", Choice(("auto", "compact", "spaced")), "auto",
        "how an empty element is closed: compact <a/>, spaced <a />, auto: as most of the "
        "file's self-closed tags are"),
    Key("exclude", StrList("globs"), [], "paths (globs) not to format, on top of exclude"),
)
FORMAT_KEYS = {k.name: k for k in FORMAT_SCHEMA}


@dataclass
class ModelSpec:
    """A ``[[models]]`` entry: the file, its argument sets, and where its output and meshes are."""
    path: str                       # absolute
    arg_sets: list[Any]             # list of dicts
    output: str | None = None       # absolute: the generated URDF written from this xacro
    mesh_base: str | None = None    # absolute: where relative mesh paths start
    # per arg set, where this config file sets each arg ({name: (file, line, col)}): a value
    # that comes from a passed arg is located there (:mod:`urdf_lint.config.places`)
    arg_places: list[dict[str, tuple[str, int, int]]] = field(default_factory=list)
    srdf: str | None = None         # absolute: the SRDF (or .srdf.xacro) of this robot
    controllers: list[str] = field(default_factory=list)  # absolute: its controller YAML
    joint_limits: str | None = None  # absolute: MoveIt's joint_limits.yaml for it
    # branch exploration of this model (docs/coverage.md): False: none; None: as the config
    explore: bool | None = None
    explore_args: dict[str, list[str]] = field(default_factory=dict)   # over explore-args


def _default(name: str) -> Any:
    """A Config field's default: the schema key's (a fresh copy per Config)."""
    key = KEYS[name]
    return field(default_factory=lambda: copy.deepcopy(key.default))


class _ConfigMethods:
    """What a :class:`Config` does; its fields are :data:`SCHEMA`'s (:func:`config_class`)."""
    root: str
    exclude: list[str]
    rule_options: dict[str, Any]

    def is_excluded(self, path: str) -> bool:
        try:
            rel = os.path.relpath(path, self.root)
        except ValueError:
            rel = path
        return any(fnmatch.fnmatch(rel, p) or fnmatch.fnmatch(rel, p.rstrip("/") + "/*")
                   for p in self.exclude)

    def options_for(self, code: str, name: str) -> dict[str, Any]:
        out = {}
        out.update(self.rule_options.get(name, {}))
        out.update(self.rule_options.get(code, {}))
        return out


# The fields of a Config that are not config keys, (name, type, default) before and after the
# schema's: where it came from, the folder paths are relative to; the raw table and the notes
# to say once loaded (deprecations). A default of dict or list is a fresh one per Config.
OWN_FIELDS_FIRST: tuple[tuple[str, str, Any], ...] = (("path", "str | None", None),
                                                      ("root", "str", "."))
OWN_FIELDS_LAST: tuple[tuple[str, str, Any], ...] = (("raw", "dict[str, Any]", dict),
                                                     ("notes", "list[Any]", list))
CONFIG_DOC = """The settings of a run, from the config file and the command line: one field per
    schema key (its attribute, type and default from :data:`SCHEMA`), plus where it came from
    (``path``, ``root``), the raw table and the notes to say once loaded."""


def config_class(schema: tuple[Key, ...] = SCHEMA) -> type:
    """The :class:`Config` dataclass of ``schema``: one field per key, its default a fresh
    copy of the key's. Adding a key to :data:`SCHEMA` adds its field; mypy and editors see the
    fields in the block that ``scripts/gen_types.py`` writes below from the same schema."""
    def own(default: Any) -> Any:
        return field(default_factory=default) if default in (dict, list) else default

    def default(key: Key) -> Any:
        return field(default_factory=lambda: copy.deepcopy(key.default))
    fields = [(n, t, own(d)) for n, t, d in OWN_FIELDS_FIRST] + \
        [(k.attr, k.annotation, default(k)) for k in schema] + \
        [(n, t, own(d)) for n, t, d in OWN_FIELDS_LAST]
    cls = make_dataclass("Config", fields, bases=(_ConfigMethods,))
    cls.__module__, cls.__doc__ = __name__, CONFIG_DOC
    return cls


if TYPE_CHECKING:
    # generated: config (scripts/gen_types.py, from SCHEMA: edit the schema, not this)
    @dataclass
    class Config(_ConfigMethods):
        """The settings of a run, from the config file and the command line: one field per
        schema key (its attribute, type and default from :data:`SCHEMA`), plus where it came from
        (``path``, ``root``), the raw table and the notes to say once loaded."""
        path: str | None = None
        root: str = "."
        select: list[str] = _default("select")
        extend_select: list[str] = _default("extend-select")
        ignore: list[str] = _default("ignore")
        per_file_ignores: dict[str, Any] = _default("per-file-ignores")
        severity: dict[str, Any] = _default("severity")
        fail_on: str = _default("fail-on")
        targets: list[str] = _default("targets")
        package_paths: dict[str, Any] = _default("package-paths")
        models: list[Any] = _default("models")
        exclude: list[str] = _default("exclude")
        env_allow: list[str] = _default("env-allow")
        timeout: float = _default("timeout")
        memory_mb: int = _default("memory-mb")
        rule_options: dict[str, Any] = _default("rule-options")
        jobs: int | None = _default("jobs")
        cache_dir: str | None = _default("cache-dir")
        output_format: str | None = _default("output-format")
        format_options: dict[str, Any] = _default("format")
        baseline: str | None = _default("baseline")
        discover: bool = _default("discover")
        explore: bool = _default("explore")
        explore_budget: float = _default("explore-budget")
        explore_args: dict[str, Any] = _default("explore-args")
        explore_exclude: list[str] = _default("explore-exclude")
        views: str | None = _default("views")
        forward_axis: str = _default("forward-axis")
        raw: dict[str, Any] = field(default_factory=dict)
        notes: list[Any] = field(default_factory=list)
    # end: config
else:
    Config = config_class()


# -- reading files ----------------------------------------------------------------------------
def _arg_places(cfg: Config, entry: int, arg_sets: list[Any], text: str | None
                ) -> list[dict[str, Any]]:
    """Where the config file (its ``text``, as read to load it) sets each arg of the
    ``entry``-th ``[[models]]`` entry."""
    from urdf_lint.config.places import arg_places
    if not cfg.path or text is None:
        return [{} for _ in arg_sets]
    return arg_places(os.path.abspath(cfg.path), text, entry, arg_sets)


def _read_config(path: Path) -> str:
    """The text of a config file: a regular file (never a FIFO or device), bounded."""
    from urdf_lint.core import fsbound
    return fsbound.read_text(path, max_bytes=fsbound.MAX_CONFIG_BYTES)


def _parse_toml(path: Path) -> dict[str, Any]:
    return _read_toml(path)[1]


def _read_toml(path: Path) -> tuple[str, dict[str, Any]]:
    """(the text of a config file, its TOML data), read once."""
    try:
        text = _read_config(path)
    except UnicodeDecodeError as e:
        raise ConfigError(f"{_shown(path)}: cannot read config: {e}") from None
    except OSError as e:
        from urdf_lint.core.escape import escape_text
        why = getattr(e, "why", None) or e.strerror or e
        raise ConfigError(f"{_shown(path)}: cannot read config: {escape_text(str(why))}") from None
    # (tomllib, with datetime, ~4 ms to import: only a run that reads a TOML file needs it)
    try:
        import tomllib
    except ImportError:  # pragma: no cover - Python 3.10
        import tomli as tomllib
    try:
        data: dict[str, Any] = tomllib.loads(text)
        return text, data
    except RecursionError:   # 50,000 nested arrays or tables: tomllib recurses per level
        raise ConfigError(f"{_shown(path)}: invalid TOML: nested too deeply") from None
    except tomllib.TOMLDecodeError as e:
        msg = str(e)
        m = re.search(r"\s*\(at line (\d+), column (\d+)\)$", msg)
        if m:
            msg = msg[:m.start()]
            raise ConfigError(f"{_shown(path)}:{m.group(1)}:{m.group(2)}: invalid TOML: {msg}") from None
        m = re.search(r"\s*\(at end of document\)$", msg)
        if m:
            line = text.count("\n") + 1
            raise ConfigError(f"{_shown(path)}:{line}: invalid TOML: {msg[:m.start()]} "
                              "(at end of file)") from None
        raise ConfigError(f"{_shown(path)}: invalid TOML: {msg}") from None


def _near_miss_table(tool: dict[str, Any]) -> str | None:
    """A ``[tool.X]`` that was meant to be ``[tool.urdf-lint]``."""
    for k in tool:
        if not isinstance(k, str) or k == "urdf-lint":
            continue
        norm = re.sub(r"[-_. ]", "", k.lower())
        if norm in ("urdflint", "urdflinter") or close_matches(
                k.lower(), ["urdf-lint"], n=1, cutoff=0.8):
            return k
    return None


def _pyproject_table(path: Path, data: dict[str, Any]) -> dict[str, Any] | None:
    tool = data.get("tool", {})
    if not isinstance(tool, dict):
        return None
    if "urdf-lint" in tool:
        table: dict[str, Any] | None = tool["urdf-lint"]   # (its type is checked by the caller)
        return table
    near = _near_miss_table(tool)
    if near is not None:
        raise ConfigError(f"{_shown(path)}: found [tool.{near}]; did you mean [{TABLE}]? "
                          f"(the table is named [{TABLE}], with a hyphen)")
    return None


def find_config(start: str) -> Path | None:
    p = Path(start).resolve()
    if p.is_file():
        p = p.parent
    for d in [p, *p.parents]:
        for fname in ("urdf-lint.toml", ".urdf-lint.toml"):
            if _found(d / fname):
                return d / fname
        pp = d / "pyproject.toml"
        if _found(pp) and _pyproject_table(pp, _parse_toml(pp)) is not None:
            return pp
    return None


def _found(path: Path) -> bool:
    """Is there a config file at ``path``? One found by looking up from the linted paths is
    never read through a symlink leading out of its folder (a committed ``pyproject.toml``
    pointing at a file elsewhere on the machine): that is a config error, before any read
    (``--config FILE`` names a file to read wherever it is)."""
    if not path.is_file():
        return False
    from urdf_lint.core import fsbound
    if not fsbound.within(path, [path.parent]):
        raise ConfigError(f"{_shown(path)} is a symlink leading out of its folder; it was not "
                          "read (name the file with --config to use it)")
    return True


def named_files(path: str | Path) -> list[str]:
    """The files a config file names (each ``[[models]]`` entry's ``path`` and ``output``),
    absolute, read without validating it: ``diff`` materialises them at the base revision
    before that revision's config is loaded (and validated against them). [] when the file
    cannot be read."""
    path = Path(path)
    try:
        data: Any = _parse_toml(path)
        if path.name == "pyproject.toml":
            data = _pyproject_table(path, data)
    except ConfigError:
        return []
    models = data.get("models") if isinstance(data, dict) else None
    return [os.path.normpath(os.path.join(path.parent, m[k]))
            for m in (models if isinstance(models, list) else []) if isinstance(m, dict)
            for k in ("path", "output") if isinstance(m.get(k), str)]


def _shown(path: str | Path) -> str:
    """A config file's path as messages show it: relative to the working directory when below."""
    if isinstance(path, str) and not os.path.exists(path):
        return path                      # "command line"
    from urdf_lint.core.locations import display_path
    return display_path(os.path.abspath(path))


def _line_of(path: Path, key: str) -> str:
    """``:LINE`` of the first ``key = ...`` in the file, when it can be found."""
    try:
        lines = _read_config(path).splitlines()
    except (OSError, UnicodeDecodeError):
        return ""
    pat = re.compile(r'^\s*(?:"|\')?' + re.escape(key) + r'(?:"|\')?\s*=')
    header = re.compile(r'^\s*\[[^\]]*[."\']' + re.escape(key) + r'["\']?\s*\]')
    ours = path.name != "pyproject.toml"   # in pyproject.toml, only [tool.urdf-lint...] tables
    for i, ln in enumerate(lines, 1):
        if ln.lstrip().startswith("["):
            ours = path.name != "pyproject.toml" or ln.lstrip().lstrip("[").startswith(TABLE)
            if ours and header.match(ln):
                return f":{i}"
        elif ours and pat.match(ln):
            return f":{i}"
    return ""


# -- validation -------------------------------------------------------------------------------
def _set(cfg: Config, key: Key, value: Any, base: Path, text: str | None = None) -> None:
    if key.name == "package-paths":
        value = {k: str((base / v).resolve()) for k, v in value.items()}
    elif key.name == "models":
        specs = []
        for n, m in enumerate(value):
            spec = ModelSpec(path=str((base / m["path"]).resolve()), arg_sets=m["args"],
                             arg_places=_arg_places(cfg, n, m["args"], text),
                             explore=m.get("explore"), explore_args=m.get("explore-args") or {})
            for k in ("output", "mesh-base", "srdf", "joint-limits"):
                if m.get(k):
                    setattr(spec, k.replace("-", "_"), str((base / m[k]).resolve()))
            spec.controllers = [str((base / c).resolve()) for c in m.get("controllers") or ()]
            if not os.path.isfile(spec.path):
                raise ConfigError(f"{_shown(cfg.path or base)}: [[models]] model {m['path']!r} does not exist"
                                  f"{_did_you_mean_file(m['path'], base)}")
            specs.append(spec)
        value = specs
    elif key.name == "baseline" and value is not None:
        value = str((base / value).resolve())
    elif key.name == "format" and isinstance(value, str):   # the old output-format key
        where = f"{_shown(cfg.path or base)}{_line_of(Path(cfg.path), 'format') if cfg.path else ''}"
        cfg.notes.append(f"note: {where}: format = {show(value)} is deprecated: write "
                         f"output-format = {show(value)} ([{TABLE}.format] is the table of "
                         "urdf-lint format's settings)")
        if "output-format" not in cfg.raw:
            cfg.output_format = value
        return
    setattr(cfg, key.attr, value)


def load_config(path: str | Path | None, known_codes: dict[str, Any] | None = None,
                rules: "Callable[[], Mapping[str, Any]] | None" = None) -> Config:
    """Load and validate. ``known_codes`` maps code -> name for checking codes; ``rules()``
    gives code -> rule (its options) for checking ``rule-options`` (the caller knows the rules:
    the config room is below the engine's)."""
    if path is None:
        return Config(root=os.getcwd())
    path = Path(path)
    text, data = _read_toml(path)
    table = "[tool.urdf-lint]"
    if path.name == "pyproject.toml":
        data = _pyproject_table(path, data) or {}
    else:
        table = path.name
        if "tool" in data and isinstance(data["tool"], dict) and (
                "urdf-lint" in data["tool"] or _near_miss_table(data["tool"])):
            raise ConfigError(f"{_shown(path)}: in {path.name} the keys go at the top level, "
                              f"without a [{TABLE}] table")
    if not isinstance(data, dict):
        raise ConfigError(f"{_shown(path)}: [{TABLE}] must be a table")
    cfg = Config(path=str(path), root=str(path.parent.resolve()), raw=data)
    for k in data:
        if k not in KEYS:
            raise ConfigError(f"{_shown(path)}{_line_of(path, k)}: unknown key {k!r} in {table}"
                              f"{did_you_mean(k, KEYS)} (known: {', '.join(sorted(KEYS))})")
    for k, v in data.items():
        key = KEYS[k]
        try:
            value = key.type.check(v)
        except _Bad as e:
            shown = show(v if e.value is None else e.value)
            inner = k
            if e.where:
                bare = re.fullmatch(r"[A-Za-z0-9_-]+", e.where)
                inner += "." + (e.where if bare else show(e.where))
            line = (_line_of(path, e.where) if e.where else "") or _line_of(path, k)
            raise ConfigError(f"{_shown(path)}{line}: invalid value for {inner}: {shown} "
                              f"(expected {e.expected})") from None
        _set(cfg, key, value, path.parent, text)
    if known_codes is not None:
        validate_codes(cfg, known_codes, str(path), rules)
    return cfg


FLAG_KEYS: tuple[Key, ...] = tuple(k for k in SCHEMA if k.flag is not None)


def trust_config_help() -> str:
    """``--trust-config``'s help, naming what it lets a repository's config do (the keys'
    ``trust`` in the schema; :mod:`urdf_lint.config.trust` applies them)."""
    loosens = [k.trust.loosens for k in SCHEMA if k.trust is not None and k.trust.loosens]
    return (f"let the repository's config set {', '.join(loosens[:-1])} and {loosens[-1]} "
            "(default: off, those keys are ignored with a note)")


def apply_cli(cfg: Config, values: dict[str, Any], source: str = "command line") -> Config:
    """Merge command-line values (strings, as typed) into ``cfg`` through the schema.

    ``values`` maps schema key names to the flag's string (a list of them for a repeatable
    flag), or None when the flag was not given. Keys with ``cli_merge="extend"`` add to the
    configured list; a path flag is made absolute."""
    for name, s in values.items():
        if s is None:
            continue
        key = KEYS[name]
        flag = key.flag or Flag((f"--{name}",), "")
        if flag.repeat and isinstance(s, (list, tuple)):
            s = ",".join(s)
        if flag.path and isinstance(s, str) and s:
            s = os.path.abspath(s)
        try:
            value = key.type.check(key.type.from_cli(s) if isinstance(s, str) else s)
        except _Bad as e:
            raise ConfigError(f"{flag.shown(name)}: invalid value {show(s)} "
                              f"(expected {e.expected})") from None
        if key.cli_merge == "extend":
            value = list(getattr(cfg, key.attr)) + value
        if name == "explore-args":   # the command line's args win over a [[models]] entry's
            for m in cfg.models:
                m.explore_args = {k: v for k, v in m.explore_args.items() if k not in value}
        setattr(cfg, key.attr, value)
    return cfg


def format_option(name: str, s: str) -> Any:
    """The value of a command-line flag of ``urdf-lint format`` (``--line-length``), checked
    by the key's type like the same key under [format]."""
    key = FORMAT_KEYS[name]
    try:
        return key.type.check(key.type.from_cli(s))
    except _Bad as e:
        raise ConfigError(f"--{name}: invalid value {show(s)} (expected {e.expected})") from None


def _did_you_mean_file(rel: str, root: Path) -> str:
    """" (did you mean 'X'?)" for the robot file under ``root`` closest to ``rel``."""
    from urdf_lint.core import fsbound
    from urdf_lint.core.tree import SKIP_DIRS
    files = [os.path.relpath(f, root) for f in fsbound.walk_files(
        root, suffixes=(".xacro", ".urdf"), skip=lambda d: d in SKIP_DIRS or d.startswith("."))]
    best = close_matches(rel, files, n=1, cutoff=0.5) or close_matches(
        os.path.basename(rel), [os.path.basename(f) for f in files], n=1, cutoff=0.5)
    if not best:
        return ""
    hit = best[0] if best[0] in files else next(f for f in files if os.path.basename(f) == best[0])
    return f" (did you mean {hit!r}?)"


def validate_codes(cfg: Config, known: dict[str, Any], where: str = "command line",
                   rules: "Callable[[], Mapping[str, Any]] | None" = None) -> None:
    names = set(known.values())

    def check(p: str, what: str) -> None:
        if p == "ALL" or p in names:
            return
        if not any(code_matches(p, c, n) for c, n in known.items()):
            line = _line_of(Path(where), what) if os.path.isfile(where) else ""
            raise ConfigError(f"{_shown(where)}{line}: unknown rule code or prefix {p!r} in {what}"
                              f"{did_you_mean(p, list(known) + sorted(names))} "
                              f"(see 'urdf-lint rules')")
    for p in cfg.select + cfg.extend_select:
        check(p, "select")
    for p in cfg.ignore:
        check(p, "ignore")
    for codes in cfg.per_file_ignores.values():
        for p in codes:
            check(p, "per-file-ignores")
    for p in cfg.severity:
        check(p, "severity")
    if rules is not None:
        validate_rule_options(cfg, where, rules)


def option_types(rule: Any) -> dict[str, Any]:
    """Option name -> accepted Python types, from the rule's ``OPTIONS`` defaults and its
    optional ``OPTION_TYPES`` declaration."""
    import sys
    declared = dict(getattr(sys.modules.get(rule.module), "OPTION_TYPES", {}) or {})
    out = {}
    for name, default in rule.options.items():
        if name in declared:
            t = declared[name]
            out[name] = tuple(t) if isinstance(t, (tuple, list)) else (t,)
        elif isinstance(default, bool):
            out[name] = (bool,)
        elif isinstance(default, float):
            out[name] = (float, int)
        else:
            out[name] = (type(default),)
    return out


def option_choices(rule: Any) -> dict[str, Any]:
    """Option name -> the values it may take, from the rule's optional ``OPTION_CHOICES``."""
    import sys
    return {k: tuple(v) for k, v in
            (getattr(sys.modules.get(rule.module), "OPTION_CHOICES", {}) or {}).items()}


_TYPE_NAMES = {bool: "true or false", int: "an integer", float: "a number", str: "a string",
               list: "a list"}


def validate_rule_options(cfg: Config, where: str,
                          load_rules: "Callable[[], Mapping[str, Any]]") -> None:
    if not cfg.rule_options:
        return
    rules = load_rules()
    by_name = {r.name: r for r in rules.values()}
    for key, opts in cfg.rule_options.items():
        rule = rules.get(key) or by_name.get(key)
        if rule is None:
            line = _line_of(Path(where), key) if os.path.isfile(where) else ""
            raise ConfigError(f"{_shown(where)}{line}: unknown rule {key!r} in rule-options"
                              f"{did_you_mean(key, list(rules) + list(by_name))} "
                              "(use a rule code like UL307 or its name)")
        types = option_types(rule)
        choices = option_choices(rule)
        for name, value in opts.items():
            line = _line_of(Path(where), name) if os.path.isfile(where) else ""
            if name not in types:
                raise ConfigError(f"{_shown(where)}{line}: unknown option {name!r} in rule-options.{key} "
                                  f"({rule.code} {rule.name})"
                                  f"{did_you_mean(name, types)} (known: "
                                  f"{', '.join(sorted(types)) or 'none'})")
            ok = types[name]
            if isinstance(value, bool) and bool not in ok or not isinstance(value, ok):
                expected = " or ".join(dict.fromkeys(_TYPE_NAMES.get(t, t.__name__) for t in ok))
                if float in ok and int in ok:
                    expected = "a number"
                raise ConfigError(f"{_shown(where)}{line}: invalid value for rule-options.{key}.{name}: "
                                  f"{show(value)} (expected {expected}, like "
                                  f"{show(rule.options[name])})")
            if float in ok and isinstance(value, int) and not isinstance(value, bool):
                opts[name] = float(value)
            allowed = choices.get(name)
            if allowed is not None and value not in allowed:
                raise ConfigError(f"{_shown(where)}{line}: invalid value: rule-options.{key}.{name} "
                                  f"must be one of {', '.join(map(repr, allowed))}, not "
                                  f"{value!r}{did_you_mean(str(value), allowed)}")
