"""`safety_controller` soft limits lie outside the joint's hard limits, or are inverted.

Why: The safety controller then lets the joint run into its hard stops.

How to fix: Put the soft limits inside `[lower, upper]`, lower below upper.

Fix: safe, for inverted soft limits: `--fix` swaps `soft_lower_limit` and `soft_upper_limit`
where they are written.
"""
CODE = "UL306"
NAME = "safety-limits"
SEVERITY = "warning"
FAIL = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="elbow" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
    <safety_controller soft_lower_limit="-1.5" soft_upper_limit="0.9" k_position="100" k_velocity="10"/></joint>
</robot>
"""
FAIL_AT = [(5, 5)]
PASS = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="elbow" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
    <safety_controller soft_lower_limit="-0.9" soft_upper_limit="0.9" k_position="100" k_velocity="10"/></joint>
</robot>
"""
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, fmt, number, set_attrs

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._joints import limits


def check(model: "Model", ctx: "Context") -> "Checked":
    for j in model.top_joints():
        sc = j.find("safety_controller")
        if sc is None:
            continue
        if sc.get("k_velocity") is None:
            yield Report(sc, f"joint '{j.get('name')}': <safety_controller> needs k_velocity")
        lim, lo, hi, _, _ = limits(j)
        slo, shi = number(sc.get("soft_lower_limit", "0")), number(sc.get("soft_upper_limit", "0"))
        if slo is not None and shi is not None and slo > shi:
            yield Report(sc, (f"joint '{j.get('name')}': soft_lower_limit {fmt(slo)} > "
                              f"soft_upper_limit {fmt(shi)}"), fix=set_attrs(
                       {"soft_lower_limit": sc.get("soft_upper_limit", "0"),
                        "soft_upper_limit": sc.get("soft_lower_limit", "0")},
                       "swap soft_lower_limit and soft_upper_limit"))
        if lim is None or j.get("type") not in ("revolute", "prismatic") or lo is None or hi is None:
            continue
        if slo is not None and slo < lo:
            yield Report(sc, (f"joint '{j.get('name')}': soft_lower_limit {fmt(slo)} is below the hard "
                              f"lower limit {fmt(lo)}"))
        if shi is not None and shi > hi:
            yield Report(sc, (f"joint '{j.get('name')}': soft_upper_limit {fmt(shi)} is above the hard "
                              f"upper limit {fmt(hi)}"))
