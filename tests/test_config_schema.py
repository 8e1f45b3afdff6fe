"""The config schema (urdf_lint/config/schema.py): every bad value is exit 2 naming the key, the value
and what was expected, in a config file and on the command line alike."""
from __future__ import annotations

import json
import os
import sys
import types

import pytest

from conftest import REPO, make_package

from urdf_lint.cli.main import main
from urdf_lint.config.schema import (KEYS, SCHEMA, Config, ConfigError, find_config, load_config,
                              option_types)
from urdf_lint.engine.registry import codes_to_names, load_rules

URDF = ('<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="continuous">'
        '<parent link="a"/><child link="b"/><axis xyz="0 0 1.01"/></joint></robot>')


@pytest.fixture
def pkg(tmp_path, monkeypatch):
    p = make_package(tmp_path, "p", {"r.urdf": URDF})
    monkeypatch.chdir(p)
    return p


def run(capsys, *args):
    rc = main(list(args))
    out, err = capsys.readouterr()
    return rc, out, err


# the five mistakes reported in issue 9, each with the words the message must carry:
# the key, the value as written, and what was expected
MISTAKES = {
    "tolerance-string": ('[rule-options.UL307]\ntolerance = "abc"\n',
                         ["rule-options.UL307.tolerance", '"abc"', "expected a number"], 2),
    "timeout-string": ('timeout = "x"\n', ["timeout", '"x"', "expected a number of seconds > 0"], 1),
    "unknown-format": ('format = "gitlab"\n',
                       ["format", '"gitlab"', "one of text, concise, json", 'did you mean "github"'], 1),
    "jobs-string": ('jobs = "four"\n', ["jobs", '"four"', "expected an integer > 0"], 1),
    "per-file-ignores-string": ('per-file-ignores = { "*.xacro" = "UL3" }\n',
                                ['per-file-ignores."*.xacro"', '"UL3"',
                                 "expected a list of rule codes or prefixes", '["UL3"]'], 1),
}


@pytest.mark.parametrize("name", sorted(MISTAKES))
def test_reported_mistakes_are_exit_2_with_key_value_and_expectation(pkg, capsys, name):
    text, words, line = MISTAKES[name]
    (pkg / "urdf-lint.toml").write_text(text)
    rc, out, err = run(capsys, "check", ".", "--no-cache")
    assert rc == 2, (out, err)
    assert out == ""                       # nothing printed before the error, no "All checks passed"
    assert err.count("\n") == 1, err       # one line
    assert err.startswith(f"urdf-lint: error: urdf-lint.toml:{line}: "), err
    for w in words:
        assert w in err, (w, err)
    assert "internal error" not in err


def test_same_mistakes_in_pyproject_point_at_the_line_in_our_table(pkg, capsys):
    (pkg / "pyproject.toml").write_text('[tool.ruff]\ntimeout = 1\n\n[tool.urdf-lint]\n'
                                        'select = ["UL3"]\ntimeout = "x"\n')
    rc, _, err = run(capsys, "check", ".", "--no-cache")
    assert rc == 2 and f"pyproject.toml:6: invalid value for timeout" in err, err


@pytest.mark.parametrize("flag,value,words", [
    ("--timeout", "x", ["--timeout", '"x"', "expected a number of seconds > 0"]),
    ("--jobs", "four", ["--jobs", '"four"', "expected an integer > 0"]),
    ("-j", "0", ["--jobs", '"0"', "expected an integer > 0"]),
    ("--format", "gitlab", ["--format", '"gitlab"', 'did you mean "github"']),
    ("--output-format", "jsn", ["--format", '"jsn"', 'did you mean "json"']),
    ("--fail-on", "errors", ["--fail-on", '"errors"', "one of error, warning, info, never"]),
])
def test_cli_values_go_through_the_same_schema(pkg, capsys, flag, value, words):
    rc, out, err = run(capsys, "check", ".", "--no-cache", flag, value)
    assert rc == 2 and out == "", err
    for w in words:
        assert w in err, (w, err)


def test_valid_values_still_work(pkg, capsys):
    (pkg / "urdf-lint.toml").write_text('timeout = 20\njobs = 1\nformat = "concise"\n'
                                        '[rule-options.UL307]\ntolerance = 1\n')
    rc, out, err = run(capsys, "check", ".", "--no-cache", "--select", "UL307")
    assert rc == 0, err
    assert out == "All checks passed: 1 model(s).\n"
    cfg = load_config(pkg / "urdf-lint.toml", codes_to_names(), load_rules)
    assert (cfg.timeout, cfg.jobs, cfg.output_format) == (20.0, 1, "concise")
    assert cfg.rule_options["UL307"]["tolerance"] == 1.0 and isinstance(
        cfg.rule_options["UL307"]["tolerance"], float)


def test_toml_syntax_error_gives_path_and_line(pkg, capsys):
    (pkg / "pyproject.toml").write_text('[tool.urdf-lint]\nselect = ["UL1"\nignore = []\n')
    rc, _, err = run(capsys, "check", ".")
    assert rc == 2
    assert err.startswith("urdf-lint: error: pyproject.toml:3:"), err
    assert "invalid TOML" in err
    # not skipped silently while looking for a config either
    with pytest.raises(ConfigError, match=r"pyproject.toml:3:\d+: invalid TOML"):
        find_config(str(pkg))


@pytest.mark.parametrize("table", ["urdf_lint", "urdflint", "urdf-lnt", "URDF-lint"])
def test_near_miss_table_name(pkg, capsys, table):
    (pkg / "pyproject.toml").write_text(f'[tool.{table}]\nselect = ["UL1"]\n')
    rc, _, err = run(capsys, "check", ".")
    assert rc == 2
    assert f"found [tool.{table}]; did you mean [tool.urdf-lint]?" in err, err


def test_unrelated_tool_tables_are_fine(pkg, capsys):
    (pkg / "pyproject.toml").write_text('[tool.ruff]\nline-length = 100\n[tool.mypy]\n')
    rc, out, _ = run(capsys, "check", ".", "--no-cache", "--select", "UL307")
    # (rc was 1: a non-unit axis is a warning since issue 25, every consumer normalises it)
    assert rc == 0 and "UL307" in out


def test_tool_table_inside_urdf_lint_toml(pkg, capsys):
    (pkg / "urdf-lint.toml").write_text('[tool.urdf-lint]\nselect = ["UL1"]\n')
    rc, _, err = run(capsys, "check", ".")
    assert rc == 2 and "keys go at the top level" in err, err


@pytest.mark.parametrize("text,words", [
    ('selcet = ["UL1"]\n', ["unknown key 'selcet'", "did you mean 'select'"]),
    ('fail_on = "warning"\n', ["unknown key 'fail_on'", "did you mean 'fail-on'"]),
    ("[rule-options.UL307]\ntolerence = 1\n", ["unknown option 'tolerence'", "did you mean 'tolerance'"]),
    ("[rule-options.joint-axes]\ntolerance = 1\n", ["unknown rule 'joint-axes'", "did you mean 'joint-axis'"]),
    ("[rule-options.UL307]\ntolerance = true\n", ["rule-options.UL307.tolerance", "true", "expected a number"]),
    ("[rule-options.UL504]\nmin-repeats = 2.5\n", ["rule-options.UL504.min-repeats", "2.5", "expected an integer"]),
    ('select = ["UL3"]\nignore = ["UL3O2"]\n', [":2: unknown rule code or prefix 'UL3O2'", "did you mean 'UL302'"]),
    ('severity = { UL302 = "fatal" }\n', ['severity.UL302: "fatal"', "one of error, warning, info"]),
    ("memory-mb = 1.5\n", ["memory-mb", "1.5", "an integer of MiB > 0"]),
    ('[[models]]\nfile = "r.urdf"\n', ["models", "'path'"]),
])
def test_more_bad_values(pkg, capsys, text, words):
    (pkg / "urdf-lint.toml").write_text(text)
    rc, out, err = run(capsys, "check", ".", "--no-cache")
    assert rc == 2 and out == "", err
    for w in words:
        assert w in err, (w, err)


def test_rule_option_types_inferred_and_declared(monkeypatch):
    mod = types.ModuleType("urdf_lint.rules._fake_typed")
    mod.OPTION_TYPES = {"count": (int, float)}
    monkeypatch.setitem(sys.modules, mod.__name__, mod)
    rule = types.SimpleNamespace(module=mod.__name__,
                                 options={"count": 3, "limit": 1e-3, "flag": False, "n": 2})
    assert option_types(rule) == {"count": (int, float), "limit": (float, int), "flag": (bool,),
                                  "n": (int,)}


def test_schema_is_complete_and_documented():
    readme = (REPO / "docs" / "configuration.md").read_text()
    defaults = Config()
    for key in SCHEMA:
        assert key.help and key.type.expected, key.name
        assert hasattr(defaults, key.attr), key.name
        if key.default is not None:
            assert getattr(defaults, key.attr) == key.default, key.name
        row = (f"| `{key.name}` | {key.type.expected.replace('|', ' or ')} | {key.default_text} "
               f"| {key.help} |")
        assert row in readme, f"docs/configuration.md's key table is stale for {key.name}: {row}"
    assert set(KEYS) == {k.name for k in SCHEMA}
    from urdf_lint.config.schema import FORMAT_SCHEMA   # [tool.urdf-lint.format]
    readme = (REPO / "docs" / "formatter.md").read_text()
    for key in FORMAT_SCHEMA:
        row = (f"| `{key.name}` | {key.type.expected} | {key.default_text} | {key.help} |")
        assert row in readme, f"docs/formatter.md's [format] table is stale for {key.name}: {row}"


def test_baseline_key_is_relative_to_the_config(pkg, capsys):
    sub = pkg / "sub"
    sub.mkdir()
    (pkg / "urdf-lint.toml").write_text('baseline = "sub/known.json"\n')
    rc, _, err = run(capsys, "check", ".", "--no-cache", "--select", "UL307",
                     "--write-baseline", "sub/known.json")
    assert rc == 0 and "wrote 1 finding(s)" in err, err
    cfg = load_config(pkg / "urdf-lint.toml")
    assert cfg.baseline == str((sub / "known.json").resolve())
    rc, out, _ = run(capsys, "check", ".", "--no-cache", "--select", "UL307")
    assert rc == 0 and out == "All checks passed: 1 model(s).\n"


# -- any value for any key: accepted with the right type, or a ConfigError naming the key ------
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

_text = st.text(st.characters(min_codepoint=32, max_codepoint=0x2FF, blacklist_characters="\x7f"),
                max_size=8)
_scalars = st.one_of(_text, st.integers(-5, 10**6), st.booleans(),
                     st.floats(allow_nan=False, allow_infinity=False, width=32),
                     st.sampled_from(["UL3", "UL302", "ALL", "error", "json", "limit-order", "4"]))
_values = st.recursive(_scalars, lambda inner: st.one_of(
    st.lists(inner, max_size=3),
    st.dictionaries(st.sampled_from(["a", "UL307", "tolerance", "*.xacro", "path", "args"]), inner,
                    max_size=2)), max_leaves=6)


def _toml(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, list):
        return "[" + ", ".join(_toml(x) for x in v) + "]"
    return "{" + ", ".join(f"{json.dumps(k)} = {_toml(x)}" for k, x in v.items()) + "}"


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(key=st.sampled_from(sorted(KEYS)), value=_values)
def test_any_value_is_accepted_or_named(tmp_path, key, value):
    f = tmp_path / "urdf-lint.toml"
    f.write_text(f"{key} = {_toml(value)}\n")
    try:
        cfg = load_config(f, codes_to_names(), load_rules)
    except ConfigError as e:
        msg = str(e)
        assert "\n" not in msg and msg.split(":")[0].endswith("urdf-lint.toml"), msg
        assert key in msg or "rule code" in msg or "rule-options" in msg, msg
        return
    got = getattr(cfg, KEYS[key].attr)
    if key == "format":   # [format]: urdf-lint format's settings; a string: output-format's
        if isinstance(value, dict):
            assert isinstance(cfg.format_options, dict) and cfg.output_format is None, (value, cfg)
        else:
            assert cfg.output_format == value and "deprecated" in cfg.notes[0], (value, cfg)
        return
    expected_type = {"timeout": float, "memory-mb": int, "jobs": int, "fail-on": str,
                     "output-format": str, "cache-dir": str, "baseline": str, "discover": bool,
                     "views": str, "forward-axis": str, "explore": bool,
                     "explore-budget": float}.get(key, (list, dict))
    assert isinstance(got, expected_type), (key, value, got)


def test_documented_config_example_is_valid(tmp_path):
    """docs/configuration.md's full example, as pasted, loads with no note."""
    import re
    readme = (REPO / "docs" / "configuration.md").read_text()
    (example,) = [b for b in re.findall(r"```toml\n(.*?)```", readme, re.S) if "[tool.urdf-lint]" in b]
    (tmp_path / "pyproject.toml").write_text(example.replace("# baseline", "baseline"))
    for m in re.findall(r'^path = "([^"]+)"', example, re.M):   # models must exist
        (tmp_path / m).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / m).write_text('<robot name="r"><link name="a"/></robot>\n')
    cfg = load_config(tmp_path / "pyproject.toml", codes_to_names(), load_rules)
    assert cfg.rule_options == {"UL307": {"tolerance": 1e-3}} and cfg.output_format == "text"
    assert cfg.notes == []
    assert cfg.baseline == str(tmp_path / "urdf-lint-baseline.json")
    assert [m.arg_sets for m in cfg.models] == [[{"ur_type": "ur5e"}, {"ur_type": "ur10e"}]]


# -- the schema is the one source: defaults, CLI flags, trust rules, the docs' tables ----------
def _gen_docs():
    from support.scripts import load_script
    return load_script("gen_docs")


def test_key_tables_are_generated_and_current():
    """The key tables of docs/configuration.md are written by scripts/gen_docs.py from the
    schema: a stale page -> this fails (run the script)."""
    gen = _gen_docs()
    readme = (REPO / "docs" / "configuration.md").read_text(encoding="utf-8")
    assert gen.render(readme) == readme, "docs/ is stale: run python scripts/gen_docs.py"
    stale = readme.replace("| `timeout` | a number of seconds > 0 | 30 |",
                           "| `timeout` | a number of seconds > 0 | 31 |")
    assert stale != readme and gen.render(stale) == readme


def test_config_fields_are_the_schema_keys_with_its_defaults():
    import dataclasses
    own = {"path", "root", "raw", "notes"}
    fields = {f.name for f in dataclasses.fields(Config)} - own
    assert fields == {k.attr for k in SCHEMA} - own
    a, b = Config(), Config()
    for key in SCHEMA:
        assert getattr(a, key.attr) == key.default, key.name
        if isinstance(key.default, (list, dict)):   # a fresh copy per Config
            assert getattr(a, key.attr) is not getattr(b, key.attr), key.name


def test_every_flag_of_the_schema_is_on_the_command_line():
    """A key with a ``flag`` is on every command that takes the flag's group; its help names
    the config key and its default; a bad value is the schema's message."""
    from urdf_lint.cli.main import SUBPARSERS, build_parser
    from urdf_lint.config.schema import FLAG_KEYS
    build_parser()
    assert {"select", "timeout", "jobs", "env-allow", "baseline"} <= {k.name for k in FLAG_KEYS}
    helps = {name: " ".join(p.format_help().split()) for name, p in SUBPARSERS.items()}
    for key in FLAG_KEYS:
        on = [name for name, h in helps.items() if f"config key '{key.name}'" in h]
        assert on and "check" in on, key.name
        for flag in key.flag.flags:
            assert flag in helps["check"], (key.name, flag)


def _loosening(key):
    """A value of ``key`` that loosens what its trust rule guards."""
    from urdf_lint.config.schema import Number, Str, StrList, Table
    t = key.type
    if isinstance(t, Number):
        return (key.default or 1) * 10
    if isinstance(t, StrList):
        return ["X_TOKEN"]
    if isinstance(t, Table):
        return {"far": "/nonexistent/elsewhere"}
    if isinstance(t, Str):
        return "/nonexistent/elsewhere"
    raise AssertionError(f"no loosening value for {key.name}")


def test_every_trust_rule_of_the_schema_is_applied(tmp_path):
    """Each key whose schema entry says a repository's config may not loosen it: set in the
    repository's config, it is back at its default with a note naming it; trusted, it is kept."""
    from urdf_lint.config import trust
    from urdf_lint.config.schema import trust_config_help
    guarded = [k for k in SCHEMA if k.trust and k.trust.rule != "confine"]
    assert {"env-allow", "cache-dir", "jobs", "timeout", "memory-mb", "package-paths"} <= {
        k.name for k in guarded}
    for key in guarded:
        f = tmp_path / "urdf-lint.toml"
        f.write_text(f"{key.name} = {_toml(_loosening(key))}\n")
        cfg = load_config(f)
        notes = trust.apply(cfg, str(tmp_path))
        assert len(notes) == 1 and f"ignored {key.name!r} from urdf-lint.toml" in notes[0], notes
        assert getattr(cfg, key.attr) == (key.default if key.default is not None else None) or \
            getattr(cfg, key.attr) == {}, (key.name, getattr(cfg, key.attr))
        cfg = load_config(f)
        assert trust.apply(cfg, str(tmp_path), trusted=True) == [], key.name
        assert getattr(cfg, key.attr) not in (key.default, {}), key.name
    assert all(k.name in trust_config_help() or k.trust.rule == "confine"
               for k in SCHEMA if k.trust)


def test_output_format_key_and_the_deprecated_string_format(pkg, capsys):
    """``output-format`` is the output format's key (the flag's name); ``format`` is the table
    of urdf-lint format, and a string there still works, with one located deprecation note."""
    (pkg / "urdf-lint.toml").write_text('output-format = "concise"\n[format]\nindent = 4\n')
    cfg = load_config(pkg / "urdf-lint.toml")
    assert (cfg.output_format, cfg.format_options, cfg.notes) == ("concise", {"indent": 4}, [])
    rc, out, err = run(capsys, "check", ".", "--no-cache", "--select", "UL307")
    assert rc == 0 and err == "", err
    (pkg / "urdf-lint.toml").write_text('select = ["UL"]\nformat = "json"\n')
    rc, out, err = run(capsys, "check", ".", "--no-cache")
    assert json.loads(out)["summary"]["models"] == 1, out
    assert err == ('urdf-lint: note: urdf-lint.toml:2: format = "json" is deprecated: write '
                   'output-format = "json" ([tool.urdf-lint.format] is the table of urdf-lint '
                   "format's settings)\n"), err
    rc, out, err = run(capsys, "check", ".", "--no-cache", "-q")
    assert err == "" and json.loads(out)
    # both: output-format wins
    (pkg / "urdf-lint.toml").write_text('format = "json"\noutput-format = "concise"\n')
    assert load_config(pkg / "urdf-lint.toml").output_format == "concise"
    (pkg / "urdf-lint.toml").write_text('output-format = "gitlab"\n')
    rc, _, err = run(capsys, "check", ".", "--no-cache")
    assert rc == 2 and 'invalid value for output-format: "gitlab"' in err and \
        'did you mean "github"' in err, err


def test_contributings_config_key_example_builds_and_a_wrong_trust_fails_at_load():
    """CONTRIBUTING's worked example of a config key, run as written: it makes a Key (its old
    text, a trust 'at-most-default' over a None default, was an internal TypeError once a
    repository set the key); a trust rule that cannot hold for its default fails at once."""
    import re
    from urdf_lint.config import schema
    text = (REPO / "CONTRIBUTING.md").read_text(encoding="utf-8")
    block = re.search(r"## 4\. A config key.*?```python\n(.*?)```", text, re.S).group(1)
    key = eval(block.strip().rstrip(","), vars(schema))   # noqa: S307 - our own docs
    assert key.name == "max-findings" and key.attr == "max_findings" and key.default is None
    assert key.trust.rule == "ignore" and key.flag.flags == ("--max-findings",)
    with pytest.raises(TypeError, match="'max-findings': trust 'at-most-default'"):
        schema.Key("max-findings", schema.Number(int, 0, "findings"), None, "x",
                   trust=schema.Trust("at-most-default", "more findings", unit="findings"))
    with pytest.raises(ValueError, match="unknown trust rule 'loose'"):
        schema.Key("x", schema.Number(int, 0, "n"), 1, "x", trust=schema.Trust("loose"))


def test_a_config_key_is_one_place_config_is_built_from_the_schema():
    """CONTRIBUTING's key, added to the schema and nowhere else, is a field of the Config made
    from it (typed from the key, its default a fresh copy of the key's); the typed block
    that mypy and editors read is the one scripts/gen_types.py writes from the schema, and a
    stale one is rewritten."""
    import dataclasses
    import re
    from urdf_lint.config import schema
    text = (REPO / "CONTRIBUTING.md").read_text(encoding="utf-8")
    block = re.search(r"## 4\. A config key.*?```python\n(.*?)```", text, re.S).group(1)
    key = eval(block.strip().rstrip(","), vars(schema))   # noqa: S307 - our own docs
    listed = schema.Key("watch", schema.StrList("globs"), ["*.xacro"], "x")
    cls = schema.config_class(schema.SCHEMA + (key, listed))
    fields = {f.name: f for f in dataclasses.fields(cls)}
    assert fields["max_findings"].type == "int | None" and fields["watch"].type == "list[str]"
    a, b = cls(), cls()
    assert a.max_findings is None and a.watch == ["*.xacro"] and a.watch is not b.watch
    assert cls(max_findings=3).max_findings == 3 and a.select == ["UL"]
    assert a.is_excluded(os.path.join(a.root, "x.urdf")) is False
    assert [f.name for f in dataclasses.fields(Config)] == \
        ["path", "root"] + [k.attr for k in SCHEMA] + ["raw", "notes"]
    import importlib.util
    spec = importlib.util.spec_from_file_location("gen_types", REPO / "scripts" / "gen_types.py")
    gen = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gen)
    source = (REPO / "urdf_lint" / "config" / "schema.py").read_text(encoding="utf-8")
    assert gen.render_config(source) == source, "schema.py is stale: run scripts/gen_docs.py"
    stale = source.replace('        timeout: float = _default("timeout")\n', "")
    assert stale != source and gen.render_config(stale) == source
