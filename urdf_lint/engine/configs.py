"""The configuration files of one robot, loaded in its worker: SRDF (a ``.srdf.xacro`` expanded
like the robot, with source lines) and YAML (every node with its line), for the rules that
check them against the robot (UL710-UL749 ros2_control and controllers, UL750-UL799 SRDF and
MoveIt). Which files configure which model is discovery's (:mod:`urdf_lint.discovery.configs`);
every file read here becomes an input of the model (editing one re-lints it).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from urdf_lint.core.findings import Problem
from urdf_lint.core.jobs import LintJob, LintSettings, ModelReport
from urdf_lint.core.locations import Origin
from urdf_lint.core.codes import RuleName

ul799_config_unreadable = RuleName("ul799_config_unreadable")


@dataclass
class YNode:
    """One YAML node: ``value`` (a dict of str -> YNode, a list of YNode, or a scalar) and where
    it is written (1-based line and column); ``key_line``/``key_col`` where the key naming it is."""
    value: Any
    line: int
    col: int
    key_line: int = 0
    key_col: int = 0

    def get(self, key: str) -> "YNode | None":
        return self.value.get(key) if isinstance(self.value, dict) else None

    def items(self) -> list[tuple[str, "YNode"]]:
        return list(self.value.items()) if isinstance(self.value, dict) else []

    def seq(self) -> list["YNode"]:
        """The items of a list, or this node itself for a scalar (``joint: j1`` and
        ``joints: [j1]`` alike)."""
        if isinstance(self.value, list):
            return self.value
        return [] if isinstance(self.value, dict) else [self]

    def plain(self) -> Any:
        if isinstance(self.value, dict):
            return {k: v.plain() for k, v in self.value.items()}
        if isinstance(self.value, list):
            return [v.plain() for v in self.value]
        return self.value


@dataclass
class ConfigDoc:
    """A configuration file of the robot: ``kind`` (see ``LintJob.configs``), its path, how it
    was tied to the model, and its content: ``root`` (a YNode, or the SRDF's root element) and,
    for an SRDF, ``origins`` (element -> Origin, the xacro line of a ``.srdf.xacro``)."""
    kind: str
    path: str
    how: str
    root: Any
    origins: dict[Any, Origin] = field(default_factory=dict)

    def key_at(self, node: YNode) -> Origin:
        """Where the key naming a YAML node is written (the node's own place when it has none)."""
        return Origin(self.path, node.key_line, node.key_col) if node.key_line else self.at(node)

    def at(self, node: Any) -> Origin:
        """Where a YAML node or an SRDF element is written."""
        if isinstance(node, YNode):
            return Origin(self.path, node.line, node.col)
        el = node
        while el is not None:
            o = self.origins.get(el)
            if o is not None:
                return o
            el = el.getparent()
        return Origin(self.path, 1, 1)


def yaml_tree(path: str, text: str) -> YNode | None:
    """The YAML document with every node's position (None for an empty document)."""
    import yaml
    loader = yaml.SafeLoader(text)
    try:
        node = loader.get_single_node()
        return _convert(node, loader) if node is not None else None
    finally:
        loader.dispose()


def _convert(node: Any, loader: Any, key: Any = None) -> YNode:
    import yaml
    line, col = node.start_mark.line + 1, node.start_mark.column + 1
    kl, kc = (key.start_mark.line + 1, key.start_mark.column + 1) if key is not None else (0, 0)
    if isinstance(node, yaml.MappingNode):
        out: dict[str, YNode] = {}
        for k, v in node.value:
            name = str(loader.construct_object(k, deep=True)) if isinstance(k, yaml.ScalarNode) else ""
            out.setdefault(name, _convert(v, loader, k))
        return YNode(out, line, col, kl, kc)
    if isinstance(node, yaml.SequenceNode):
        return YNode([_convert(v, loader) for v in node.value], line, col, kl, kc)
    return YNode(loader.construct_object(node), line, col, kl, kc)


def known_args(job: LintJob) -> dict[str, str]:
    """The model's xacro args: those of the job, and the literal defaults the entry file
    declares (``<xacro:arg name="tf_prefix" default=""/>``): what a launch substitution of the
    same name in a controller YAML stands for in this variant."""
    out: dict[str, str] = {}
    if job.kind == "xacro":
        from lxml import etree
        from urdf_lint.core import fsbound
        try:
            root = fsbound.parse_xml(job.entry, etree.XMLParser(resolve_entities=False,
                                                                no_network=True, load_dtd=False))
        except (etree.XMLSyntaxError, OSError):
            root = None
        for el in root if root is not None else ():
            if isinstance(el.tag, str) and etree.QName(el).localname == "arg" and \
                    el.get("name") and "$" not in el.get("default", "$"):
                out[el.get("name")] = el.get("default")
    out.update(job.args)
    return out


def load_configs(job: LintJob, settings: LintSettings, resolver: Any, model: Any,
                 out: ModelReport) -> list[ConfigDoc]:
    """The job's configuration files, read and parsed; what cannot be read is one UL799 at the
    file. An SRDF tied by convention (not by ``.setup_assistant`` or the config) is kept only
    when its robot name is the model's; an ``initial_positions.yaml`` the robot's xacro reads
    itself is its input, not a configuration checked by name."""
    docs = []
    read = set(out.deps)   # the files the robot's expansion read (xacro.load_yaml)
    for kind, path, how in job.configs:
        if kind == "initial-positions" and path in read:
            continue   # the robot's own input, keyed as its xacro looks it up (UL713 checks
            #            the <ros2_control> initial_value it gives)
        if path not in out.deps:
            out.deps.append(path)
        try:
            doc = (_load_srdf(path, job, settings, resolver, out) if kind == "srdf"
                   else _load_yaml(path, kind, how))
        except _Unreadable as e:
            out.problems.append(Problem.at(ul799_config_unreadable.CODE,
                                           f"{kind} file not checked against the robot: {e}",
                                           e.where or (path, 1, 1)))
            continue
        if doc is None:
            continue
        doc.kind, doc.how = kind, how
        if kind == "srdf" and how.startswith("package") and doc.root.get("name") != model.name:
            continue   # another robot's SRDF in the same package
        if kind == "controllers" and how == "package-shared" and not _names_any(doc.root, model):
            continue   # another robot's controllers (the 2F-85's YAML beside the 2F-140)
        docs.append(doc)
    if not any(d.kind == "srdf" for d in docs):   # MoveIt's files beside another robot's SRDF
        docs = [d for d in docs if d.kind == "controllers" or not d.how.startswith("package")]
    return docs


JOINT_KEYS = ("joints", "joint", "left_wheel_names", "right_wheel_names")


def _names_any(root: YNode, model: Any) -> bool:
    """Whether a controller YAML found by the package convention is about this robot: it
    names no joint, or one of the robot's, or one built by a launch substitution."""
    found: list[str] = []

    def walk(node: YNode) -> None:
        for k, v in node.items():
            if k in JOINT_KEYS:
                found.extend(n.value for n in v.seq() if isinstance(n.value, str))
            elif isinstance(v.value, dict):
                walk(v)
    walk(root)
    return not found or any(n in model.joints or "$(" in n for n in found)


class _Unreadable(Exception):
    def __init__(self, why: str, where: Any = None):
        super().__init__(why)
        self.where = where


def _load_yaml(path: str, kind: str, how: str) -> ConfigDoc | None:
    from urdf_lint.core import fsbound
    try:
        text = fsbound.read_text(path)
    except (OSError, UnicodeDecodeError) as e:
        raise _Unreadable(f"cannot read it ({getattr(e, 'strerror', None) or e})") from None
    import yaml
    try:
        root = yaml_tree(path, text)
    except yaml.YAMLError as e:
        mark = getattr(e, "problem_mark", None)
        where = (path, mark.line + 1, mark.column + 1) if mark is not None else None
        raise _Unreadable(f"invalid YAML ({getattr(e, 'problem', None) or e})", where) from None
    return ConfigDoc(kind, path, how, root) if root is not None else None


def _load_srdf(path: str, job: LintJob, settings: LintSettings, resolver: Any,
               out: ModelReport) -> ConfigDoc:
    if path.endswith(".xacro"):
        from urdf_lint.expansion import expand_file
        exp = expand_file(path, job.args, resolver, env_allow=settings.env_allow,
                          expr_policy=settings.expr_policy, env_set=settings.env_set)
        out.deps += [d for d in exp.deps if d not in out.deps]
        out.missing += [d for d in exp.missing if d not in out.missing]
        out.digests.update(exp.digests)
        if exp.error is not None:
            raise _Unreadable(f"it does not expand ({exp.error.message})",
                              (exp.error.file, exp.error.line, exp.error.col))
        from urdf_lint.engine.model import model_from_xml
        try:
            m = model_from_xml(path, job.args, exp.xml or "", exp.origins, exp.deps, resolver)
        except Exception as e:  # noqa: BLE001 - lxml refused what xacro produced
            raise _Unreadable(f"its expansion is not XML ({e})") from None
        return ConfigDoc("srdf", path, "", m.root, dict(m.origins))
    from urdf_lint.core import fsbound
    from urdf_lint.engine.model import parse_urdf_bytes
    try:
        data = fsbound.read_bytes(path)
    except OSError as e:
        raise _Unreadable(f"cannot read it ({e.strerror or e})") from None
    root, origins, errors = parse_urdf_bytes(path, data)
    if root is None:
        first = errors[0] if errors else None
        raise _Unreadable(f"not XML ({first.message if first else 'unreadable'})",
                          (first.file, first.line, first.col) if first else None)
    return ConfigDoc("srdf", path, "", root, dict(origins))
