"""An inertia tensor that no rigid body can have: not positive definite, or violating the triangle
inequality (ixx + iyy >= izz, and the two other pairs).

Why: Physics engines reject such links or explode. Typical causes: a sign error in a product of
inertia, or principal moments copied from the wrong part. Products are taken as given.

Also reported: a link with a positive mass but an all-zero tensor on a body that moves (the
link a non-fixed joint moves, plus everything fixed to it) where no link of that body has any
inertia. Simulators either refuse such a body or let it spin freely. An all-zero tensor on a
fixed frame, or on a massless link, is a placeholder and is left alone.

How to fix: Recompute the tensor from the part's geometry and mass (CAD tools export it).
"""
CODE = "UL603"
NAME = "inertia-tensor"
SEVERITY = "error"
FAIL = """<robot name="r">
  <link name="a"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.5"/></inertial></link>
</robot>
"""
FAIL_AT = [(2, 45)]
PASS = """<robot name="r">
  <link name="a"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.15"/></inertial></link>
</robot>
"""
from urdf_lint.ruleutil import fmt, number
from urdf_lint.rules._inertial import Bodies, is_zero, mass, tensor


def _spins_freely(model, bodies, lk):
    """The joint that moves this massive, inertia-less link's body, when nothing in the body
    has inertia; else None."""
    if not (mass(lk) or 0) > 0:
        return None
    body = bodies.moving_body(lk.get("name"))
    if body is None:
        return None
    if any(tensor(o) is not None and not is_zero(tensor(o)) for o in body[2]):
        return None
    return body[1]


def check(model, ctx):
    bodies = None
    for lk in model.top_links():
        i = lk.find("inertial/inertia")
        if i is None:
            continue
        v = {a: number(i.get(a, "0")) for a in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
        if any(x is None for x in v.values()):
            continue  # UL206
        a, b, c = v["ixx"], v["iyy"], v["izz"]
        xy, xz, yz = v["ixy"], v["ixz"], v["iyz"]
        name = lk.get("name")
        if a == b == c == xy == xz == yz == 0:
            bodies = bodies or Bodies(model)
            j = _spins_freely(model, bodies, lk)
            if j is not None:
                yield i, (f"link '{name}': mass {fmt(mass(lk))} kg but an all-zero inertia tensor, "
                          f"and it moves (joint '{j.get('name')}'); simulators refuse it or let it "
                          "spin freely: give it the inertia of its geometry")
            continue  # otherwise an all-zero tensor is a (common) placeholder
        d1, d2 = a, a * b - xy * xy
        d3 = a * (b * c - yz * yz) - xy * (xy * c - yz * xz) + xz * (xy * yz - b * xz)
        if d1 <= 0 or d2 <= 0 or d3 <= 0:
            yield i, (f"link '{name}': inertia tensor is not positive definite (ixx={fmt(a)} "
                      f"iyy={fmt(b)} izz={fmt(c)} ixy={fmt(xy)} ixz={fmt(xz)} iyz={fmt(yz)})")
            continue
        tol = 1e-9 * (a + b + c)
        for p, q, r, names in ((a, b, c, "ixx + iyy >= izz"), (a, c, b, "ixx + izz >= iyy"),
                               (b, c, a, "iyy + izz >= ixx")):
            if p + q < r - tol:
                yield i, (f"link '{name}': inertia breaks the triangle inequality ({names}: "
                          f"{fmt(p)} + {fmt(q)} < {fmt(r)})")
                break
