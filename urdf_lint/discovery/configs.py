"""Which configuration files configure which model: the SRDF, MoveIt's YAML and the
ros2_control controller YAML next to a robot description (``LintJob.configs``).

A file is tied to a model (each variant of it) in one of three ways, strongest first:

* **explicit**: a ``[[tool.urdf-lint.models]]`` entry's ``srdf``, ``controllers`` and
  ``joint-limits`` keys;
* **setup-assistant**: a MoveIt configuration package's ``.setup_assistant`` names the URDF
  (package and relative path) and the SRDF: both are tied, with the package's ``config/``
  MoveIt files (:data:`MOVEIT_FILES`), to that URDF's model and to the package's own models
  (``config/<robot>.urdf.xacro``, what ``moveit_configs_utils`` launches);
* **package**: the SRDFs (``*.srdf``, ``*.srdf.xacro``) of the package a model is in (the
  worker keeps one only when its robot name is the model's), the MoveIt files beside them, and
  the package's controller YAML (``*controllers*.yaml`` that is not MoveIt's). When the
  package holds several candidate models (``package-shared``), the worker keeps a controller
  YAML only for the models it names a joint of (the 2F-85's YAML beside the 2F-140).

Only files of these kinds are tied: a ``joint_limits.yaml`` that a description reads itself
(``xacro.load_yaml``, keyed by the description's own names) is an input of the model, not
MoveIt's limits, unless a MoveIt package or the config names it.
"""
from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any

from urdf_lint.discovery.packages import inside

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.core.jobs import LintJob

MOVEIT_FILES = {"joint_limits.yaml": "joint-limits", "kinematics.yaml": "kinematics",
                "initial_positions.yaml": "initial-positions",
                "moveit_controllers.yaml": "moveit-controllers",
                "ros2_controllers.yaml": "controllers"}
SRDF_SUFFIXES = (".srdf", ".srdf.xacro")
MAX_PACKAGE_FILES = 5000      # a package walked for its configuration files (meshes skipped)
_SKIP = {"meshes", "mesh", "textures", "materials", "build", "install", "log", ".git"}


def package_dir(path: str, stop: tuple[str, ...] = ()) -> str | None:
    """The folder of the ``package.xml`` nearest above ``path`` (not above ``stop`` folders)."""
    d = os.path.dirname(os.path.abspath(path))
    while True:
        if os.path.isfile(os.path.join(d, "package.xml")):
            return d
        parent = os.path.dirname(d)
        if parent == d or d in stop:
            return None
        d = parent


def package_files(pkg: str, suffixes: tuple[str, ...] = (*SRDF_SUFFIXES, ".yaml", ".yml"),
                  names: frozenset[str] = frozenset({".setup_assistant"})) -> list[str]:
    """The SRDF and YAML files of a package (or those with other ``suffixes``; mesh folders
    skipped, at most MAX_PACKAGE_FILES)."""
    from urdf_lint.core import fsbound
    out = []
    for f in fsbound.walk_files(pkg, suffixes=suffixes, names=set(names),
                                skip=lambda d: d in _SKIP):
        if os.path.dirname(f) != pkg and os.path.isfile(os.path.join(os.path.dirname(f),
                                                                     "package.xml")):
            continue   # a nested package's own files
        out.append(f)
        if len(out) >= MAX_PACKAGE_FILES:
            break
    return out


def _kind(f: str, pkg_files_moveit: bool) -> str | None:
    name = os.path.basename(f)
    if name.endswith(SRDF_SUFFIXES):
        return "srdf"
    if pkg_files_moveit:   # also the variants: hard_joint_limits.yaml, left_initial_positions.yaml
        for suffix, kind in MOVEIT_FILES.items():
            if name == suffix or name.endswith("_" + suffix):
                return kind
    if name.endswith((".yaml", ".yml")) and "controllers" in name and "moveit" not in name:
        return "controllers"
    return None


def setup_assistant(pkg: str, resolver: Any) -> tuple[str | None, str | None, dict[str, str]]:
    """(the URDF path, the SRDF path, the xacro args) a MoveIt configuration package's
    ``.setup_assistant`` names; (None, None, {}) when it has none or it cannot be read."""
    from urdf_lint.core import fsbound
    f = os.path.join(pkg, ".setup_assistant")
    if not os.path.isfile(f):
        return None, None, {}
    try:
        import yaml
        data = yaml.safe_load(fsbound.read_text(f, max_bytes=1 << 20))
    except Exception:  # noqa: BLE001 - unreadable or not YAML: no tie from it
        return None, None, {}
    conf = data.get("moveit_setup_assistant_config") if isinstance(data, dict) else None
    if not isinstance(conf, dict):
        return None, None, {}
    urdf_sec, srdf_sec = conf.get("URDF") or {}, conf.get("SRDF") or {}
    urdf = srdf = None
    if isinstance(urdf_sec, dict) and urdf_sec.get("package") and urdf_sec.get("relative_path"):
        try:
            urdf = str(resolver.find(str(urdf_sec["package"])) / str(urdf_sec["relative_path"]))
        except Exception:  # noqa: BLE001 - a package not in the workspace
            urdf = None
    if isinstance(srdf_sec, dict) and srdf_sec.get("relative_path"):
        srdf = os.path.join(pkg, str(srdf_sec["relative_path"]))
    args = {}
    for tok in str(urdf_sec.get("xacro_args") or "").split() if isinstance(urdf_sec, dict) else ():
        if ":=" in tok:
            k, v = tok.split(":=", 1)
            args[k] = v
    return urdf, srdf, args


class _Ties:
    """model entry -> (kind, path) -> how it was tied (the first, strongest, tie wins)."""

    def __init__(self, resolver: Any):
        self.resolver = resolver
        self.by: dict[str, dict[tuple[str, str], str]] = {}

    def tie(self, entry: str, kind: str, path: str, how: str) -> None:
        if os.path.isfile(path) and self.resolver.is_inside(path):
            self.by.setdefault(entry, {}).setdefault((kind, os.path.realpath(path)), how)


def attach_configs(jobs: list[LintJob], cfg: Any, resolver: Any) -> list[LintJob]:
    """The jobs with ``configs`` set (see the module's docstring)."""
    import dataclasses
    if resolver is None:
        return jobs
    ties = _Ties(resolver)
    _explicit(ties, cfg)
    # the walk up to a model's package stops at the outermost roots only: checking one file
    # (`check urdf/arm.urdf.xacro`, the hook, diff's base) makes its own folder a root too,
    # which must not hide the package.xml above it
    all_roots = [str(r) for r in resolver.roots]
    roots = tuple(r for r in all_roots if not any(o != r and inside(r, o) for o in all_roots))
    entries = {j.entry for j in jobs if j.kind in ("xacro", "urdf")}
    by_pkg: dict[str, list[str]] = {}
    for e in entries:
        pkg = package_dir(e, roots)
        if pkg is not None:
            by_pkg.setdefault(pkg, []).append(e)
    moveit_pkgs = _moveit_packages(resolver, by_pkg)
    for pkg in moveit_pkgs:
        _moveit_ties(ties, pkg, resolver, by_pkg.get(pkg, []), entries)
    for pkg, models in by_pkg.items():
        if pkg not in moveit_pkgs:
            _package_ties(ties, pkg, models)
    return [dataclasses.replace(j, configs=tuple((k, p, how) for (k, p), how in
                                                 sorted(ties.by[j.entry].items())))
            if j.entry in ties.by and j.kind in ("xacro", "urdf") else j for j in jobs]


def _explicit(ties: _Ties, cfg: Any) -> None:
    """The ``srdf``, ``controllers`` and ``joint-limits`` of the config's models entries."""
    for spec in getattr(cfg, "models", ()):
        for kind, paths in (("srdf", [spec.srdf] if spec.srdf else []),
                            ("controllers", spec.controllers),
                            ("joint-limits", [spec.joint_limits] if spec.joint_limits else [])):
            for p in paths:
                ties.tie(spec.path, kind, p, "explicit")


def _moveit_ties(ties: _Ties, pkg: str, resolver: Any, own: list[str], entries: set[str]) -> None:
    """A MoveIt configuration package's SRDF and config/ files, tied to the URDF its
    ``.setup_assistant`` names and to the package's own models."""
    urdf, srdf, _ = setup_assistant(pkg, resolver)
    files = package_files(pkg)
    models = list(own)
    if urdf and os.path.realpath(urdf) in entries:
        models.append(os.path.realpath(urdf))
    for e in models:
        if srdf:
            ties.tie(e, "srdf", srdf, "setup-assistant")
        for f in files:
            k = _kind(f, inside(f, os.path.join(pkg, "config")))
            if k is not None:
                ties.tie(e, k, f, "package" if k == "srdf" else "setup-assistant")


def _package_ties(ties: _Ties, pkg: str, models: list[str]) -> None:
    """A package's SRDFs, the MoveIt files beside them and its controller YAML, tied to its
    models (the worker keeps those about the model: discovery cannot tell)."""
    files = package_files(pkg)
    srdf_dirs = {os.path.dirname(f) for f in files if f.endswith(SRDF_SUFFIXES)}
    # shared: the package holds other robot files than the run's one model (`check` of one
    # file, the hook, diff's base): what `check .` of the package would count as its models
    shared = len(models) > 1 or any(
        not f.endswith(SRDF_SUFFIXES) and os.path.realpath(f) not in models
        for f in package_files(pkg, (".urdf", ".xacro"), frozenset()))
    how = "package-shared" if shared else "package"
    for f in files:
        k = _kind(f, os.path.dirname(f) in srdf_dirs)
        if k is not None:
            for e in models:
                ties.tie(e, k, f, how)


def _moveit_packages(resolver: Any, by_pkg: dict[str, Any]) -> list[str]:
    """The packages with a ``.setup_assistant``: those of the run's models and the packages the
    resolver found by scanning (a MoveIt configuration package holds no model of its own)."""
    dirs = dict.fromkeys([*by_pkg, *(str(d) for d in resolver.scanned.values())])
    return [d for d in dirs if os.path.isfile(os.path.join(d, ".setup_assistant"))]
