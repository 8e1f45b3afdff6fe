"""Where a package's build installs its source folders: ``$(find pkg)/ros2_control/x.xacro`` in a
built workspace is ``pkg/description/ros2_control/x.xacro`` in the source tree when the package's
``CMakeLists.txt`` says ``install(DIRECTORY description/ros2_control DESTINATION
share/${PROJECT_NAME})`` (ros2_control_demos lays every example out so).

urdf-lint reads the source tree, so a path below a package that does not exist there is looked
up through these rules before it is reported missing. Only ``install(DIRECTORY ...)`` and
``install(FILES ...)`` into ``share/${PROJECT_NAME}`` (or ``share/<name>``) count; the file is
read as text (never run), bounded, through the file boundary."""
from __future__ import annotations

import os
import re

# (source, destination below share/NAME): a folder's contents (``dir/``) or the folder itself
Rule = tuple[str, str]

_INSTALL = re.compile(r"\binstall\s*\(([^()]*)\)", re.IGNORECASE)
_KEYWORDS = {"DIRECTORY", "FILES", "PROGRAMS", "TARGETS", "DESTINATION", "FILES_MATCHING",
             "PATTERN", "REGEX", "EXCLUDE", "PERMISSIONS", "USE_SOURCE_PERMISSIONS",
             "OPTIONAL", "MESSAGE_NEVER", "COMPONENT", "RENAME", "CONFIGURATIONS",
             "DIRECTORY_PERMISSIONS", "FILE_PERMISSIONS", "EXPORT", "TYPE"}
MAX_CMAKE_BYTES = 1 << 20


def install_rules(text: str, name: str) -> list[Rule]:
    """The rules of a ``CMakeLists.txt`` that install source paths into ``share/`` of package
    ``name``."""
    text = re.sub(r"#[^\n]*", "", text)
    share = re.compile(r"share/(?:\$\{PROJECT_NAME\}|" + re.escape(name) + r")(?:/(.*))?$")
    out: list[Rule] = []
    for m in _INSTALL.finditer(text):
        words = [w.strip('"') for w in m.group(1).split()]
        if not words or words[0].upper() not in ("DIRECTORY", "FILES"):
            continue
        folder = words[0].upper() == "DIRECTORY"
        sources = []
        for w in words[1:]:
            if w.upper() in _KEYWORDS:
                break
            sources.append(w)
        dest = next((words[i + 1] for i, w in enumerate(words[:-1]) if w.upper() == "DESTINATION"),
                    None)
        hit = share.match(dest.rstrip("/")) if dest else None
        if hit is None:
            continue
        below = (hit.group(1) or "").strip("/")
        for s in sources:
            if "$" in s or s.startswith("/") or ".." in s.split("/"):
                continue
            if folder and s.endswith("/"):      # the folder's contents
                out.append((s.rstrip("/"), below))
            else:                               # the folder (or the file) itself
                out.append((s.rstrip("/"), "/".join(p for p in (below, os.path.basename(
                    s.rstrip("/"))) if p)))
    return out


def source_of(rel: str, rules: list[Rule]) -> list[str]:
    """The source paths (relative to the package) an installed ``rel`` may come from, in the
    order of the rules."""
    out = []
    for src, dest in rules:
        if not dest:
            out.append(f"{src}/{rel}" if src else rel)
        elif rel == dest:
            out.append(src)
        elif rel.startswith(dest + "/"):
            out.append(f"{src}/{rel[len(dest) + 1:]}" if src else rel[len(dest) + 1:])
    return out
