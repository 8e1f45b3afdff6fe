"""Lint one model: expand (or parse) it, build the Model, run the selected rules.

``run_job`` takes and returns plain data, so it runs the same in process and in a worker.
"""
from __future__ import annotations

import os
import traceback

from .locations import Origin

XACRO_DIRECTIVES = {"macro", "property", "arg", "include"}


class Context:
    """What a rule's ``check`` gets besides the model."""

    def __init__(self, options: dict, mesh_cache_dir: str | None):
        self.options = options
        self.mesh_cache_dir = mesh_cache_dir
        self._refs: dict = {}

    def mesh_ref(self, model, uri):
        from . import meshes
        key = (model.base_dir, uri)
        if key not in self._refs:
            self._refs[key] = meshes.resolve(model, uri)
        return self._refs[key]

    def mesh(self, path):
        from . import meshes
        return meshes.get_mesh(path)

    def mesh_facts(self, path):
        from . import meshes
        return meshes.mesh_facts(path, self.mesh_cache_dir)


def _finding(code, message, origin: Origin | tuple, target=None):
    o = origin
    d = {"code": code, "message": message, "file": o[0], "line": o[1], "col": o[2],
         "chain": [list(c) for c in (o[3] if len(o) > 3 else ())]}
    if target:
        d["target"] = target
    return d


def _target(el):
    """("link"|"joint", name) of the nearest enclosing top-level link or joint, for snapshots."""
    while el is not None:
        parent = el.getparent()
        if el.tag in ("link", "joint") and parent is not None and parent.tag == "robot":
            return [el.tag, el.get("name")]
        el = parent
    return None


def classify_xacro(path: str) -> str:
    """'candidate', 'library' (only macro/property/arg/include at top level) or 'not-robot'."""
    from lxml import etree
    try:
        root = etree.parse(path, _quick_parser()).getroot()
    except (etree.XMLSyntaxError, OSError):
        return "candidate"  # let expansion report the problem with its location
    if etree.QName(root).localname != "robot":
        return "not-robot"
    for el in root:
        if not isinstance(el.tag, str):
            continue
        q = etree.QName(el)
        if not (q.namespace and "xacro" in q.namespace and q.localname in XACRO_DIRECTIVES):
            return "candidate"
    return "library"


def _quick_parser():
    from lxml import etree
    return etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False)


def _expanded_xml_error(e: Exception, exp, entry: str) -> dict:
    """A located UL001 for an expansion lxml cannot hold (nesting deeper than its limit, a
    huge attribute, a control character an expression produced), at the source line of the
    element the error is in."""
    from .model import element_positions
    msg = " ".join(str(getattr(e, "msg", None) or e).split())
    line = (getattr(e, "position", None) or (0, 0))[0]
    origin = (entry, 1, 1, ())
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
    return _finding("UL001", f"the expanded URDF is not valid XML: {msg}{hint}", origin)


def _record_reads(out: dict) -> None:
    """Digests of the inputs not recorded at parse time (YAML, meshes, textures), taken here,
    in the worker, right after it used them (see urdf_lint/cache.py)."""
    from .cache import file_record
    digests = out.setdefault("digests", {})
    for d in out["deps"]:
        if d not in digests:
            rec = file_record(d)
            if rec is not None:
                digests[d] = rec


def run_job(job: dict, settings: dict) -> dict:
    from .packages import PackageResolver
    entry = job["entry"]
    out = {"entry": entry, "args": job.get("args", {}), "status": "model", "deps": [entry],
           "findings": [], "stats": {}, "internal": []}
    resolver = PackageResolver.from_dict(settings["resolver"])
    findings = out["findings"]
    from . import meshes as _meshes
    _meshes.set_confinement(resolver.is_inside)
    if job["kind"] == "expand":  # `urdf-lint expand`: the expansion itself, in a worker too
        from .expand import expand_file
        exp = expand_file(entry, job.get("args", {}), resolver,
                          env_allow=settings.get("env_allow", ()),
                          display_name=job.get("display_name"),
                          expr_policy=settings.get("expr_policy"))
        out.update(status="failed" if exp.error else "model", deps=list(exp.deps), xml=exp.xml,
                   notes=list(exp.notes), error=exp.error)
        return out
    from .model import model_from_xml, parse_urdf_bytes, Model  # lxml: not needed by expand

    if job["kind"] == "xacro":
        if not job.get("explicit"):
            kind = classify_xacro(entry)
            if kind != "candidate":
                out["status"] = kind
                return out
        from .expand import expand_file
        exp = expand_file(entry, job.get("args", {}), resolver,
                          env_allow=settings.get("env_allow", ()),
                          expr_policy=settings.get("expr_policy"))
        out["deps"] = list(exp.deps)
        out["missing"] = list(exp.missing)
        out["digests"] = dict(exp.digests)
        findings.extend(exp.notes)
        if exp.error is not None:
            findings.append(exp.error)
            out["status"] = "failed"
            return out
        try:
            model = model_from_xml(entry, job.get("args", {}), exp.xml, exp.origins, exp.deps,
                                   resolver)
        except Exception as e:  # noqa: BLE001 - lxml refused what xacro produced
            findings.append(_expanded_xml_error(e, exp, entry))
            out["status"] = "failed"
            return out
        if not model.top_links() and not job.get("explicit"):
            out["status"] = "library"
            out["findings"] = []
            return out
    else:
        from .packages import MAX_SOURCE_BYTES, regular_file
        if not resolver.is_inside(entry):
            findings.append(_finding("UL902", "this file resolves outside the package roots and "
                                     "the linted repository (a symlink?); it was not read",
                                     (entry, 1, 1)))
            out["status"] = "failed"
            return out
        if not regular_file(entry, MAX_SOURCE_BYTES):
            findings.append(_finding("UL001", "not a regular file of at most "
                                     f"{MAX_SOURCE_BYTES >> 20} MiB (a device, FIFO or a huge "
                                     "file?); it was not read", (entry, 1, 1)))
            out["status"] = "failed"
            return out
        try:
            from .cache import file_record
            before = os.stat(entry)
            with open(entry, "rb") as f:
                data = f.read()
            rec = file_record(entry, data)
            if rec is not None:
                rec[0] = [before.st_size, before.st_mtime_ns]
                out["digests"] = {entry: rec}
        except OSError as e:
            findings.append(_finding("UL001", f"cannot read file: {e.strerror}", (entry, 1, 1)))
            out["status"] = "failed"
            return out
        if b"<!DOCTYPE" in data[:4096] or b"<!ENTITY" in data:
            line = data[:data.find(b"<!")].count(b"\n") + 1
            findings.append(_finding("UL007", "DOCTYPE/ENTITY declaration in a robot description; "
                                     "remove it (URDF needs none, and urdf-lint never loads DTDs)",
                                     (entry, line, 1)))
        root, origins, error = parse_urdf_bytes(entry, data)
        if error:
            findings.append(error)
        if root is None:
            out["status"] = "failed"
            return out
        model = Model(entry=entry, args={}, root=root, origins=origins, deps=[entry],
                      resolver=resolver)

    if model.root.tag != "robot":
        findings.append(_finding("UL006", f"root element is <{model.root.tag}>, not <robot>",
                                 model.origin(model.root)))
        out["status"] = "failed"
        return out
    if not model.top_links():
        findings.append(_finding("UL006", "robot has no <link>: a URDF needs at least one link",
                                 model.origin(model.root)))

    from .registry import load_rules
    rules = load_rules()
    ctx = Context({}, settings.get("mesh_cache_dir"))
    for code in settings["selected"]:
        rule = rules.get(code)
        if rule is None or rule.check is None:
            continue
        opts = dict(rule.options)
        opts.update(settings.get("options", {}).get(code, {}))
        ctx.options = opts
        try:
            for item in rule.check(model, ctx):
                el, msg = item[0], item[1]
                findings.append(_finding(code, msg, model.origin(el), _target(el)))
        except Exception:  # noqa: BLE001 - a crashing rule must not hide the others
            out["internal"].append(f"rule {code} crashed on {entry}:\n{traceback.format_exc()}")

    # dependencies: every mesh / texture the model points at (resolved, inside the roots)
    mesh_deps, missing = [], []
    from . import meshes
    for m in list(model.root.iter("mesh")) + list(model.root.iter("texture")):
        uri = m.get("filename")
        if uri:
            ref = ctx.mesh_ref(model, uri)
            if ref.path and ref.problem is None:
                mesh_deps.append(ref.path)
                for t in meshes.texture_refs(ref.path) if m.tag == "mesh" else ():
                    if resolver.is_inside(t):  # references outside the roots are never deps
                        (mesh_deps if os.path.exists(t) else missing).append(t)
            elif ref.path and ref.problem == "UL401":
                missing.append(ref.path)
    out["deps"] = list(dict.fromkeys(list(out["deps"]) + mesh_deps))
    _record_reads(out)
    out["missing"] = sorted(set(missing))
    o = model.origin(model.root)
    out["stats"] = {"name": model.name, "name_loc": [o.file, o.line, o.col],
                    "links": len(model.top_links()),
                    "joints": len(model.top_joints()),
                    "meshes": len(list(model.root.iter("mesh")))}
    if settings.get("render_dir"):
        from .render import render_model
        from .registry import load_rules as _lr
        sev = {c: r.severity for c, r in _lr().items()}
        shown = [dict(f, severity=sev.get(f["code"], "error")) for f in findings]
        out["stats"]["snapshot"] = render_model(model, ctx, shown, settings["render_dir"],
                                                settings.get("render_base"),
                                                rrd=settings.get("render_rrd", True))
    return out
