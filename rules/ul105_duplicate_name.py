"""Two links, or two joints, share a name.

Why: URDF parsers reject the model (urdfdom: "link/joint is not unique"; PyBullet 3.2.7
crashes on a duplicate joint); with xacro this usually means a macro was called twice without a
distinct `prefix`. MuJoCo 4.0.0 loads two joints of one name (a warning for `mujoco`) (measured with MuJoCo 4.0.0, Pinocchio 4.1.0, PyBullet 3.2.7).

How to fix: Rename one of them, or pass each macro call its own prefix.
"""
CODE = "UL105"
NAME = "duplicate-name"
SEVERITY = "error"
FAIL = """<robot name="r">
  <link name="a"/><link name="b"/><link name="b"/>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
</robot>
"""
FAIL_AT = [(2, 35)]
PASS = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
</robot>
"""


from urdf_lint.engine.api import Report


def check(model, ctx):
    for tag in ("link", "joint"):
        first: dict = {}
        for e in model.root:
            if e.tag != tag or not e.get("name"):
                continue
            n = e.get("name")
            if n in first:
                yield Report(e, (f"duplicate {tag} name '{n}' (first defined at "
                                 f"{model.origin(first[n]).place()}); give each a unique name"),
                             targets={"mujoco": "warning"} if tag == "joint" else None)
            else:
                first[n] = e
