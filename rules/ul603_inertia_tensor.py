"""An inertia tensor that no rigid body can have: not positive definite, or violating the triangle
inequality (ixx + iyy >= izz, and the two other pairs).

Why: Physics engines reject such links or explode. Typical causes: a sign error in a product of
inertia, or principal moments copied from the wrong part. Products are taken as given.

Also reported: a link with a positive mass but an all-zero tensor on a body that moves (the
link a non-fixed joint moves, plus everything fixed to it) where no link of that body has any
inertia. Simulators either refuse such a body or let it spin freely. An all-zero tensor on a
fixed frame, or on a massless link, is a placeholder and is left alone.

Principal moments (the eigenvalues) are tested, as MuJoCo does: a tensor whose diagonal passes
can still break the inequality once its products of inertia are taken into account. Entries
below 1e-9 of the tensor's largest (or all below 1e-15 kg m^2, float noise of a lumped body) are
taken as zero, so a 1e-20 tensor is treated like its exact-zero twin; all six entries equal and
at most 1e-6 on a dummy link of at most 1e-6 kg is a placeholder. Per target: a tensor whose
written diagonal already fails is an error (as before) but a warning for `pinocchio` and
`pybullet`, which load it (measured with MuJoCo 4.0.0, Pinocchio 4.1.0, PyBullet 3.2.7); one that only its
principal moments show is an error for `mujoco` (MuJoCo 4.0.0 rejects it: "use
'balanceinertia'") and a warning for the others (urdfdom 6.0.0, Pinocchio 4.1.0, PyBullet 3.2.7
load it silently, Drake 1.51.1 with a warning). Under `gazebo` (sdformat 12.3, measured by
bench/consumers/harness.py) a triangle break is an error, a zero principal moment that keeps
the inequality (a thin rod: 0, I, I) a warning: sdformat loads it. The Python parsers,
iDynTree, the Isaac importer and Drake load any tensor: a warning for them.

How to fix: Recompute the tensor from the part's geometry and mass (CAD tools export it).
"""
CODE = "UL603"
NAME = "inertia-tensor"
SEVERITY = "error"
TARGETS = {"mujoco": "error", "pinocchio": "warning", "pybullet": "warning", "python": "warning",
           "idyntree": "warning", "isaac": "warning", "drake": "warning"}
FAIL = """<robot name="r">
  <link name="a"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.5"/></inertial></link>
  <link name="b"><inertial><mass value="0.01"/><inertia ixx="4.7e-6" ixy="0" ixz="2.5e-6" iyy="3.65e-6" iyz="0" izz="4.7e-6"/></inertial></link>
</robot>
"""
FAIL_AT = [(2, 45), (3, 48)]
PASS = """<robot name="r">
  <link name="a"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.15"/></inertial></link>
  <link name="lumped"><inertial><mass value="0"/><inertia ixx="1e-20" ixy="0" ixz="1e-21" iyy="1e-20" iyz="0" izz="0"/></inertial></link>
  <link name="dummy"><inertial><mass value="1e-6"/><inertia ixx="1e-6" ixy="1e-6" ixz="1e-6" iyy="1e-6" iyz="1e-6" izz="1e-6"/></inertial></link>
</robot>
"""
import math

from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report, fmt, number

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._inertial import Bodies, is_zero, mass, tensor

NOISE = 1e-15      # kg m^2: below MuJoCo's mjMINVAL, float noise of a lumped body, not inertia
RELATIVE = 1e-9    # of the tensor's largest entry: noise in a real tensor
PRINCIPAL_ONLY = {"*": "warning", "mujoco": "error", "gazebo": "error"}
# a placeholder tensor (six equal tiny entries on a dummy link) only MuJoCo refuses
PLACEHOLDER = {"*": "off", "mujoco": "error", "gazebo": "error"}


def _spins_freely(model: "Model", bodies: Any, lk: Any) -> Any:
    """The joint that moves this massive, inertia-less link's body, when nothing in the body
    has inertia; else None."""
    if not (mass(lk) or 0) > 0:
        return None
    body = bodies.moving_body(lk.get("name"))
    if body is None:
        return None
    if any(tensor(o) is not None and not _negligible(tensor(o)) for o in body[2]):
        return None
    return body[1]


def _negligible(t: dict[str, float]) -> bool:
    return bool(is_zero(t)) or max(abs(x) for x in t.values()) <= NOISE


def _placeholder(lk: Any, v: dict[str, float]) -> bool:
    """All six entries equal and tiny on a dummy link of at most 1e-6 kg: a placeholder."""
    m = mass(lk)
    return m is not None and 0 <= m <= 1e-6 and len(set(v.values())) == 1 and \
        0 < v["ixx"] <= 1e-6


def principal_moments(xx: float, yy: float, zz: float, xy: float, xz: float,
                      yz: float) -> list[float]:
    """The eigenvalues of the symmetric tensor, ascending (closed form, Smith 1961: no numpy in
    a worker that lints a model without meshes)."""
    p1 = xy * xy + xz * xz + yz * yz
    if p1 == 0:
        return sorted((xx, yy, zz))
    q = (xx + yy + zz) / 3
    p = math.sqrt(((xx - q) ** 2 + (yy - q) ** 2 + (zz - q) ** 2 + 2 * p1) / 6)
    b = [[(xx - q) / p, xy / p, xz / p], [xy / p, (yy - q) / p, yz / p],
         [xz / p, yz / p, (zz - q) / p]]
    r = (b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[2][1])
         - b[0][1] * (b[1][0] * b[2][2] - b[1][2] * b[2][0])
         + b[0][2] * (b[1][0] * b[2][1] - b[1][1] * b[2][0])) / 2
    phi = math.acos(max(-1.0, min(1.0, r))) / 3
    big = q + 2 * p * math.cos(phi)
    small = q + 2 * p * math.cos(phi + 2 * math.pi / 3)
    return sorted((small, 3 * q - big - small, big))


def _diagonal_test(a: float, b: float, c: float, xy: float, xz: float, yz: float) -> bool:
    """The test on the written entries (Sylvester's criterion, the triangle inequality on the
    diagonal): what urdf-lint reported before it looked at the principal moments."""
    d2 = a * b - xy * xy
    d3 = a * (b * c - yz * yz) - xy * (xy * c - yz * xz) + xz * (xy * yz - b * xz)
    if a <= 0 or d2 <= 0 or d3 <= 0:
        return True
    tol = 1e-9 * (a + b + c)
    return a + b < c - tol or a + c < b - tol or b + c < a - tol


def check(model: "Model", ctx: "Context") -> "Checked":
    bodies = None
    for lk in model.top_links():
        i = lk.find("inertial/inertia")
        if i is None:
            continue
        got = {a: number(i.get(a, "0")) for a in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
        if any(x is None for x in got.values()):
            continue  # UL206
        v = {a: x for a, x in got.items() if x is not None}
        name = lk.get("name")
        if _negligible(v):
            bodies = bodies or Bodies(model)
            j = _spins_freely(model, bodies, lk)
            if j is not None:
                yield Report(i, (f"link '{name}': mass {fmt(mass(lk))} kg but an all-zero inertia tensor, "
                                 f"and it moves (joint '{j.get('name')}'); simulators refuse it or let it "
                                 "spin freely: give it the inertia of its geometry"))
            continue  # otherwise an all-zero (or float-noise) tensor is a common placeholder
        if _placeholder(lk, v):
            yield Report(i, (f"link '{name}': six equal inertia entries ({fmt(v['ixx'])}) on a "
                             f"{fmt(mass(lk))} kg dummy link: principal moments 0, 0, "
                             f"{3 * v['ixx']:.3g}; MuJoCo rejects it (\"inertia must have positive "
                             "eigenvalues\"): write a diagonal tensor"), targets=PLACEHOLDER)
            continue
        a, b, c = v["ixx"], v["iyy"], v["izz"]
        xy, xz, yz = v["ixy"], v["ixz"], v["iyz"]
        scale = max(abs(x) for x in v.values())
        tol = RELATIVE * scale
        clean = {k: (0.0 if abs(x) <= tol else x) for k, x in v.items()}
        e1, e2, e3 = principal_moments(clean["ixx"], clean["iyy"], clean["izz"], clean["ixy"],
                                       clean["ixz"], clean["iyz"])
        table = None if _diagonal_test(a, b, c, xy, xz, yz) else PRINCIPAL_ONLY
        written = (f"ixx={fmt(a)} iyy={fmt(b)} izz={fmt(c)} ixy={fmt(xy)} ixz={fmt(xz)} "
                   f"iyz={fmt(yz)}")
        moments = f"principal moments {e1:.3g}, {e2:.3g}, {e3:.3g}"
        if e1 <= tol:
            if e1 >= -tol and e1 + e2 >= e3 - tol:
                # a zero principal moment that keeps the triangle inequality: sdformat 12 loads
                # it (measured on the corpus's finger links), MuJoCo does not
                table = {**(table or TARGETS), "gazebo": "warning"}
            yield Report(i, (f"link '{name}': inertia tensor is not positive definite ({written}; "
                             f"{moments})"), targets=table)
        elif e1 + e2 < e3 - tol:
            if table is None:   # the written diagonal breaks it: name the pair, as before
                for p, q, r, names in ((a, b, c, "ixx + iyy >= izz"), (a, c, b, "ixx + izz >= iyy"),
                                       (b, c, a, "iyy + izz >= ixx")):
                    if p + q < r - tol:
                        yield Report(i, (f"link '{name}': inertia breaks the triangle inequality "
                                         f"({names}: {fmt(p)} + {fmt(q)} < {fmt(r)})"))
                        break
                else:
                    yield Report(i, (f"link '{name}': inertia breaks the triangle inequality ({moments}: "
                                     f"{e1:.3g} + {e2:.3g} < {e3:.3g})"))
                continue
            yield Report(i, (f"link '{name}': its {moments} break the triangle inequality ({e1:.3g} + "
                             f"{e2:.3g} < {e3:.3g}), although the diagonal ({written}) passes: no rigid "
                             "body has this tensor; MuJoCo rejects it (\"use 'balanceinertia'\")"), targets=table)
