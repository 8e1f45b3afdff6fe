"""``[tool.urdf-lint]`` in pyproject.toml, or urdf-lint.toml: loading and validation."""
from __future__ import annotations

import fnmatch
import os
from dataclasses import dataclass, field
from pathlib import Path

from .policy import code_matches

try:
    import tomllib
except ImportError:  # pragma: no cover - Python 3.10
    import tomli as tomllib


# environment variables $(env)/$(optenv) may read without configuration
DEFAULT_ENV_ALLOW = ("ROS_DISTRO", "ROS_VERSION", "ROS_PYTHON_VERSION", "ROS_DOMAIN_ID",
                     "GAZEBO_MODEL_PATH", "IGN_GAZEBO_RESOURCE_PATH", "GZ_SIM_RESOURCE_PATH")


class ConfigError(Exception):
    pass


KNOWN_KEYS = {
    "select", "extend-select", "ignore", "per-file-ignores", "severity", "fail-on",
    "package-paths", "models", "exclude", "env-allow", "timeout", "memory-mb", "rule-options",
    "jobs", "cache-dir", "format", "discover",
}


@dataclass
class ModelSpec:
    path: str                       # absolute
    arg_sets: list                  # list of dicts
    output: str | None = None       # absolute: the generated URDF written from this xacro
    mesh_base: str | None = None    # absolute: where relative mesh paths start


@dataclass
class Config:
    path: str | None = None         # the file it came from
    root: str = "."                 # folder paths are relative to
    select: list = field(default_factory=lambda: ["UL"])
    extend_select: list = field(default_factory=list)
    ignore: list = field(default_factory=list)
    per_file_ignores: dict = field(default_factory=dict)
    severity: dict = field(default_factory=dict)
    fail_on: str = "error"
    package_paths: dict = field(default_factory=dict)
    models: list = field(default_factory=list)
    exclude: list = field(default_factory=list)
    env_allow: list = field(default_factory=list)
    timeout: float = 30.0
    memory_mb: int = 2048
    rule_options: dict = field(default_factory=dict)
    jobs: int | None = None
    cache_dir: str | None = None
    format: str | None = None
    discover: bool = True           # false: lint only the configured models
    raw: dict = field(default_factory=dict)

    def is_excluded(self, path: str) -> bool:
        try:
            rel = os.path.relpath(path, self.root)
        except ValueError:
            rel = path
        return any(fnmatch.fnmatch(rel, p) or fnmatch.fnmatch(rel, p.rstrip("/") + "/*")
                   for p in self.exclude)

    def options_for(self, code: str, name: str) -> dict:
        out = {}
        out.update(self.rule_options.get(name, {}))
        out.update(self.rule_options.get(code, {}))
        return out


def find_config(start: str) -> Path | None:
    p = Path(start).resolve()
    if p.is_file():
        p = p.parent
    for d in [p, *p.parents]:
        for fname in ("urdf-lint.toml", ".urdf-lint.toml"):
            if (d / fname).is_file():
                return d / fname
        pp = d / "pyproject.toml"
        if pp.is_file():
            try:
                data = tomllib.loads(pp.read_text(encoding="utf-8"))
            except Exception:
                continue
            if "urdf-lint" in data.get("tool", {}):
                return pp
    return None


def load_config(path: str | Path | None, known_codes: dict | None = None) -> Config:
    """Load and validate. ``known_codes`` maps code -> name for checking codes and options."""
    if path is None:
        return Config(root=os.getcwd())
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except Exception as e:
        raise ConfigError(f"{path}: cannot read config: {e}") from None
    if path.name == "pyproject.toml":
        data = data.get("tool", {}).get("urdf-lint", {})
    cfg = Config(path=str(path), root=str(path.parent.resolve()), raw=data)
    unknown = set(data) - KNOWN_KEYS
    if unknown:
        raise ConfigError(f"{path}: unknown key(s) in [tool.urdf-lint]: {', '.join(sorted(unknown))} "
                          f"(known: {', '.join(sorted(KNOWN_KEYS))})")

    def lst(key):
        v = data.get(key, [])
        if not isinstance(v, list) or not all(isinstance(x, str) for x in v):
            raise ConfigError(f"{path}: '{key}' must be a list of strings")
        return v
    if "select" in data:
        cfg.select = lst("select")
    cfg.extend_select = lst("extend-select")
    cfg.ignore = lst("ignore")
    cfg.exclude = lst("exclude")
    cfg.env_allow = lst("env-allow")
    pfi = data.get("per-file-ignores", {})
    if not isinstance(pfi, dict):
        raise ConfigError(f"{path}: 'per-file-ignores' must be a table of glob = [codes]")
    cfg.per_file_ignores = {k: list(v) for k, v in pfi.items()}
    sev = data.get("severity", {})
    for code, s in sev.items():
        if s not in ("error", "warning", "info"):
            raise ConfigError(f"{path}: severity of {code} must be error, warning or info, not {s!r}")
    cfg.severity = dict(sev)
    cfg.fail_on = data.get("fail-on", "error")
    if cfg.fail_on not in ("error", "warning", "info", "never"):
        raise ConfigError(f"{path}: 'fail-on' must be error, warning, info or never")
    cfg.package_paths = {k: str((path.parent / v).resolve()) for k, v in
                         data.get("package-paths", {}).items()}
    cfg.timeout = float(data.get("timeout", cfg.timeout))
    cfg.memory_mb = int(data.get("memory-mb", cfg.memory_mb))
    cfg.jobs = data.get("jobs")
    cfg.cache_dir = data.get("cache-dir")
    cfg.format = data.get("format")
    ro = data.get("rule-options", {})
    if not isinstance(ro, dict):
        raise ConfigError(f"{path}: 'rule-options' must be a table of tables")
    cfg.rule_options = {k: dict(v) for k, v in ro.items()}
    for m in data.get("models", []):
        if not isinstance(m, dict) or "path" not in m:
            raise ConfigError(f"{path}: each [[tool.urdf-lint.models]] needs a 'path'")
        extra = set(m) - {"path", "args", "output", "mesh-base"}
        if extra:
            raise ConfigError(f"{path}: unknown key(s) in a models entry: {', '.join(sorted(extra))}")
        args = m.get("args", [{}])
        if isinstance(args, dict):
            args = [args]
        arg_sets = [{k: str(v) for k, v in a.items()} for a in args]
        spec = ModelSpec(path=str((path.parent / m["path"]).resolve()), arg_sets=arg_sets)
        for key in ("output", "mesh-base"):
            if key in m:
                if not isinstance(m[key], str) or not m[key]:
                    raise ConfigError(f"{path}: '{key}' of model {m['path']} must be a path")
                setattr(spec, key.replace("-", "_"), str((path.parent / m[key]).resolve()))
        if not os.path.isfile(spec.path):
            raise ConfigError(f"{path}: model {m['path']!r} does not exist"
                              f"{_did_you_mean_file(m['path'], path.parent)}")
        cfg.models.append(spec)
    discover = data.get("discover", True)
    if not isinstance(discover, bool):
        raise ConfigError(f"{path}: 'discover' must be true or false")
    cfg.discover = discover
    if known_codes is not None:
        validate_codes(cfg, known_codes, str(path))
    return cfg


def _did_you_mean_file(rel: str, root: Path) -> str:
    """" (did you mean 'X'?)" for the robot file under ``root`` closest to ``rel``."""
    import difflib
    from .packages import iter_files
    files = [os.path.relpath(f, root) for f in iter_files(root, suffixes=(".xacro", ".urdf"))]
    best = difflib.get_close_matches(rel, files, n=1, cutoff=0.5) or difflib.get_close_matches(
        os.path.basename(rel), [os.path.basename(f) for f in files], n=1, cutoff=0.5)
    if not best:
        return ""
    hit = best[0] if best[0] in files else next(f for f in files if os.path.basename(f) == best[0])
    return f" (did you mean {hit!r}?)"


def validate_codes(cfg: Config, known: dict, where: str = "command line"):
    names = set(known.values())

    def check(p, what):
        if p == "ALL" or p in names:
            return
        if not any(code_matches(p, c, n) for c, n in known.items()):
            raise ConfigError(f"{where}: unknown rule code or prefix {p!r} in {what} "
                              f"(see 'urdf-lint rules')")
    for p in cfg.select + cfg.extend_select:
        check(p, "select")
    for p in cfg.ignore:
        check(p, "ignore")
    for codes in cfg.per_file_ignores.values():
        for p in codes:
            check(p, "per-file-ignores")
    for p in cfg.severity:
        check(p, "severity")
    for p in cfg.rule_options:
        check(p, "rule-options")
