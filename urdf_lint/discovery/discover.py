"""Discovery: which files under the linted paths are candidate models, with which xacro args,
and which package roots they may read from."""
from __future__ import annotations

import os
import re
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, Iterable, Iterator, Sequence

from urdf_lint.core.findings import Problem
from urdf_lint.core.jobs import LintJob
from urdf_lint.core.tree import inside as inside   # (part of this module's API)
from urdf_lint.discovery.packages import PackageResolver, iter_files
from urdf_lint.discovery.vcs import git_root

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.config.schema import Config, ModelSpec


def start_dir(paths: Sequence[str]) -> str:
    """The folder a run starts from: the first path, or its folder when it is a file."""
    first = os.path.abspath(paths[0] if paths else ".")
    return first if os.path.isdir(first) else os.path.dirname(first)


def repository_root(paths: Sequence[str]) -> str:
    """The repository the paths belong to: git's work tree, else the working directory when
    it holds the paths, else the folder of the first path."""
    start = start_dir(paths) if paths else os.getcwd()
    top = git_root(start)
    if top:
        return top
    cwd = os.getcwd()
    if all(inside(os.path.realpath(p), os.path.realpath(cwd)) for p in paths):
        return cwd
    return os.path.abspath(start)


def build_resolver(paths: Sequence[str], cfg: "Config",
                   cli_packages: dict[str, str] | None = None) -> PackageResolver:
    """The package roots of a run (:func:`urdf_lint.discovery.packages.discover_roots`): the packages,
    the git repository and the colcon workspace holding the linted paths; never the working
    directory by itself, and nothing above the linted paths without git (fail closed)."""
    from urdf_lint.discovery.packages import discover_roots
    start = start_dir(paths) if paths else os.getcwd()
    scan, extra_roots = discover_roots(paths or [start], git_root(start))
    explicit = dict(cfg.package_paths)
    explicit.update(cli_packages or {})
    # a [[models]] mesh-base is where that model's meshes are: a root like the package, when it
    # lies inside the config's folder (a file linted alone, outside git, no longer sees every
    # mesh of a mesh-base above it as outside the roots, UL403)
    top_cfg = os.path.realpath(cfg.root) if cfg.path else None
    extra_roots += [m.mesh_base for m in cfg.models if m.mesh_base and top_cfg
                    and inside(os.path.realpath(m.mesh_base), top_cfg)]
    # the enclosing colcon/catkin workspace (sibling package repositories, install space): its
    # packages are indexed, and the workspace is a root like the repository (never the working
    # directory by itself: see SECURITY.md)
    from urdf_lint.discovery.workspace import index, install_share_packages, workspace_roots
    found: dict[str, str] = {}
    for ws in workspace_roots([*paths, start]):
        extra_roots.append(ws)
        for name, d in index(ws).items():
            found.setdefault(name, d)
    # an install layout being linted (share/NAME/package.xml; the package scan skips install/)
    top = git_root(start)
    for d in dict.fromkeys([*([top] if top else []), *(os.path.abspath(p) for p in paths)]):
        if os.path.isdir(d):
            for name, pkg in install_share_packages(d).items():
                found.setdefault(name, pkg)
    res = PackageResolver.build(scan, explicit=explicit,
                                extra_roots=list(dict.fromkeys(extra_roots)), packages=found)
    searched = [os.path.join(ws, "src") for ws in workspace_roots([*paths, start])]
    searched = [s for s in searched if os.path.isdir(s) and s not in res.scanned_dirs]
    if searched:   # searched too: named in UL004's list (a new snapshot: the resolver is frozen)
        import dataclasses
        res = dataclasses.replace(res, scanned_dirs=(*res.scanned_dirs, *searched))
    return res


def _kind(f: str) -> str:
    return "urdf" if f.endswith(".urdf") else "xacro"


@dataclass
class Discovery:
    """What discovery found: the jobs to lint, the fragments (file -> the linted files that
    include it) that are linted only through the models including them, and the generated
    URDFs (checked against their xacro by UL011, and linted too: consumers read them)."""
    jobs: list[LintJob]
    fragments: dict[str, list[str]]
    graph: "IncludeGraph"
    generated: dict[str, str] = field(default_factory=dict)   # generated .urdf -> the xacro it comes from
    folders: list[str] = field(default_factory=list)     # every folder the walk looked into
    problems: list[Problem] = field(default_factory=list)    # located findings about the config (UL008)


def candidate_files(paths: Iterable[str], cfg: "Config", folders: list[str] | None = None
                    ) -> Iterator[tuple[str, str]]:
    """(file, the path it was found under) for every .urdf/.xacro under the paths; the
    folders walked are added to ``folders``."""
    seen = set()
    for p in paths:
        p = os.path.abspath(p)
        for found in iter_files(Path(p), suffixes=(".urdf", ".xacro"), folders=folders):
            f = os.path.realpath(found) if not os.path.islink(found) else os.path.abspath(found)
            if f.endswith(".srdf.xacro"):   # a robot's semantic description, not a robot
                continue
            # an exclude does not apply below a path that is itself excluded and named explicitly
            if f in seen or (cfg.is_excluded(f) and not cfg.is_excluded(p)):
                continue
            seen.add(f)
            yield f, p


def discover_models(paths: Sequence[str], cfg: "Config", resolver: "PackageResolver | None" = None,
                    cache_dir: str | None = None) -> Discovery:
    """Every candidate model under the paths, with the arg sets to expand it with.

    ``fragments`` are the xacro files another linted file includes (read from the include
    graph): the pipeline keeps one as a model of its own only when it is a complete robot by
    itself (links, and none of the findings a fragment gives: undefined links or names);
    otherwise it is linted only through the models including it. A file named explicitly or
    listed in config is always a model."""
    configured = {m.path: m for m in cfg.models}
    folders: list[str] = []
    found = list(candidate_files(paths, cfg, folders))
    graph = include_graph([f for f, _ in found], resolver, cache_dir)
    problems = [p for spec in cfg.models for p in _check_args(spec, graph, cfg)]
    graph.save()
    by = graph.included_by()
    linted = {f for f, _ in found}
    jobs, fragments = [], {}
    discover_all = getattr(cfg, "discover", True)
    detected = _detected_outputs(found, paths, resolver)
    generated = {o: x for x, os_ in detected.items() for o in os_}
    generated.update({m.output: m.path for m in cfg.models if m.output})
    recorded = _recorded_args(detected, resolver)
    for f, p in found:
        if f in configured:
            jobs.extend(_configured_jobs(configured[f], detected.get(f, ()), recorded, graph))
            continue
        if not discover_all and p != f:
            continue
        includers = [g for g in by.get(f, ()) if g in linted]
        if includers and p != f:
            fragments[f] = includers
        jobs.extend(_variant_jobs(f, [{}], p == f, None, None, detected.get(f, ()),
                                  recorded, graph))
    # configured models inside the linted paths that the walk did not reach
    for f, spec in configured.items():
        if f in linted or not any(inside(f, os.path.abspath(p)) for p in paths):
            continue
        jobs.extend(_configured_jobs(spec, detected.get(f, ()), recorded, graph))
    jobs = _inherit_mesh_base(jobs, graph)
    from urdf_lint.discovery.configs import attach_configs
    jobs = attach_configs(jobs, cfg, resolver)
    return Discovery(jobs, fragments, graph, generated, folders, problems)


def _inherit_mesh_base(jobs: list[LintJob], graph: "IncludeGraph") -> list[LintJob]:
    """A file included by models that set where relative mesh paths start (a ``mesh-base``,
    or the folder of their generated URDF) starts them there too when it is linted on its own
    (a complete robot that is also a fragment): its meshes sit next to those URDFs, not next
    to the xacro. Only when the models including it agree on one folder."""
    import dataclasses
    base: dict[str, str] = {}
    for j in jobs:
        b = j.mesh_base or (os.path.dirname(j.output) if j.output else None)
        if b:
            base.setdefault(j.entry, b)
    out = []
    for j in jobs:
        if j.kind == "xacro" and not (j.mesh_base or j.output):
            got = {base[g] for g in graph.includers(j.entry) if g in base}
            if len(got) == 1:
                j = dataclasses.replace(j, mesh_base=got.pop())
        out.append(j)
    return out


def _detected_outputs(found: list[tuple[str, str]], paths: Sequence[str],
                      resolver: PackageResolver | None = None) -> dict[str, list[str]]:
    """xacro -> the checked-in ``.urdf`` files whose generator header names it (no config
    needed), the one named after the xacro first (``robot.urdf`` for ``robot.urdf.xacro``),
    then in path order: every one is compared with today's expansion (UL011). Headers are
    read from regular files inside the roots only."""
    from urdf_lint.discovery.generated import find_source, header_source
    xacros = [f for f, _ in found if f.endswith(".xacro")]
    if not xacros:
        return {}
    root = os.path.realpath(repository_root(paths))
    out: dict[str, list[str]] = {}
    for f, _ in found:
        if not f.endswith(".urdf"):
            continue
        named = header_source(f, resolver.roots if resolver is not None else None,
                              resolved=True)   # a discovered file: a real path (or a link)
        src = find_source(f, named, xacros, root) if named else None
        if src:
            out.setdefault(src, []).append(f)
    for src, fs in out.items():
        stem = os.path.basename(src)[:-len(".xacro")]
        stem = stem[:-len(".urdf")] if stem.endswith(".urdf") else stem
        fs.sort(key=lambda f: (os.path.basename(f) != stem + ".urdf", f))
    return out


def _check_args(spec: "ModelSpec", graph: "IncludeGraph", cfg: "Config") -> list[Problem]:
    """A ``UL008`` warning, at the config line that sets it, for an arg a configured model
    sets that no ``xacro:arg`` of the file (or its includes) declares and no ``$(arg NAME)``
    there reads: xacro accepts and ignores it (a launch file's args often hold more), so the
    model is linted as its default variant for that arg."""
    from urdf_lint.core.findings import Problem
    from urdf_lint.core.codes import RuleName
    ul008_xacro_warning = RuleName("ul008_xacro_warning")
    if not spec.path.endswith(".xacro"):
        return []
    declared = graph.declared_args(spec.path)
    if graph.unresolved_below(spec.path):
        return []   # an include only expansion resolves may declare it
    out = []
    for args in spec.arg_sets:
        for name in sorted(set(args) - declared):
            import difflib
            close = difflib.get_close_matches(name, sorted(declared), n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            known = ", ".join(sorted(declared)) or "none"
            where = (cfg.path, *config_line(cfg.path, name)) if cfg.path else (spec.path, 1, 1)
            out.append(Problem.at(
                ul008_xacro_warning.CODE,
                f"model {os.path.relpath(spec.path, cfg.root)}: arg {name!r} is not declared "
                f"by any xacro:arg (nor read by $(arg ...)) in the file or its includes{hint} "
                f"(declared: {known}); xacro ignores it", where))
    return list({p.key(): p for p in out}.values())


def config_line(path: str, name: str) -> tuple[int, int]:
    """(line, col) of the first ``name =`` in the config file (an arg in ``args``), else (1, 1)."""
    pat = re.compile(r"""(?:^|[\s{,])["']?""" + re.escape(name) + r"""["']?\s*=""")
    from urdf_lint.core import fsbound
    try:   # the config file: a regular file of bounded size (the boundary)
        text = fsbound.read_text(path, errors="replace")
    except OSError:
        text = ""
    for i, line in enumerate(text.splitlines(), 1):
        m = pat.search(line)
        if m:
            return i, m.start() + 1 + (line[m.start()] in " \t{,")
    return 1, 1


def _recorded_args(detected: dict[str, list[str]], resolver: PackageResolver | None = None
                   ) -> dict[str, dict[str, str] | None]:
    """detected output -> the args ``urdf-lint generate`` recorded in its header, or None."""
    from urdf_lint.discovery.generated import header_args
    roots = resolver.roots if resolver is not None else None
    return {o: header_args(o, roots, resolved=True) for outs in detected.values() for o in outs}


def _configured_jobs(spec: "ModelSpec", detected: Sequence[str] = (),
                     recorded: dict[str, dict[str, str] | None] | None = None,
                     graph: "IncludeGraph | None" = None) -> list[LintJob]:
    """One job per arg set of a models entry (see :func:`_variant_jobs`)."""
    jobs = _variant_jobs(spec.path, [dict(a) for a in spec.arg_sets], True, spec.output,
                         spec.mesh_base, detected, recorded or {}, graph)
    places = list(getattr(spec, "arg_places", None) or [])
    for n, job in enumerate(jobs[:len(places)]):   # (the configured sets come first)
        if places[n]:
            jobs[n] = replace(job, arg_origins=tuple(sorted(places[n].items())))
    return jobs


def _variant_jobs(f: str, arg_sets: list[dict[str, str]], explicit: bool, output: str | None,
                  mesh_base: str | None, detected: Sequence[str],
                  recorded: dict[str, dict[str, str] | None],
                  graph: "IncludeGraph | None") -> list[LintJob]:
    """One job per arg set of ``f``, each with the outputs tied to its args: the configured
    ``output`` to the first; a detected output (a header names ``f``) to the args
    ``urdf-lint generate`` recorded in its header (a job of its own when no arg set has
    them), else to the only variant when ``f`` reads no arg. The other detected outputs are
    untied: the first job compares them with every arg set and the default args."""
    if not arg_sets:   # (``args = []``: no variant is linted)
        return []
    tied: list[list[str]] = [[] for _ in arg_sets]
    tied[0] += [output] if output else []
    more: dict[tuple[tuple[str, str], ...], list[str]] = {}
    untied: list[str] = []
    one = graph is None or not f.endswith(".xacro") or not (
        graph.declared_args(f) or graph.unresolved_below(f))
    for o in detected:
        if o == output:
            continue
        args = recorded.get(o)
        if args is None:
            tied[0].append(o)
            if not one:
                untied.append(o)
        elif args in arg_sets:
            tied[arg_sets.index(args)].append(o)
        else:
            more.setdefault(tuple(sorted(args.items())), []).append(o)
    # the untied outputs are compared with every arg set, and the defaults (xacro's own)
    known = arg_sets[1:] + ([{}] if {} not in arg_sets else [])
    variants = tuple(tuple(sorted(a.items())) for a in known) if untied else ()
    # (``mesh_base`` only when configured: the engine starts from the output's folder itself,
    # and knows it assumed it)
    jobs = [LintJob(f, dict(args), _kind(f), explicit=explicit,
                    output=outs[0] if outs else None, outputs=tuple(outs[1:]),
                    untied=tuple(untied) if n == 0 else (),
                    variants=variants if n == 0 else (), mesh_base=mesh_base)
            for n, (args, outs) in enumerate(zip(arg_sets, tied, strict=True))]
    jobs += [LintJob(f, dict(key), _kind(f), explicit=explicit, output=outs[0],
                     outputs=tuple(outs[1:]), mesh_base=mesh_base)
             for key, outs in more.items()]
    return jobs


def discover(paths: Sequence[str], cfg: "Config", resolver: "PackageResolver | None" = None) -> list[LintJob]:
    """The jobs of :func:`discover_models`."""
    return discover_models(paths, cfg, resolver).jobs


# -- the include graph ---------------------------------------------------------------------------
_XACRO_NS_HINT = "xacro"
_ARG_RE = re.compile(r"\$\(\s*arg\s+([^)\s]+)\s*\)")
_FIND_RE = re.compile(r"\$\(\s*find\s+([^)\s]+)\s*\)")
# $(optenv VAR default): expansion reads no variable outside env-allow, so it gets the default
_OPTENV_RE = re.compile(r"\$\(\s*optenv\s+[^)\s]+\s*([^)]*?)\s*\)")
# what the memo of the include graph holds (bump when _read_includes reads more)
GRAPH_FORMAT = 2


@dataclass
class IncludeGraph:
    """Which xacro files include which, read from a quick parse of every candidate.

    ``includes[f]`` are the files ``f`` names in an ``xacro:include`` (anywhere: inside
    ``xacro:if``/``unless`` and macros too), resolved through the package resolver;
    ``unresolved[f]`` counts the includes whose file name needs expansion to be known
    (``${...}``, ``$(arg ...)``, an unknown package): for those the dependencies expansion
    records are used instead. ``args[f]`` are the ``xacro:arg`` names ``f`` declares."""
    includes: dict[str, list[str]] = field(default_factory=dict)
    unresolved: dict[str, int] = field(default_factory=dict)
    args: dict[str, list[str]] = field(default_factory=dict)
    _by: dict[str, list[str]] | None = None
    _resolver: "PackageResolver | None" = None
    _memo_file: str | None = None
    _memo: dict[str, Any] = field(default_factory=dict)
    _fresh: dict[str, Any] = field(default_factory=dict)
    _dirty: bool = False

    def included_by(self) -> dict[str, list[str]]:
        """file -> the files that include it."""
        if self._by is None:
            by: dict[str, list[str]] = {}
            for f, inc in self.includes.items():
                for g in inc:
                    if g != f:
                        by.setdefault(g, []).append(f)
            self._by = by
        return self._by

    def declared_args(self, f: str, _seen: set[str] | None = None) -> set[str]:
        """The ``xacro:arg`` names of ``f`` and of everything it includes (transitively)."""
        seen = _seen if _seen is not None else set()
        if f in seen:
            return set()
        seen.add(f)
        if f not in self.args:
            self.add(f, self._resolver)
        out = set(self.args.get(f, ()))
        for g in self.includes.get(f, ()):
            out |= self.declared_args(g, seen)
        return out

    def unresolved_below(self, f: str) -> bool:
        """Does ``f`` or a file it includes have an include only expansion can resolve?"""
        todo, seen = [f], set()
        while todo:
            g = todo.pop()
            if g in seen:
                continue
            seen.add(g)
            if self.unresolved.get(g):
                return True
            todo.extend(self.includes.get(g, ()))
        return False

    def includers(self, f: str) -> list[str]:
        """Every file that includes ``f``, directly or through other files."""
        by = self.included_by()
        out, todo = [], [f]
        seen = {f}
        while todo:
            for g in by.get(todo.pop(), ()):
                if g not in seen:
                    seen.add(g)
                    out.append(g)
                    todo.append(g)
        return out

    def add(self, f: str, resolver: "PackageResolver | None") -> None:
        """Read ``f``'s includes and args: from the memo when its size and mtime are those
        recorded last run, else from a quick parse."""
        self._by = None
        try:
            st = os.stat(f)
            stamp = [st.st_size, st.st_mtime_ns]
        except OSError:
            stamp = None
        hit = self._memo.get(f)
        if stamp is not None and hit and hit[0] == stamp:
            self.includes[f], self.unresolved[f], self.args[f] = list(hit[1]), hit[2], list(hit[3])
        else:
            self.includes[f], self.unresolved[f], self.args[f], glob_used = \
                _read_includes(f, resolver)
            self._dirty = True
            if glob_used:
                stamp = None   # what a glob matches changes without this file: never memoised
        self._fresh[f] = [stamp, self.includes[f], self.unresolved[f], self.args[f]]

    def save(self) -> None:
        """Write the memo for the next run (when something was parsed or dropped)."""
        if self._memo_file and (self._dirty or set(self._fresh) != set(self._memo)):
            _save_memo(self._memo_file, self._fresh)
            self._memo, self._dirty = dict(self._fresh), False


def _resolve_include(name: str, base: str, resolver: PackageResolver | None) -> list[str] | None:
    """The files an include's ``filename`` names, or None when only expansion can tell."""
    name = name.strip()
    if resolver is not None:
        def find(m: "re.Match[str]") -> str:
            return str(resolver.find(m.group(1)))
        try:
            name = _FIND_RE.sub(find, name)
            if name.startswith("package://"):
                pkg, _, rel = name[len("package://"):].partition("/")
                name = os.path.join(str(resolver.find(pkg)), rel)
        except Exception:  # noqa: BLE001 - unknown package: expansion reports it
            return None
    name = _OPTENV_RE.sub(lambda m: m.group(1), name)
    if "$" in name or not name:
        return None
    if name.startswith("file://"):
        name = name[len("file://"):]
    path = os.path.normpath(os.path.join(base, name))
    if any(c in name for c in "*?["):
        # as xacro globs it, but bounded: a pattern that would look at too many entries is
        # left to expansion (in the sandboxed worker, with its time limit)
        from urdf_lint.core import fsbound
        got = fsbound.bounded_glob(path)
        return None if got is None else sorted(os.path.realpath(p) for p in got)
    return [os.path.realpath(path)]


_EXPR = re.compile(r"\$\{[^}]*\}|\$\((?!find\s)[^)]*\)")


def _maybe_included(name: str, base: str, resolver: PackageResolver | None) -> list[str]:
    """The files an include whose ``filename`` is built from a macro parameter or an arg
    (``${side}_arm.transmissions.urdf.xacro``) may name: the expressions read as ``*``, when
    what is left names enough (at least 4 characters besides the extension), so that such
    a fragment is linted through its includers, not alone (where it lacks their params)."""
    pattern = _EXPR.sub("*", name.strip())
    if "$" in pattern.replace("$(find", "") or "*" not in pattern:
        return []
    literal = os.path.basename(pattern).replace("*", "")
    for ext in (".urdf.xacro", ".xacro", ".urdf"):
        if literal.endswith(ext):
            literal = literal[:-len(ext)]
            break
    if len(literal.strip("._-")) < 4:
        return []
    return _resolve_include(pattern, base, resolver) or []


def _default_file(value: str | None, base: str, resolver: PackageResolver | None) -> list[str]:
    """The model file an arg's default or a property's value names (``$(find p)/urdf/empty.urdf``,
    ``$(optenv EXTRAS empty.urdf)``), when it exists: an include of ``$(arg NAME)`` reads it, so
    it is included (a placeholder that makes "no extras" the default is no model of its own)."""
    value = _OPTENV_RE.sub(lambda m: m.group(1), value or "").strip()
    if not value.endswith((".urdf", ".xacro")):
        return []
    got = _resolve_include(value, base, resolver) or []
    return [f for f in got if os.path.isfile(f)]


def _read_includes(f: str, resolver: PackageResolver | None
                   ) -> tuple[list[str], int, list[str], bool]:
    """(included files, number of unresolvable includes, declared or used arg names, whether
    an include is a glob)."""
    from lxml import etree
    from urdf_lint.core import fsbound
    try:   # a regular file inside the roots, bounded (never a FIFO or /dev/stdout)
        # (f is a real path: a discovered file, or an include resolved by realpath)
        root = fsbound.parse_xml(f, etree.XMLParser(resolve_entities=False, no_network=True,
                                                    load_dtd=False),
                                 resolver.roots if resolver is not None else None,
                                 resolved=True)
    except (etree.XMLSyntaxError, OSError):
        return [], 0, [], False
    inc, unresolved, args, glob_used = [], 0, [], False
    base = os.path.dirname(f)
    for el in root.iter():
        if not isinstance(el.tag, str):
            continue
        q = etree.QName(el)
        if not (q.namespace and _XACRO_NS_HINT in q.namespace):
            continue
        if q.localname == "include":
            glob_used = glob_used or any(c in el.get("filename", "") for c in "*?[")
            got = _resolve_include(el.get("filename", ""), base, resolver)
            if got is None:
                unresolved += 1
                maybe = _maybe_included(el.get("filename", ""), base, resolver)
                if maybe:   # ${side}_arm.transmissions.urdf.xacro: left_ and right_ are included
                    inc.extend(maybe)
                    glob_used = True
            else:
                inc.extend(got)
        elif q.localname == "arg" and el.get("name"):
            args.append(el.get("name"))
            inc.extend(_default_file(el.get("default"), base, resolver))
        elif q.localname == "property":
            inc.extend(_default_file(el.get("value"), base, resolver))
    # an arg used as $(arg NAME) without a declaration is set on xacro's command line
    for el in root.iter():
        if isinstance(el.tag, str):
            for v in [*el.attrib.values(), el.text or ""]:
                if "$(arg" in v:
                    args.extend(_ARG_RE.findall(v))
    return list(dict.fromkeys(inc)), unresolved, list(dict.fromkeys(args)), glob_used


def include_graph(files: Iterable[str], resolver: PackageResolver | None,
                  cache_dir: str | None = None) -> IncludeGraph:
    """The include graph of ``files``; with ``cache_dir``, a file whose size and mtime are
    unchanged since the last run (with the same resolver) is not parsed again (call
    ``save()`` when done: files added later, e.g. for arg checks, are memoised too)."""
    memo_file = _memo_path(cache_dir, resolver)
    g = IncludeGraph(_resolver=resolver, _memo_file=memo_file, _memo=_load_memo(memo_file))
    for f in files:
        if f.endswith(".xacro"):
            g.add(f, resolver)
    return g


def _memo_path(cache_dir: str | None, resolver: PackageResolver | None) -> str | None:
    if not cache_dir:
        return None
    import hashlib
    import json
    # everything an include's resolution depends on: the package maps, the roots and the
    # environment's search paths
    key = json.dumps([GRAPH_FORMAT, resolver.to_dict() if resolver is not None else {}],
                     sort_keys=True)
    return os.path.join(cache_dir, "graph",
                        hashlib.blake2b(key.encode(), digest_size=10).hexdigest() + ".json")


def _load_memo(path: str | None) -> dict[str, Any]:
    if not path:
        return {}
    import json
    from urdf_lint.core import fsbound
    try:
        data = json.loads(fsbound.read_bytes(path, max_bytes=fsbound.MAX_DATA_BYTES))
        return data if isinstance(data, dict) else {}
    except (OSError, ValueError, RecursionError):
        return {}


def _save_memo(path: str, data: dict[str, Any]) -> None:
    import json
    from urdf_lint.core.cachedir import ensure
    try:
        cache_dir = os.path.dirname(os.path.dirname(path))
        ensure(cache_dir)
        from urdf_lint.core import fsbound
        fsbound.write_text(path, json.dumps(data), cache_dir, make_dirs=True)
    except OSError:
        pass
