"""A `<gazebo reference="...">` names neither a link nor a joint of the model.

Why: Gazebo silently ignores the block, so the friction, colour, sensor or plugin it carries
never takes effect.

How to fix: Fix the reference to the link or joint it is meant for.

Fix: safe, when the name has a single close "did you mean" candidate that no other `<gazebo>` block names: `--fix`
writes it where the name is written.
"""
CODE = "UL703"
NAME = "gazebo-reference"
SEVERITY = "error"
TARGETS = {"mujoco": "warning", "pinocchio": "warning", "pybullet": "warning", "yourdfpy": "warning",
           "urdf_parser_py": "warning", "urchin": "warning", "idyntree": "warning", "isaac": "warning", "drake": "warning"}
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
from urdf_lint.rules._schema import literal_names
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, did_you_mean, reference_fixes

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model


def check(model: "Model", ctx: "Context") -> "Checked":
    names = set(model.links) | set(model.joints)
    found, taken = [], set()
    for g in model.root:
        if g.tag != "gazebo":
            continue
        r = g.get("reference")
        if r is not None and r not in names:
            found.append((g, r))
        elif r is not None:
            taken.add(r)
    fixes = reference_fixes([(g, "reference", r) for g, r in found], names, taken)
    for g, r in found:
        braced = literal_names(model, r)
        if braced:   # a forgotten '$' (UL212), not a misspelt name: no wrong suggestion
            yield Report(g, (f"<gazebo reference=\"{r}\"> names no link or joint: it holds a literal "
                             f"'{{{braced[0]}}}' (did you mean '${{{braced[0]}}}'? see UL212)"))
            continue
        yield Report(g, (f"<gazebo reference=\"{r}\"> names no link or joint"
                         + did_you_mean(r, names)), fix=fixes.get((g, "reference")))
