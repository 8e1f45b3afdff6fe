"""``textDocument/completion``: rule codes in a suppression comment, macros (with their
required parameters as a snippet; a block macro as an open/close pair), ``package://`` files,
macro parameters, URDF attributes and elements, args, packages, names in an expression, link
and joint names (also those of the last model that expanded, while the file is mid-edit)."""
from __future__ import annotations

import os
import re
from typing import Callable

from lsprotocol import types

from urdf_lint.lsp.cursor import At, enclosing_macro, params_of
from urdf_lint.lsp.index import macro_params
from urdf_lint.lsp.methods import completion_xacro, config_definition
from urdf_lint.lsp.services import Services

Items = list[types.CompletionItem]
OPTIONS = types.CompletionOptions(trigger_characters=[":", "{", " ", "/", '"'])


def handle(sv: Services, params: types.CompletionParams) -> types.CompletionList:
    path, pos = params_of(params)
    return types.CompletionList(is_incomplete=False, items=completion(sv, path, pos))


def completion(sv: Services, path: str, pos: types.Position) -> Items:
    first = config_definition.completion(sv, path, pos)   # an SRDF or controller YAML
    if first is not None:
        return first
    at = At(sv.doc(path), pos)
    for complete in COMPLETERS:
        got = complete(sv, path, at)
        if got is not None:
            return _refine(sv, path, at, complete, got)
    return []


def _refine(sv: Services, path: str, at: At, completer: Callable[[Services, str, At],
                                                                  Items | None], items: Items
            ) -> Items:
    """Mid-edit (:mod:`.completion_xacro`): a block macro as an open/close pair; the link
    and joint names of the last model of each variant that expanded."""
    if completer is _macros:
        return completion_xacro.block_pairs(sv, path, items)
    if completer is _references:
        return completion_xacro.with_last_good(sv, path, at, items)
    return items


# Each completer returns its items where the cursor is its kind of place, else None (the next
# one is asked); they are asked in the order of COMPLETERS.
def _codes(sv: Services, path: str, at: At) -> Items | None:
    """Rule codes in a suppression comment."""
    if not (at.comment and re.search(r"urdf[-_]lint\s*:\s*[\w-]*\s.*$", at.before)):
        return None
    from urdf_lint.engine.registry import catalogue
    return [types.CompletionItem(label=code, detail=e.name,
                                 kind=types.CompletionItemKind.EnumMember)
            for code, e in catalogue().items()]


def _macros(sv: Services, path: str, at: At) -> Items | None:
    """Macro names after ``<xacro:``, with their required parameters as a snippet."""
    if not re.search(r"<xacro:[\w-]*$", at.before):
        return None
    items: dict[str, types.CompletionItem] = {}
    for d in sv.index.decls(path, "macro"):
        if d.name in items:
            continue
        req = [n for n, v in macro_params(d.attrs.get("params", ""))
               if v is None and not n.startswith("*")]
        snippet = d.name + "".join(f' {n}="${{{i}}}"' for i, n in enumerate(req, 1)) + "/>"
        items[d.name] = types.CompletionItem(
            label=d.name, kind=types.CompletionItemKind.Function,
            detail=f"macro ({os.path.basename(d.file)}:{d.line})",
            insert_text=snippet, insert_text_format=types.InsertTextFormat.Snippet)
    return list(items.values())


def _package_files(sv: Services, path: str, at: At) -> Items | None:
    pm = re.search(r"package://([\w-]+)/([^\"'\s]*)$", at.before)
    return package_files(sv, pm.group(1), pm.group(2)) if pm else None


def _in_attribute_name(at: At) -> bool:
    """Inside a tag where an attribute name goes (not its value, not the tag's name)."""
    return bool(at.in_tag and at.value is None and at.tag) and \
        not re.search(r"<[\w:.-]*$", at.before)


def _macro_params(sv: Services, path: str, at: At) -> Items | None:
    """Parameter names inside a macro call (those not written yet)."""
    if not (_in_attribute_name(at) and at.tag and at.tag.startswith("xacro:")):
        return None
    items: dict[str, types.CompletionItem] = {}
    name = at.tag.split(":", 1)[1]
    start = at.doc.text.rfind("<", 0, at.off)
    written = set(re.findall(r"([\w-]+)\s*=", at.doc.text[start:at.off]))
    for d in sv.index.decls(path, "macro", name)[:1]:
        for n, default in macro_params(d.attrs.get("params", "")):
            if not n.startswith("*") and n not in written:
                items[n] = types.CompletionItem(
                    label=n, kind=types.CompletionItemKind.Property,
                    detail="required" if default is None else f"default {default}",
                    insert_text=f'{n}="${{1}}"',
                    insert_text_format=types.InsertTextFormat.Snippet)
    return list(items.values())


def _urdf_attributes(sv: Services, path: str, at: At) -> Items | None:
    """The attributes of a URDF element."""
    if not (_in_attribute_name(at) and at.tag and not at.tag.startswith("xacro:")):
        return None
    attrs = URDF_ATTRIBUTES.get(at.tag.split(":")[-1])
    if not attrs:
        return None
    return [types.CompletionItem(label=a, kind=types.CompletionItemKind.Property,
                                 insert_text=f'{a}="${{1}}"',
                                 insert_text_format=types.InsertTextFormat.Snippet)
            for a in attrs]


def _elements(sv: Services, path: str, at: At) -> Items | None:
    if not re.search(r"<[\w-]*$", at.before) or at.comment:
        return None
    return [types.CompletionItem(label=e, kind=types.CompletionItemKind.Keyword)
            for e in URDF_ATTRIBUTES]


def _args(sv: Services, path: str, at: At) -> Items | None:
    if not re.search(r"\$\(arg\s+[\w-]*$", at.before):
        return None
    items: dict[str, types.CompletionItem] = {}
    for d in sv.index.decls(path, "arg"):
        items.setdefault(d.name, types.CompletionItem(
            label=d.name, kind=types.CompletionItemKind.Variable,
            detail=f"arg, default {d.attrs.get('default')!r}"))
    return list(items.values())


def _packages(sv: Services, path: str, at: At) -> Items | None:
    if not re.search(r"(package://|\$\(find\s+)[\w-]*$", at.before):
        return None
    ws = sv.ws
    names = set(ws.resolver.explicit) | set(ws.resolver.scanned) if ws else set()
    return [types.CompletionItem(label=n, kind=types.CompletionItemKind.Module)
            for n in sorted(names)]


def _expression(sv: Services, path: str, at: At) -> Items | None:
    """Inside ``${...}``: the enclosing macro's parameters, then the properties."""
    if at.expr() is None:
        return None
    items: dict[str, types.CompletionItem] = {}
    m = enclosing_macro(sv, path, at)
    if m is not None:
        for n, _default in macro_params(m.attrs.get("params", "")):
            if not n.startswith("*"):
                items[n] = types.CompletionItem(label=n, kind=types.CompletionItemKind.Variable,
                                                detail=f"parameter of {m.name}")
    for d in sv.index.decls(path, "property"):
        items.setdefault(d.name, types.CompletionItem(
            label=d.name, kind=types.CompletionItemKind.Constant,
            detail=f"property = {d.attrs.get('value', '')}"[:80]))
    return list(items.values())


def _references(sv: Services, path: str, at: At) -> Items | None:
    """Link (or joint) names of the models this file is part of, in a reference."""
    if not (at.value is not None and at.tag in ("parent", "child", "gazebo", "mimic") and
            at.attr in ("link", "reference", "joint")):
        return None
    items: dict[str, types.CompletionItem] = {}
    want = "joint" if at.attr == "joint" else "link"
    for view in sv.views():
        if path not in view.files:
            continue
        for (k, n) in view.named:
            if k == want or at.attr == "reference":
                items.setdefault(n, types.CompletionItem(
                    label=n, kind=types.CompletionItemKind.Reference,
                    detail=f"{k} in {view.name}"))
    return list(items.values())


COMPLETERS: tuple[Callable[[Services, str, At], Items | None], ...] = (
    _codes, _macros, _package_files, _macro_params, _urdf_attributes, _elements, _args,
    _packages, _expression, _references)


# the URDF schema's elements and their attributes (urdfdom, plus the common ROS extensions)
URDF_ATTRIBUTES = {
    "robot": ["name", "version"], "link": ["name", "type"], "joint": ["name", "type"],
    "parent": ["link"], "child": ["link"], "origin": ["xyz", "rpy"], "axis": ["xyz"],
    "limit": ["lower", "upper", "effort", "velocity"], "dynamics": ["damping", "friction"],
    "mimic": ["joint", "multiplier", "offset"], "calibration": ["rising", "falling"],
    "safety_controller": ["soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"],
    "inertial": [], "mass": ["value"],
    "inertia": ["ixx", "ixy", "ixz", "iyy", "iyz", "izz"], "visual": ["name"],
    "collision": ["name"], "geometry": [], "box": ["size"], "cylinder": ["radius", "length"],
    "sphere": ["radius"], "mesh": ["filename", "scale"], "material": ["name"],
    "color": ["rgba"], "texture": ["filename"], "transmission": ["name"],
    "gazebo": ["reference"], "ros2_control": ["name", "type"],
}
MAX_LISTED = 200


def package_files(sv: Services, package: str, partial: str) -> Items:
    """Files and folders below a package for ``package://pkg/partial`` (inside the roots)."""
    ws = sv.ws
    if ws is None:
        return []
    try:
        base = os.path.realpath(str(ws.resolver.find(package)))
    except Exception:  # noqa: BLE001 - an unknown package: nothing to list
        return []
    if not base:
        return []
    folder = os.path.realpath(os.path.join(base, os.path.dirname(partial)))
    if not (folder == base or folder.startswith(base + os.sep)) or \
            not ws.resolver.is_inside(folder):
        return []
    out = []
    try:
        from urdf_lint.core import fsbound
        names = sorted(fsbound.list_dir(folder))[:MAX_LISTED]
    except OSError:
        return []
    for n in names:
        if n.startswith("."):
            continue
        is_dir = os.path.isdir(os.path.join(folder, n))
        out.append(types.CompletionItem(
            label=n + ("/" if is_dir else ""),
            kind=types.CompletionItemKind.Folder if is_dir else types.CompletionItemKind.File))
    return out
