"""A link that no joint connects, in a model with more than one link.

Why: It floats free: parsers see it as a second root, and simulators drop or misplace it.

How to fix: Add the joint that attaches it, or remove it.
"""
CODE = "UL104"
NAME = "disconnected-link"
SEVERITY = "error"
TARGETS = {"mujoco": "warning", "yourdfpy": "warning", "urdf_parser_py": "warning",
           "idyntree": "warning", "isaac": "warning", "drake": "warning"}
FAIL = """<robot name="r">
  <link name="a"/><link name="b"/><link name="lonely"/>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
</robot>
"""
FAIL_AT = [(2, 35)]
PASS = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
</robot>
"""


from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model


def check(model: "Model", ctx: "Context") -> "Checked":
    links = model.top_links()
    if len(links) < 2:
        return
    used = set()
    for j in model.top_joints():
        for role in ("parent", "child"):
            e = j.find(role)
            if e is not None and e.get("link"):
                used.add(e.get("link"))
    for lk in links:
        n = lk.get("name")
        if n and n not in used and model.links.get(n) is lk:
            yield Report(lk, f"link '{n}' is not connected by any joint")
