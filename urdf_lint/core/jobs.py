"""The typed data that crosses the worker pipe: a job, the run's settings, a model's report.

``LintJob`` and ``LintSettings`` go to a worker (pickled: a fork of the same interpreter), a
``ModelReport`` comes back as plain data (:mod:`urdf_lint.runner.wire`); the cache stores a
``ModelReport`` with :meth:`ModelReport.to_record`.
"""
from __future__ import annotations

import enum
import os
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Iterable

from urdf_lint.core.findings import Problem
from urdf_lint.core.locations import Origin

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.expansion.sourcemap import SourceMap


class Status(str, enum.Enum):
    """What linting one candidate file found it to be."""
    MODEL = "model"            # a robot model, linted
    FAILED = "failed"          # could not be expanded or parsed (its problems say why)
    LIBRARY = "library"        # a macro library (only macros/properties/args/includes)
    NOT_ROBOT = "not-robot"    # an XML file whose root is not <robot>
    FRAGMENT = "fragment"      # a file other linted files include: linted through them

    def __str__(self) -> str:
        return self.value

    def __reduce_ex__(self, protocol: object) -> tuple[type[Status], tuple[str]]:
        # pickled by value, as Python 3.12 does: early Python 3.11 releases pickle a member as
        # getattr(Status, name). Results reach the parent as plain data (runner/wire.py); what
        # still pickles (jobs to a worker, the pipe of the fallback without fork) stays by value
        return Status, (self.value,)


@dataclass(frozen=True)
class LintJob:
    """One model to lint: an entry file and the xacro args to expand it with."""
    entry: str                 # absolute path
    args: dict[str, str] = field(default_factory=dict)
    kind: str = "xacro"        # "xacro" | "urdf" | "expand" (urdf-lint expand, in a worker too)
    explicit: bool = False     # named by the user or the config (never skipped as a library)
    display_name: str | None = None  # expand: the entry as the user wrote it (xacro's messages)
    output: str | None = None      # config: the generated URDF this xacro is written to
    mesh_base: str | None = None   # config: the folder relative mesh paths start from
    outputs: tuple[str, ...] = ()  # more checked-in URDFs this variant made (a header names
                                   # this xacro, and these args or none)
    # those of ``output`` and ``outputs`` no args tie to this variant (xacro's banner records
    # none): current when any variant of the xacro gives them, never rewritten
    untied: tuple[str, ...] = ()
    # the xacro's other configured arg sets (sorted items), tried for the untied outputs
    variants: tuple[tuple[tuple[str, str], ...], ...] = ()
    # urdf-lint server: unsaved editor buffers ((path, bytes), ...) read in place of those
    # files by this job's expansion and lint (urdf_lint/core/overlay.py); such a result is not cached
    overlay: tuple[tuple[str, bytes], ...] = ()
    # where the config sets each of ``args`` ((name, (file, line, col)), ...): a value written
    # as one passed ``$(arg NAME)`` is located there (a finding's ``value_from``)
    arg_origins: tuple[tuple[str, tuple[str, int, int]], ...] = ()
    # the configuration files tied to this model (urdf_lint.discovery.configs): (kind, path,
    # how), kind "srdf" | "controllers" | "joint-limits" | "kinematics" | "initial-positions" |
    # "moveit-controllers", how "explicit" | "setup-assistant" | "package" | "package-shared"
    configs: tuple[tuple[str, str, str], ...] = ()
    # what the run's other workers measured that this worker has not been told yet
    # ((name, record), ...: mesh facts under the content digest the parent computed,
    # urdf_lint.run.worker.share): set by the pool when it hands the job over
    shared: tuple[tuple[str, Any], ...] = ()


JobKey = tuple[str, tuple[tuple[str, str], ...]]   # (entry, sorted args)


def model_key(entry: str, args: dict[str, str]) -> JobKey:
    """One variant of a model, as a key: its entry and its args, sorted."""
    return entry, tuple(sorted(args.items()))


def job_key(job: LintJob) -> JobKey:
    """:func:`model_key` of a job."""
    return model_key(job.entry, job.args)


# environment variables $(env)/$(optenv) may read without configuration (here, not in config.py:
# the expansion reads it in a worker that never needs the config schema)
DEFAULT_ENV_ALLOW = ("ROS_DISTRO", "ROS_VERSION", "ROS_PYTHON_VERSION", "ROS_DOMAIN_ID",
                     "GAZEBO_MODEL_PATH", "IGN_GAZEBO_RESOURCE_PATH", "GZ_SIM_RESOURCE_PATH")

# the limits of one model (the config keys ``timeout`` and ``memory-mb`` default to them; here
# for the same reason as DEFAULT_ENV_ALLOW: the workers enforce them)
DEFAULT_TIMEOUT = 30.0     # seconds of CPU time
DEFAULT_MEMORY_MB = 2048   # MiB


@dataclass(frozen=True)
class LintSettings:
    """Everything a worker needs besides the job; the same for every model of a run."""
    resolver: dict[str, Any]                 # PackageResolver.to_dict()
    selected: tuple[str, ...] = ()           # rule codes to run
    # the consumer targets of the run (core.targets): a rule whose findings only some targets
    # keep may skip the work when none of them is selected (ctx.targets)
    targets: tuple[str, ...] = ("ros",)
    # code -> {option: value} (configured only)
    options: dict[str, dict[str, Any]] = field(default_factory=dict)
    env_allow: tuple[str, ...] = ()
    # the names (never the values) of the variables set where the run started: a worker's own
    # environment is scrubbed to env_allow, and $(optenv) of a variable that is set but not
    # allowed is a warning (None: the worker's own). Not part of cache_key: a result records
    # the few variables it looked up (ModelReport.env, env_unchanged)
    env_set: tuple[str, ...] | None = None
    timeout: float = DEFAULT_TIMEOUT         # per job, in seconds (runner.worker.run_jobs)
    memory_mb: int = DEFAULT_MEMORY_MB       # per worker, in MiB
    mesh_cache_dir: str | None = None
    expr_policy: object = None
    render_dir: str | None = None            # set: the worker also writes a snapshot
    render_rrd: bool = True
    render_base: str | None = None          # picture names are relative to it (the repository)
    render_refused: tuple[str, ...] = ()     # picture names two models of the run would share
    render_views: str = "single"             # "single" (a 3/4 view) or "sheet" (2x2 views)
    render_forward: str = "+x"               # the robot's forward axis, for the named views
    keep_model: bool = False                 # send the expanded robot back (urdf-lint diff)
    diff_render: bool = False                # diff --render: the geometry of its picture too
    diff_rrd: bool = True                    # diff --render: also the plan of its recording

    def cache_key(self) -> list[Any]:
        """What a cached result depends on (rendering does not change findings): the values of
        the variables ``$(env)``/``$(optenv)`` may read too, as the workers will see them."""
        env = {k: os.environ.get(k) for k in self.env_allow}
        return [list(self.selected), list(self.targets), self.options, env, self.resolver]


def env_unchanged(env: dict[str, bool]) -> bool:
    """Is each variable in ``env`` (name -> was it set) still set, or still unset, here?"""
    return all((name in os.environ) == bool(was) for name, was in env.items())


@dataclass(frozen=True)
class KeptModel:
    """The expanded robot itself, sent back when ``LintSettings.keep_model`` is set."""
    xml: str | None                          # None for a plain .urdf: the parent parses it
    origins: "SourceMap | None" = None
    # per element (document order): {attribute: ((file, line, col), derived)} of the values
    # read from YAML (Expansion.values): diff names the YAML line of a changed value
    values: tuple[Any, ...] = ()


@dataclass
class ModelReport:
    """What linting one job produced."""
    entry: str
    args: dict[str, str]
    status: Status = Status.MODEL
    deps: list[str] = field(default_factory=list)   # files read (absolute), entry first
    missing: list[str] = field(default_factory=list)  # files looked for and not found
    problems: list[Problem] = field(default_factory=list)  # Problem, as found (before policy)
    internal: list[str] = field(default_factory=list)  # internal errors (exit 2)
    name: str = ""                                  # the robot's name
    name_origin: Origin | None = None               # where the name was set
    links: int = 0
    joints: int = 0
    meshes: int = 0
    snapshot: dict[str, Any] | None = None          # what the renderer wrote (render runs only)
    kept_model: KeptModel | None = None             # the robot itself (keep_model runs only)
    diff_geometry: object = None                    # diff --render: render.Geometry
    diff_rrd: object = None                         # diff --render: recording.Plan of this side
    digests: dict[str, Any] = field(default_factory=dict)  # file -> [stat before read, digest of bytes read]
    directive_files: list[str] | None = None        # deps holding urdf-lint comments (None: unknown)
    cached: bool = False
    cacheable: bool = True                          # False: a fact depended on the environment
    env: dict[str, bool] = field(default_factory=dict)  # $(optenv) variables not allowed ->
                                                    # set? (the result holds while they stay so)
    current_outputs: list[str] = field(default_factory=list)  # generated URDFs that are today's
                                                    # expansion of this model (not linted again)
    # mesh facts the worker measured, for the parent's facts store: [name, path, digest, record]
    # (plain lists, str and JSON records; urdf_lint.meshes.store.FactsStore.accept)
    mesh_facts: list[list[Any]] = field(default_factory=list)
    # the <xacro:if>/<xacro:unless> outcomes of the expansion: [file, line, col, kept]
    # (expansion.expand.Expansion.branches; branch coverage, urdf_lint.run.explore)
    branches: list[list[Any]] = field(default_factory=list)
    seconds: float = 0.0     # what linting it took in the worker (the next run's cost estimate)

    @classmethod
    def failed(cls, job: LintJob, problems: Iterable[Problem] = (),
               internal: Iterable[str] = ()) -> "ModelReport":
        return cls(job.entry, dict(job.args), Status.FAILED, deps=[job.entry],
                   problems=list(problems), internal=list(internal))

    @property
    def label(self) -> str:
        from urdf_lint.core.locations import display_path
        base = display_path(self.entry)
        if self.args:
            base += " [" + " ".join(f"{k}:={v}" for k, v in sorted(self.args.items())) + "]"
        return base

    @property
    def stats(self) -> dict[str, Any]:
        """The counts, as the reporters show them."""
        return {"name": self.name, "links": self.links, "joints": self.joints,
                "meshes": self.meshes}

    # -- cache -------------------------------------------------------------------------------
    def to_record(self) -> dict[str, Any]:
        o = self.name_origin
        return {"status": self.status.value, "deps": list(self.deps),
                "missing": list(self.missing),
                "problems": [p.to_record() for p in self.problems],
                "name": self.name, "name_origin": [o.file, o.line, o.col] if o else None,
                "links": self.links, "joints": self.joints, "meshes": self.meshes,
                "directive_files": self.directive_files,
                "current_outputs": list(self.current_outputs), "env": dict(self.env),
                "branches": [list(b) for b in self.branches]}

    @classmethod
    def from_record(cls, job: LintJob, rec: dict[str, Any]) -> "ModelReport":
        o = rec.get("name_origin")
        return cls(job.entry, dict(job.args), Status(rec["status"]), deps=list(rec["deps"]),
                   missing=list(rec.get("missing", [])),
                   problems=[Problem.from_record(p) for p in rec["problems"]],
                   name=rec.get("name", ""), name_origin=Origin(o[0], o[1], o[2]) if o else None,
                   links=rec.get("links", 0), joints=rec.get("joints", 0),
                   meshes=rec.get("meshes", 0), directive_files=rec.get("directive_files"),
                   cached=True, current_outputs=list(rec.get("current_outputs", ())),
                   env={str(k): bool(v) for k, v in dict(rec.get("env") or {}).items()},
                   branches=[list(b) for b in rec.get("branches", ())])
