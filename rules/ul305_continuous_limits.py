"""A continuous joint carries `lower`/`upper` limits, which URDF ignores for that type.

Why: The limits look effective to a reader but no tool applies them.

How to fix: Either make the joint `revolute` (limited), or remove the limits.

Fix: unsafe (`--unsafe-fixes`): removes `lower` and `upper` from the `<limit>`, or, with the
option `fix = "revolute"`, makes the joint `revolute` where its type is written.

Options: `fix` (default `"drop-limits"`): `"drop-limits"` or `"revolute"`.
"""
CODE = "UL305"
NAME = "continuous-limits"
SEVERITY = "warning"
OPTIONS = {"fix": "drop-limits"}
OPTION_CHOICES = {"fix": ("drop-limits", "revolute")}
FAIL = """<robot name="r">
  <link name="a"/><link name="wheel"/>
  <joint name="axle" type="continuous"><parent link="a"/><child link="wheel"/><axis xyz="0 1 0"/>
    <limit lower="-3.14" upper="3.14" effort="10" velocity="10"/></joint>
</robot>
"""
FAIL_AT = [(4, 5)]
PASS = """<robot name="r">
  <link name="a"/><link name="wheel"/>
  <joint name="axle" type="continuous"><parent link="a"/><child link="wheel"/><axis xyz="0 1 0"/>
    <limit effort="10" velocity="10"/></joint>
</robot>
"""



from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, drop_attrs, set_attrs

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model


def check(model: "Model", ctx: "Context") -> "Checked":
    how = ctx.options.get("fix", "drop-limits")
    for j in model.top_joints():
        lim = j.find("limit")
        if j.get("type") == "continuous" and lim is not None and (
                lim.get("lower") is not None or lim.get("upper") is not None):
            if how == "revolute":
                fix = set_attrs({"type": "revolute"}, "make the joint revolute", safe=False,
                                on_parent=True)
            else:
                fix = drop_attrs([a for a in ("lower", "upper") if lim.get(a) is not None],
                                 "drop the position limits")
            yield Report(lim, (f"continuous joint '{j.get('name')}' has position limits, which are ignored; "
                               "make it revolute or drop lower/upper"), fix=fix)
