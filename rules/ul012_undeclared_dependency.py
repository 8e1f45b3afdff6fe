"""A `package://NAME/...` mesh or texture, a file read from another package, or `$(find NAME)`
written in the model's own files (an include, an arg's default, a path in an element's text
such as a controllers file handed to a plugin) names a package that the model's own
`package.xml` does not declare as a dependency (`<depend>`, `<exec_depend>`,
`<build_export_depend>`, or `<run_depend>` in format 1). It is reported at the line in the
model's own package: the `$(find)`, or the macro call that made the element.

Why: `rosdep install` and the build farm install only declared dependencies: on a fresh machine
or in a released binary the description loads without those meshes or includes (RViz shows
nothing, `robot_state_publisher` fails on the include). Each package is reported once, with
every reference to it listed under it.

How to fix: Add `<exec_depend>NAME</exec_depend>` (or `<depend>`) to the package.xml of the
package that holds the model.
"""
CODE = "UL012"
NAME = "undeclared-dependency"
SEVERITY = "warning"
FAIL = """<robot name="r">
  <link name="a"><visual><geometry><mesh filename="package://other_meshes/meshes/part.stl"/></geometry></visual></link>
</robot>
"""
FAIL_AT = [(2, 36)]
PASS = """<robot name="r">
  <link name="a"><visual><geometry><mesh filename="package://example_pkg/meshes/part.stl"/></geometry></visual></link>
</robot>
"""
import os
import re

from typing import TYPE_CHECKING, Any, Iterator
from urdf_lint.engine.api import Cause, Origin, Report, display_path, read_source

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._meshes import TETRA_STL
from urdf_lint.rules._schema import urdf_iter

EXAMPLE_FILES = {
    "third_party/other_meshes/package.xml":
        '<?xml version="1.0"?>\n<package format="3"><name>other_meshes</name><version>0.0.0'
        '</version><description>t</description><maintainer email="a@b.c">t</maintainer>'
        '<license>BSD</license></package>\n',
    "third_party/other_meshes/meshes/part.stl": TETRA_STL,
    "meshes/part.stl": TETRA_STL,
}

DEPEND_TAGS = ("depend", "exec_depend", "build_export_depend", "run_depend")
_DEP = re.compile(r"<(" + "|".join(DEPEND_TAGS) + r")(?:\s[^>]*)?>\s*([^<\s]+)\s*</\1>")
_NAME = re.compile(r"<name>\s*([^<\s]+)\s*</name>")
_COMMENT = re.compile(r"<!--.*?-->", re.S)
_FIND = re.compile(r"\$\(\s*find\s+([^)\s]+)\s*\)")


def own_package(model: "Model") -> tuple[str, str, set[str]] | None:
    """(name, package.xml path, declared dependencies) of the package holding the model's
    entry (the nearest package.xml above it, inside the package roots), or None."""
    resolver = model.resolver
    d = os.path.dirname(os.path.abspath(model.entry))
    while True:
        pxml = os.path.join(d, "package.xml")
        if resolver is not None and not resolver.is_inside(d):
            return None
        if os.path.isfile(pxml):
            data = read_source(pxml, 1 << 20)   # a regular file of bounded size (the boundary)
            if data is None:
                return None
            text = _COMMENT.sub("", data.decode("utf-8", "replace"))
            m = _NAME.search(text)
            return (m.group(1) if m else os.path.basename(d), pxml,
                    {x.group(2) for x in _DEP.finditer(text)})
        up = os.path.dirname(d)
        if up == d:
            return None
        d = up


def _package_of(resolver: Any, path: str) -> str | None:
    """The name of the known package whose folder holds ``path`` (the deepest), or None."""
    best, name = "", None
    for n, where in list(resolver.scanned.items()) + list(resolver.explicit.items()):
        w = str(where)
        if (path == w or path.startswith(w + os.sep)) and len(w) > len(best):
            best, name = w, n
    return name


def _cause(own: str, pxml: str, name: str) -> Cause:
    return Cause(CODE, f"undeclared-dependency:{own}:{name}",
                 f"package '{name}' is used but {display_path(pxml)} does not declare it: add "
                 f"<exec_depend>{name}</exec_depend> (or <depend>)")


def _known(resolver: Any, pkg: str) -> bool:
    try:
        resolver.find(pkg)
        return True
    except Exception:  # noqa: BLE001 - an unknown package is UL004's
        return False


def _finds(model: "Model", top: str, ok: set[str]) -> Iterator[tuple[str, Origin]]:
    """(package, Origin) of every `$(find NAME)` written in the model's own sources (the files
    it read below ``top``, its package's folder; not in comments) for a known package that is
    not in ``ok``: in an include, an arg's default or an element's text (a controllers file
    handed to a plugin), each at its line in the linted repository."""
    for f in model.deps:
        path = os.path.abspath(f)
        if not path.startswith(top + os.sep) or not path.endswith((".xacro", ".urdf")):
            continue
        data = read_source(path, 1 << 22)
        if data is None:
            continue
        text = _COMMENT.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)),
                            data.decode("utf-8", "replace"))
        for m in _FIND.finditer(text):
            pkg = m.group(1)
            if pkg not in ok and "$" not in pkg and _known(model.resolver, pkg):
                line = text.count("\n", 0, m.start()) + 1
                yield pkg, Origin(path, line, m.start() - text.rfind("\n", 0, m.start()))


def _own_place(o: Any, top: str) -> Origin | None:
    """The innermost macro call in the linted package that made an element (its own line when
    it is there), or None."""
    if o.file.startswith(top + os.sep):
        return None
    for c in reversed(o.chain):
        if str(c[0]).startswith(top + os.sep):
            return Origin(c[0], c[1], c[2])
    return None


def check(model: "Model", ctx: "Context") -> "Checked":
    own = own_package(model)
    if own is None or model.resolver is None:
        return
    name, pxml, declared = own
    ok = declared | {name}
    top = os.path.dirname(os.path.abspath(pxml))
    for tag in ("mesh", "texture"):
        for m in urdf_iter(model, tag):
            uri = m.get("filename") or ""
            if uri.startswith("package://"):
                pkg = uri[len("package://"):].partition("/")[0]
                if pkg and pkg not in ok and ctx.mesh_ref(model, uri).path:
                    yield Report(m, f"{tag} '{uri}'", cause=_cause(name, pxml, pkg))
    seen: set[str] = set()
    for pkg, at in _finds(model, top, ok):
        seen.add(pkg)
        yield Report(at, f"$(find {pkg})", cause=_cause(name, pxml, pkg))
    # files read otherwise (package:// includes): at the first element they made, or at the
    # macro call in the linted package that made it
    firsts: dict[str, str] = {}
    for dep in model.deps[1:]:
        pkg = _package_of(model.resolver, os.path.abspath(dep))
        if pkg and pkg not in ok and pkg not in firsts and pkg not in seen:
            firsts[pkg] = dep
    if not firsts:
        return
    for el, o in model.origins.items():
        for pkg, dep in list(firsts.items()):
            if o.file == dep or any(c[0] == dep for c in o.chain):
                yield Report(_own_place(o, top) or el, f"reads {display_path(dep)}",
                             cause=_cause(name, pxml, pkg))
                del firsts[pkg]
        if not firsts:
            return
