"""Lint one model: expand (or parse) it, build the Model, run the selected model-scope rules.

``lint_model`` takes a typed job and the run's settings and returns a :class:`ModelReport`
(plus the model itself, for consumers such as the renderer). It runs the same in process and
in a worker.
"""
from __future__ import annotations

import os
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from urdf_lint.core.findings import Problem
from urdf_lint.core.jobs import KeptModel, LintJob, LintSettings, ModelReport, Status
from urdf_lint.core.locations import Origin
from urdf_lint.core.codes import RuleName

# the rules raised here, by name (urdf_lint.core.codes: no rule module is imported)
ul001_xml_syntax = RuleName("ul001_xml_syntax")
ul006_not_a_robot = RuleName("ul006_not_a_robot")
ul007_doctype = RuleName("ul007_doctype")
ul902_outside_roots = RuleName("ul902_outside_roots")
ul011_stale_output = RuleName("ul011_stale_output")

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.meshes.facts import MassFacts, MeshFacts
    from urdf_lint.meshes.store import MeshStore
    from urdf_lint.engine.model import Model
    from urdf_lint.meshes.resolve import MeshRef

# lxml is imported where it is used: `urdf-lint expand` runs in a worker that never needs it

XACRO_DIRECTIVES = {"macro", "property", "arg", "include"}


class Context:
    """What a rule's ``check`` gets besides the model: its options, the consumer targets of the
    run (``targets``), and the mesh look-ups of the run (``meshes``, the run's
    :class:`urdf_lint.meshes.store.MeshStore`: where facts are cached, which texture references
    may be read)."""

    def __init__(self, options: dict[str, Any], mesh_cache_dir: str | None,
                 meshes: MeshStore | None = None, targets: tuple[str, ...] = ("ros",)):
        self.options = options
        self.configs: list[Any] = []    # engine.configs.ConfigDoc of the job's configuration
        self.config_args: dict[str, str] = {}   # the model's xacro args, with their defaults
        self.targets = targets          # the run's consumer targets (LintSettings.targets)
        self.mesh_cache_dir = mesh_cache_dir
        if meshes is None:   # (the mesh modules load where a rule reads a mesh: not in the parent)
            from urdf_lint.meshes.store import MeshStore
            meshes = MeshStore(cache_dir=mesh_cache_dir)
        self.meshes = meshes
        self._refs: dict[tuple[str, str], MeshRef] = {}
        self._mesh_facts: dict[str, MeshFacts] = {}
        self._mass_facts: dict[str, MassFacts] = {}

    def mesh_ref(self, model: Model, uri: str) -> MeshRef:
        from urdf_lint.meshes import resolve as meshes
        key = (model.base_dir, uri)
        if key not in self._refs:
            self._refs[key] = meshes.resolve(model, uri)
        return self._refs[key]

    def mesh(self, path: str) -> Any:
        from urdf_lint.meshes import resolve as meshes
        return meshes.get_mesh(path)

    def mesh_facts(self, path: str) -> MeshFacts:
        """A mesh file's facts, looked up once per model: several rules ask for every mesh
        element (a 200-link robot: 1,200 asks, each a stat of the file and of its digest)."""
        got = self._mesh_facts.get(path)
        if got is None:
            from urdf_lint.meshes import resolve as meshes
            from urdf_lint.meshes.facts import MeshFacts
            got = self._mesh_facts[path] = MeshFacts.from_record(
                meshes.mesh_facts(path, store=self.meshes))
        return got

    def mass_facts(self, path: str) -> MassFacts:
        """A mesh file's volume properties, looked up once per model (like ``mesh_facts``)."""
        got = self._mass_facts.get(path)
        if got is None:
            from urdf_lint.meshes import resolve as meshes
            from urdf_lint.meshes.facts import MassFacts
            got = self._mass_facts[path] = MassFacts.from_record(
                meshes.mass_facts(path, store=self.meshes))
        return got

    def texture_refs(self, path: str) -> list[str]:
        """The image (and MTL) files a mesh refers to; those outside the roots are not read."""
        from urdf_lint.meshes import resolve as meshes
        return meshes.texture_refs(path, self.meshes)


def target_of(el: Any) -> tuple[str, str] | None:
    """("link"|"joint", name) of the nearest enclosing top-level link or joint, for snapshots."""
    while el is not None:
        parent = el.getparent()
        if el.tag in ("link", "joint") and parent is not None and parent.tag == "robot":
            return (el.tag, el.get("name"))
        el = parent
    return None


def classify_xacro(path: str) -> Status | None:
    """None for a candidate model, LIBRARY (only macro/property/arg at top level, no include)
    or NOT_ROBOT."""
    from lxml import etree
    from urdf_lint.core import fsbound
    try:   # a regular file, bounded (a FIFO named as a file never blocks)
        root = fsbound.parse_xml(path, _quick_parser())
    except (etree.XMLSyntaxError, OSError):
        return None  # let expansion report the problem with its location
    if etree.QName(root).localname != "robot":
        return Status.NOT_ROBOT
    includes = False
    for el in root:
        if not isinstance(el.tag, str):
            continue
        q = etree.QName(el)
        if not (q.namespace and "xacro" in q.namespace and q.localname in XACRO_DIRECTIVES):
            return None
        includes = includes or q.localname == "include"
    # a file made of includes may be a robot whose included files emit the links: expansion
    # tells (no link after expansion: a library)
    return None if includes else Status.LIBRARY


def _quick_parser() -> Any:
    from lxml import etree
    return etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False)


def _check_output(job: LintJob, xml: str, out: ModelReport,
                  expand: Callable[[dict[str, str]], str | None]) -> None:
    """UL011 at each checked-in generated file that differs from today's expansion of the
    variant that made it; the outputs become inputs of the model (editing one re-lints the
    model). An untied output (xacro's banner records no args) is current when any configured
    variant of the xacro gives it (``expand(args)``: that variant's XML, or None); else the
    finding names the closest variant."""
    from urdf_lint.discovery.generated import closest_variant, describe_args, stale_at
    from urdf_lint.core.locations import display_path
    others: list[tuple[dict[str, str], str | None]] | None = None
    for output in (job.output or "",) + tuple(job.outputs):
        (out.deps if os.path.exists(output) else out.missing).append(output)
        got = stale_at(output, xml)
        if got is not None and output in job.untied and os.path.exists(output):
            if others is None:
                others = [(dict(v), expand(dict(v))) for v in job.variants]
            args, got = closest_variant(output, [(job.args, xml)] + [
                (a, x) for a, x in others if x is not None])
            if got is not None:
                line, col, what = got
                out.problems.append(Problem.at(ul011_stale_output.CODE,
                                               _untied_message(job, args, what),
                                               (output, line, col)))
                continue
        if got is None and os.path.exists(output):
            out.current_outputs.append(output)
        if got is not None:
            line, col, what = got
            made = f" with {describe_args(job.args)}" if job.args else ""
            out.problems.append(Problem.at(
                ul011_stale_output.CODE,
                f"generated file is stale ({what}): it is not what {display_path(job.entry)} "
                f"expands to today{made}; regenerate it with 'urdf-lint generate'",
                (output, line, col)))


def _untied_message(job: LintJob, closest: dict[str, str], what: str) -> str:
    """UL011 at an untied output no variant gives: the variants it was compared with, the
    closest one and where it first differs."""
    from urdf_lint.discovery.generated import describe_args
    from urdf_lint.core.locations import display_path
    if job.variants:
        tried = (f"any of {len(job.variants) + 1} variants (its configured args and the "
                 f"defaults; closest: {describe_args(closest)}, {what})")
    else:
        tried = f"{describe_args(job.args)} ({what})"
    return (f"generated file is stale, or made with args urdf-lint does not know: it is not "
            f"what {display_path(job.entry)} expands to today with {tried}; add a "
            "[[tool.urdf-lint.models]] entry with its output and args")


def _other_variant(job: LintJob, settings: LintSettings, resolver: Any,
                   out: ModelReport) -> Callable[[dict[str, str]], str | None]:
    """``args -> the XML of that variant of the job's xacro`` (None when it does not expand);
    what it reads becomes an input of the model."""
    def expand(args: dict[str, str]) -> str | None:
        from urdf_lint.expansion import expand_file
        exp = expand_file(job.entry, args, resolver, env_allow=settings.env_allow,
                          expr_policy=settings.expr_policy)
        out.deps += [d for d in exp.deps if d not in out.deps]
        out.missing += [d for d in exp.missing if d not in out.missing]
        out.digests.update(exp.digests)
        return exp.xml if exp.error is None else None
    return expand


def _load(job: LintJob, settings: LintSettings, resolver: Any, out: ModelReport) -> Model | None:
    """The Model of the job, or None (``out`` then says why)."""
    from urdf_lint.engine.model import model_from_xml, parse_urdf_bytes, Model
    entry = job.entry
    problems = out.problems
    if job.kind == "xacro":
        if not job.explicit:
            kind = classify_xacro(entry)
            if kind is not None:
                out.status = kind
                return None
        from urdf_lint.expansion import expand_file
        exp = expand_file(entry, job.args, resolver, env_allow=settings.env_allow,
                          expr_policy=settings.expr_policy, env_set=settings.env_set,
                          arg_origins=dict(job.arg_origins))
        out.env = dict(exp.env)
        out.branches = [list(b) for b in exp.branches]
        out.deps = list(exp.deps)
        out.missing = list(exp.missing)
        out.digests = dict(exp.digests)
        problems.extend(exp.notes)
        if exp.error is not None:
            problems.append(exp.error)
            out.status = Status.FAILED
            return None
        assert exp.xml is not None  # expand_file sets xml or error
        if job.output or job.outputs:
            _check_output(job, exp.xml, out, _other_variant(job, settings, resolver, out))
        try:
            model = model_from_xml(entry, job.args, exp.xml, exp.origins, exp.deps, resolver,
                                   exp.values)
        except Exception as e:  # noqa: BLE001 - lxml refused what xacro produced
            problems.append(_expanded_xml_error(e, exp, entry))
            out.status = Status.FAILED
            return None
        # meshes written relative to the generated URDF (or a configured folder)
        model.mesh_base = job.mesh_base or (os.path.dirname(job.output) if job.output else None)
        if not job.mesh_base and job.output:   # assumed, not configured: see Model
            model.mesh_base_fallback = os.path.dirname(entry)
        if not model.top_links() and not job.explicit:
            out.status = Status.LIBRARY
            out.problems = []
            return None
        if settings.keep_model:  # urdf-lint diff compares the robots themselves
            out.kept_model = KeptModel(exp.xml, exp.origins, exp.values)
        return model
    from urdf_lint.core.hashing import read_recorded
    from urdf_lint.discovery.packages import MAX_SOURCE_BYTES, regular_file
    if not resolver.is_inside(entry):
        problems.append(Problem.at(ul902_outside_roots.CODE,
                                   "this file resolves outside the package roots and the linted "
                                   "repository (a symlink?); it was not read", (entry, 1, 1)))
        out.status = Status.FAILED
        return None
    if not regular_file(entry, MAX_SOURCE_BYTES):
        problems.append(Problem.at(ul001_xml_syntax.CODE,
                                   f"not a regular file of at most {MAX_SOURCE_BYTES >> 20} MiB "
                                   "(a device, FIFO or a huge file?); it was not read",
                                   (entry, 1, 1)))
        out.status = Status.FAILED
        return None
    try:
        data, rec = read_recorded(entry)
        out.digests = {entry: rec}
    except OSError as e:
        problems.append(Problem.at(ul001_xml_syntax.CODE, f"cannot read file: {e.strerror}",
                                   (entry, 1, 1)))
        out.status = Status.FAILED
        return None
    if b"<!DOCTYPE" in data[:4096] or b"<!ENTITY" in data:
        line = data[:data.find(b"<!")].count(b"\n") + 1
        problems.append(Problem.at(ul007_doctype.CODE,
                                   "DOCTYPE/ENTITY declaration in a robot description; remove it "
                                   "(URDF needs none, and urdf-lint never loads DTDs)",
                                   (entry, line, 1)))
    root, origins, errors = parse_urdf_bytes(entry, data)
    problems.extend(errors or ())
    if root is None:
        out.status = Status.FAILED
        return None
    if not job.explicit and _placeholder(root):
        out.status = Status.LIBRARY
        out.problems = []
        return None
    if settings.keep_model:
        out.kept_model = KeptModel(None)   # the parent parses the .urdf itself
    return Model(entry=entry, args={}, root=root, origins=origins, deps=[entry], resolver=resolver)


def _placeholder(root: Any) -> bool:
    """A ``<robot>`` that is no model by design: no name, and no element (an ``empty.urdf``
    included so that "no extras" is the default, the expansion of a macro-only file), or no
    ``<link>`` of its own and xacro elements in it (an extras file an arg or environment
    variable includes, such as jackal's ``custom_example.urdf``): no model to lint."""
    if root.tag != "robot" or root.get("name"):
        return False
    kids = [c for c in root if isinstance(c.tag, str)]
    return not kids or (not any(c.tag == "link" for c in kids) and any(
        isinstance(e.tag, str) and (e.tag.startswith("xacro:") or e.tag.startswith(_XACRO_NS))
        for e in root.iter()))


_XACRO_NS = ("{http://www.ros.org/wiki/xacro}", "{http://ros.org/wiki/xacro}",
             "{http://wiki.ros.org/xacro}")


def _expand_only(job: LintJob, settings: LintSettings, resolver: Any, out: ModelReport) -> None:
    """`urdf-lint expand`: the expansion itself, in a worker too (limits, sandbox). The XML
    comes back as ``kept_model.xml``; the notes and the error as ``problems``."""
    from urdf_lint.expansion import expand_file
    exp = expand_file(job.entry, job.args, resolver, env_allow=settings.env_allow,
                      display_name=job.display_name, expr_policy=settings.expr_policy,
                      env_set=settings.env_set)
    out.deps = list(exp.deps)
    out.problems.extend(exp.notes)
    if exp.error is not None:
        out.problems.append(exp.error)
        out.status = Status.FAILED
    else:
        out.kept_model = KeptModel(exp.xml)


def _expanded_xml_error(e: Exception, exp: Any, entry: str) -> Problem:
    """A located UL001 for an expansion lxml cannot hold (nesting deeper than its limit, a
    huge attribute, a control character an expression produced), at the source line of the
    element the error is in."""
    from urdf_lint.engine.model import element_positions
    msg = " ".join(str(getattr(e, "msg", None) or e).split())
    line = (getattr(e, "position", None) or (0, 0))[0]
    origin = Origin(entry, 1, 1)
    if line:
        positions = element_positions(exp.xml.encode("utf-8", "replace"))
        idx = max((i for i, (ln, _) in enumerate(positions) if ln <= line), default=None)
        if positions and positions[-1][0] < line and len(positions) < len(exp.origins):
            idx = len(positions)  # expat stopped at the same character: the next element
        if idx is not None and idx < len(exp.origins) and exp.origins[idx] is not None:
            origin = exp.origins[idx]
    hint = ""
    if "invalid character" in msg.lower() or "char" in msg.lower():
        hint = " (an expression produced a character XML cannot hold)"
    elif "depth" in msg.lower():
        hint = " (elements nested deeper than 256 levels)"
    elif "limit" in msg.lower():
        hint = " (a text or attribute longer than 10 MB)"
    return Problem.at(ul001_xml_syntax.CODE, f"the expanded URDF is not valid XML: {msg}{hint}",
                      origin)


def _record_reads(out: ModelReport) -> None:
    """Digests of the inputs not recorded at parse time (YAML, meshes, textures), taken here,
    in the worker, right after it used them (see urdf_lint/run/cache.py)."""
    from urdf_lint.core.hashing import file_record
    for d in out.deps:
        if d not in out.digests:
            rec = file_record(d)
            if rec is not None:
                out.digests[d] = rec


def lint_model(job: LintJob, settings: LintSettings) -> tuple[ModelReport, Model | None, Context]:
    """(ModelReport, Model or None, Context) for one job."""
    report, model, ctx = _lint_model(job, settings)
    # the digests of every input not recorded at parse time, here in the worker, on every
    # return path: the parent never hashes inputs again when it writes the cache
    _record_reads(report)
    if job.kind != "expand":
        from urdf_lint.engine.suppress import with_directives
        # which sources hold suppression comments: the parent parses only those, also when
        # the result comes from the cache (a warm run reads no source file)
        report.directive_files = with_directives(report.deps)
    return report, model, ctx


def _lint_model(job: LintJob, settings: LintSettings) -> tuple[ModelReport, Model | None, Context]:
    from urdf_lint.discovery.packages import from_settings
    out = ModelReport(job.entry, dict(job.args), Status.MODEL, deps=[job.entry])
    ctx = Context({}, settings.mesh_cache_dir, targets=settings.targets)
    resolver = from_settings(settings.resolver)
    if job.kind == "expand":  # reads no mesh: the mesh module is not even imported
        _expand_only(job, settings, resolver, out)
        return out, None, ctx
    # texture/MTL references stay in the roots; texture scans are cached with the mesh facts;
    # a render run draws the meshes the rules measured: they are loaded once and kept
    from urdf_lint.meshes.store import MeshStore
    ctx.meshes = MeshStore(resolver.is_inside, settings.mesh_cache_dir,
                           bool(settings.render_dir or settings.diff_render))
    model = _load(job, settings, resolver, out)
    if model is None:
        return out, None, ctx
    problems = out.problems
    if model.root.tag != "robot":
        problems.append(Problem.at(ul006_not_a_robot.CODE,
                                   f"root element is <{model.root.tag}>, not <robot>",
                                   model.origin(model.root)))
        out.status = Status.FAILED
        return out, None, ctx
    if not model.top_links():
        problems.append(Problem.at(ul006_not_a_robot.CODE,
                                   "robot has no <link>: a URDF needs at least one link",
                                   model.origin(model.root)))

    from urdf_lint.engine.registry import run_rules
    fixer = None
    if job.configs:   # the SRDF and YAML files that configure this robot (discovery.configs)
        from urdf_lint.engine.configs import known_args, load_configs
        ctx.configs = load_configs(job, settings, resolver, model, out)
        ctx.config_args = known_args(job)
    for rule, el, msg, sev, req, cause, table, related in run_rules(
            "model", settings.selected, settings.options, model, ctx, out.internal,
            f" on {job.entry}", with_fix=True, with_table=True, with_related=True):
        if isinstance(el, Origin):   # a place in a source that no element has (a line)
            line_fix = None
            if req is not None and req.kind == "rename_at":
                from urdf_lint.engine.api import read_source
                from urdf_lint.fix.kinds.rename_at import fix_at
                line_fix = fix_at(el, read_source(el.file), req)
            p = Problem.at(rule.code, msg, el, None, sev, consumers=table, fix=line_fix,
                           related=_related(model, related))
        else:
            fix = None
            from urdf_lint.fix.fixes import Fixer
            fixer = fixer or Fixer(model)
            if req is not None:
                fix = fixer.fix(el, req)
            value_from = fixer.value_from(el, fixer.traced(req), msg)
            p = Problem.at(rule.code, msg, model.origin(el), target_of(el), sev, fix=fix,
                           consumers=table, value_from=value_from)
        if cause is not None:   # one finding per root cause, this problem one instance of it
            p = p.replace(code=cause.code, message=cause.message, detail=msg, group=cause.key)
        problems.append(p)

    out.deps, out.missing = _mesh_deps(model, ctx, out.deps)
    out.name = model.name
    o = model.origin(model.root)
    out.name_origin = Origin(o.file, o.line, o.col)
    out.links = len(model.top_links())
    out.joints = len(model.top_joints())
    out.meshes = len(list(model.root.iter("mesh")))
    return out, model, ctx


def _mesh_deps(model: Model, ctx: Context, deps: list[str]) -> tuple[list[str], list[str]]:
    """(deps + every mesh / texture the model points at that resolved inside the roots,
    the ones that were looked for and are missing)."""
    from urdf_lint.meshes import resolve as meshes
    mesh_deps: list[str] = []
    missing: list[str] = []
    for m in list(model.root.iter("mesh")) + list(model.root.iter("texture")):
        uri = m.get("filename")
        if uri:
            ref = ctx.mesh_ref(model, uri)
            if ref.path and ref.status is meshes.MeshStatus.OK:
                mesh_deps.append(ref.path)
                for t in ctx.texture_refs(ref.path) if m.tag == "mesh" else ():
                    if model.resolver is None or model.resolver.is_inside(t):
                        # references outside the roots are never deps
                        (mesh_deps if os.path.exists(t) else missing).append(t)
            elif ref.path and ref.status is meshes.MeshStatus.NOT_FOUND:
                missing.append(ref.path)
    return list(dict.fromkeys(list(deps) + mesh_deps)), sorted(set(missing))


def run_job(job: LintJob, settings: LintSettings) -> ModelReport:
    """Lint one job in process (no rendering)."""
    return lint_model(job, settings)[0]


def _related(model: Any, related: Any) -> Any:
    """Where a configuration finding's related location is: the robot element's xacro line,
    or a place in another configuration file a rule gives as an Origin (the SRDF group a
    MoveIt controller serves)."""
    if related is None:
        return ()
    return related if isinstance(related, Origin) else model.origin(related)
