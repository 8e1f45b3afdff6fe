"""A `<gazebo reference="...">` names neither a link nor a joint of the model.

Why: Gazebo silently ignores the block, so the friction, colour, sensor or plugin it carries
never takes effect.

How to fix: Fix the reference to the link or joint it is meant for.
"""
CODE = "UL703"
NAME = "gazebo-reference"
SEVERITY = "error"
FAIL = """<robot name="r">
  <link name="base_link"/>
  <gazebo reference="base_lnk"><material>Gazebo/Blue</material></gazebo>
</robot>
"""
FAIL_AT = [(3, 3)]
PASS = """<robot name="r">
  <link name="base_link"/>
  <gazebo reference="base_link"><material>Gazebo/Blue</material></gazebo>
</robot>
"""
from urdf_lint.ruleutil import did_you_mean


def check(model, ctx):
    names = set(model.links) | set(model.joints)
    for g in model.root:
        if g.tag != "gazebo":
            continue
        r = g.get("reference")
        if r is not None and r not in names:
            yield g, f"<gazebo reference=\"{r}\"> names no link or joint" + did_you_mean(r, names)
