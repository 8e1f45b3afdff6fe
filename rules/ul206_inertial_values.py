"""An `<inertial>` lacks `<mass value>` or an `<inertia>` with all six values (ixx ixy ixz iyy iyz
izz), each a finite number.

Why: URDF parsers reject an inertial with a missing mass or inertia value; a typo in a number
silently breaks dynamics.

How to fix: Give the mass and all six inertia values as numbers.
"""
CODE = "UL206"
NAME = "inertial-values"
SEVERITY = "error"
FAIL = """<robot name="r">
  <link name="a">
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1"/></inertial>
  </link>
</robot>
"""
FAIL_AT = [(3, 32)]
PASS = """<robot name="r">
  <link name="a">
    <inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
  </link>
</robot>
"""
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, number

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model

# <inertial> without <inertia>: MuJoCo, PyBullet and urchin reject it; Pinocchio, Drake (a
# point mass), yourdfpy, urdf_parser_py, iDynTree, sdformat and the Isaac importer load it
POINT_MASS = {"pinocchio": "warning", "drake": "warning", "yourdfpy": "warning",
              "urdf_parser_py": "warning", "idyntree": "warning", "isaac": "warning",
              "gazebo": "warning"}
INERTIA = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


def check(model: "Model", ctx: "Context") -> "Checked":
    for lk in model.top_links():
        for inr in lk.findall("inertial"):
            name = lk.get("name")
            m = inr.find("mass")
            if m is None:
                yield Report(inr, f"link '{name}': <inertial> has no <mass value=...>")
            elif number(m.get("value")) is None:
                yield Report(m, f"link '{name}': mass value {m.get('value')!r} is not a number")
            i = inr.find("inertia")
            if i is None:
                yield Report(inr, f"link '{name}': <inertial> has no <inertia .../>",
                             targets=POINT_MASS)
                continue
            missing = [a for a in INERTIA if i.get(a) is None]
            if missing:
                yield Report(i, f"link '{name}': <inertia> is missing {', '.join(missing)}")
            bad = [f"{a}={i.get(a)!r}" for a in INERTIA if i.get(a) is not None and number(i.get(a)) is None]
            if bad:
                yield Report(i, f"link '{name}': <inertia> values are not numbers: {', '.join(bad)}")
