"""A joint's parent or child names a link that is not defined.

Why: Parsers refuse the model. Usually a typo, a prefix that was not applied
(`${prefix}base_link`), or a link defined behind an `xacro:if` that evaluated false.

How to fix: Define the link or fix the name.
"""
CODE = "UL103"
NAME = "missing-link"
SEVERITY = "error"
FAIL = """<robot name="r">
  <link name="base_link"/><link name="arm"/>
  <joint name="j" type="fixed"><parent link="base_lnk"/><child link="arm"/></joint>
</robot>
"""
FAIL_AT = [(3, 32)]
PASS = """<robot name="r">
  <link name="base_link"/><link name="arm"/>
  <joint name="j" type="fixed"><parent link="base_link"/><child link="arm"/></joint>
</robot>
"""
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, did_you_mean

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model


def check(model: "Model", ctx: "Context") -> "Checked":
    for j in model.top_joints():
        for role in ("parent", "child"):
            e = j.find(role)
            if e is None:
                continue
            name = e.get("link")
            if name is not None and name not in model.links:
                yield Report(e, (f"joint '{j.get('name')}': {role} link '{name}' is not defined"
                                 + did_you_mean(name, model.links)))
