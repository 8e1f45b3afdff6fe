"""The end of a run, in one place: what ``check``, the hook, ``render``, ``diff``, ``--fix``,
the pytest plugin, the MCP server and the language server all report from the reports the
workers sent back.

:func:`finish` takes the linted models (:func:`split_models` decides which reports are models)
and the run's own problems to the findings: each rule's severity under the policy and the
selected targets (:func:`with_policy`), the run-scope rules (:func:`run_rules_of`), merged,
inline suppressions applied (:func:`suppress`), selection and per-file ignores, no fix of a
generated URDF. :func:`scope` then applies what depends on who asks: the fix-scope rule (a
fix may edit only the linted paths: ``check --fix``'s rule, also for the editor's code
actions) and the baseline (only new findings). Grouping (one finding per source location and
rule) is :func:`urdf_lint.core.findings.group`, which every output and count applies to
these findings. The language server applies the configured baseline too: an editor shows what
``check`` would.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Iterable, Sequence

from urdf_lint.config.policy import Policy, code_matches
from urdf_lint.core.codes import RuleName
from urdf_lint.core.findings import Problem, merge
from urdf_lint.core.jobs import LintSettings, ModelReport, Status

# the rules raised or consulted here, by name (core.codes: no rule module is imported)
ul002_xacro_error = RuleName("ul002_xacro_error")
ul006_not_a_robot = RuleName("ul006_not_a_robot")
ul103_missing_link = RuleName("ul103_missing_link")
unused_suppression = RuleName("ul009_unused_suppression")
invalid_suppression = RuleName("ul010_invalid_suppression")

# findings that usually mean "this file is a fragment: the model including it defines the rest"
FRAGMENT_HINT_CODES = (ul002_xacro_error.CODE, ul006_not_a_robot.CODE, ul103_missing_link.CODE)

# a finding of a run-scope rule belongs to no single model; its "models" list holds this label
RUN_LABEL = ""


@dataclass
class RunView:
    """What a run-scope rule's ``check(run, ctx)`` sees: every linted model of the run."""
    models: list[ModelReport]
    generated: dict[str, str] = field(default_factory=dict)   # generated .urdf -> the xacro it comes from


class RunContext:
    def __init__(self, options: dict[str, Any]) -> None:
        self.options = options



def with_policy(problems: Iterable[Problem], label: str, policy: Policy) -> list[Problem]:
    """Problems with their rule name, effective severity and model label. The severity is the
    configured override, else the highest the selected targets give (:mod:`urdf_lint.core.targets`:
    the finding's own target table, else the rule's ``TARGETS``, over the severity the rule
    chose for it, else the rule's); a finding no selected target keeps is dropped."""
    from urdf_lint.engine.registry import catalogue
    from urdf_lint.core.targets import resolve
    rules = catalogue()
    out = []
    for p in problems:
        r = rules.get(p.code)
        name = r.name if r else p.code
        base = p.severity or (r.severity if r else "error")
        table = dict(p.consumers) if p.consumers is not None else (r.targets if r else {})
        sev, by = resolve(table, base, policy.targets) if table else (base, ())
        if sev is None:
            continue
        over = policy.override_of(p.code, name)
        if over is not None:
            sev, by = over, ()
        out.append(p.replace(name=name, severity=sev, models=(label,), severity_from=by))
    return out


def split_models(results: list[ModelReport], explicit: "set[str] | frozenset[str]" = frozenset(),
                 fragments: dict[str, list[str]] | None = None
                 ) -> tuple[list[ModelReport], list[ModelReport]]:
    """(models, skipped): macro-only files and XML that is not a robot are skipped. A file
    other files include (``fragments``, from the include graph, or a file a model's expansion
    read, for includes only expansion resolves such as ``${prefix}.xacro``) is kept as a model
    of its own only when it is a complete robot by itself; otherwise it is a fragment, linted
    through the models that include it. A file named explicitly is always a model."""
    used = set(fragments or ())
    for r in results:
        if r.status is Status.MODEL:   # (a generated .urdf output is an input, not an include)
            used.update(d for d in r.deps[1:] if d != r.entry and d.endswith(".xacro"))
    models, skipped = [], []
    for r in sorted(results, key=lambda r: (r.entry, sorted(r.args.items()))):
        if r.status in (Status.LIBRARY, Status.NOT_ROBOT):
            skipped.append(r)
        elif r.entry in used and not r.args and r.entry not in explicit \
                and not complete_robot(r):
            r.status = Status.FRAGMENT
            skipped.append(r)
        else:
            models.append(r)
    return models, skipped


def complete_robot(r: ModelReport) -> bool:
    """Does an included file also stand alone as a robot (a named robot with links, no
    undefined link or name)?"""
    return r.status is Status.MODEL and r.links > 0 and bool(r.name) and not any(
        p.code in FRAGMENT_HINT_CODES for p in r.problems)


def run_rules_of(run: "RunView", settings: LintSettings, internal: list[str] | None = None
                 ) -> list[Problem]:
    """The run-scope rules (``SCOPE = "run"``) over every linted model (``internal`` hears a
    rule that failed)."""
    from urdf_lint.engine.registry import run_rules
    return [Problem.at(rule.code, msg, loc, severity=sev, consumers=table)
            for rule, loc, msg, sev, table in run_rules("run", settings.selected,
                                                        settings.options, run, RunContext({}),
                                                        internal if internal is not None
                                                        else [], with_table=True)]


def suppress(merged: list[Problem], models: Iterable[ModelReport], settings: LintSettings,
              policy: Policy) -> list[Problem]:
    """Drop what inline comments suppress; add a finding for each unused suppression."""
    from urdf_lint.engine import suppress
    from urdf_lint.engine.registry import catalogue
    rules = catalogue()
    files: set[str] = set()
    # a generated URDF that is today's expansion is not linted: the comments xacro copied
    # into it suppress nothing there (they are the xacro's)
    current = {o for r in models for o in r.current_outputs}
    for r in models:
        sources = [d for d in r.deps if d.endswith(suppress.SOURCE_SUFFIXES)
                   and d not in current]
        # the worker said which sources hold urdf-lint comments (kept in the cache with the
        # result, valid while the deps are); otherwise every source is read
        known = None if r.directive_files is None else set(r.directive_files)
        files.update(d for d in sources if known is None or d in known)
    from urdf_lint.discovery.packages import MAX_SOURCE_BYTES, PackageResolver
    resolver = PackageResolver.from_dict(settings.resolver)
    # the parent reads only what the workers could: inside the roots, regular, bounded
    directives = {f: suppress.parse_directives(f) for f in sorted(files)
                  if resolver.readable(f, MAX_SOURCE_BYTES)}
    selected = settings.selected
    kept, unused, invalid = suppress.apply(
        merged, directives,
        is_selected=lambda c: any(code_matches(c, s, rules[s].name) for s in selected))
    from urdf_lint.fix.fixes import remove_comment
    about_comments = [Problem.at(unused_suppression.CODE, msg, loc, fix=remove_comment(loc))
                      for loc, msg in unused]
    about_comments += [Problem.at(invalid_suppression.CODE, msg, loc) for loc, msg in invalid]
    kept += [p.replace(models=()) for p in with_policy(about_comments, RUN_LABEL, policy)]
    return kept


def finish(models: Sequence[ModelReport], run_problems: Sequence[Problem],
           settings: LintSettings, policy: Policy, generated: dict[str, str] | None = None,
           run_rules: bool = True, internal: list[str] | None = None) -> list[Problem]:
    """The findings of a run: the models', the run-scope rules' (``run_rules``) and the run's
    own (discovery's, the config's), with the policy's severities, suppressions and selection
    applied, no fix of a generated URDF, sorted."""
    problems: list[Problem] = []
    for r in models:
        problems.extend(with_policy(r.problems, r.label, policy))
    if run_rules:
        view = RunView(models=list(models), generated=dict(generated or {}))
        problems.extend(with_policy(run_rules_of(view, settings, internal), RUN_LABEL, policy))
    problems.extend(with_policy(run_problems, RUN_LABEL, policy))
    kept = suppress(merge(problems), models, settings, policy)
    final = [f for f in kept if policy.is_selected(f.code, f.name)
             and not policy.ignored_for_file(f.code, f.name, f.file)]
    from urdf_lint.fix.scope import not_in_generated
    return sorted(not_in_generated(final, generated or {}),
                  key=lambda f: (f.file, f.line, f.col, f.code))


@dataclass(frozen=True)
class Scope:
    """What the end of a run depends on who asks: ``fix_paths``, the paths a fix may edit
    (None: every fix is kept as the rules made it); ``baseline``, a baseline file whose
    findings are not reported (``note`` hears that an old one should be rewritten)."""
    fix_paths: tuple[str, ...] | None = None
    baseline: str | None = None
    note: Callable[[str], object] | None = field(default=None, compare=False)


def scope(findings: list[Problem], how: Scope, generated: dict[str, str] | None = None
          ) -> tuple[list[Problem], int]:
    """(the findings as ``how`` reports them, how many the baseline hid): a fix that would
    edit a file outside ``how.fix_paths`` or a generated URDF is refused (``check --fix``'s
    rule), then the baseline's findings are left out."""
    if how.fix_paths is not None:
        from urdf_lint.fix.scope import inside_paths
        findings = inside_paths(findings, list(how.fix_paths), generated)
    hidden = 0
    if how.baseline:
        from urdf_lint.engine.baseline import filter_baseline
        kept = filter_baseline(how.baseline, findings, how.note)
        hidden, findings = len(findings) - len(kept), kept
    return findings, hidden


