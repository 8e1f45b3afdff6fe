"""`<robot version=...>` is not `major.minor`, or is a version the URDF parsers do not support.

Why: urdfdom 6.0.0 supports 1.0, 1.1 (`quat_xyzw`, `<capsule>`) and 1.2 (`acceleration`,
`deceleration`, `jerk` on `<limit>`), and refuses `version="1"`, `"1.3"`, `"2.0"` or `"foo"`
(Pinocchio 4.1.0, which parses with it, rejects `version="1.3"`: measured). MuJoCo 4.0.0 and
PyBullet 3.2.7 load any version (a warning for `mujoco` and `pybullet`); what each consumer reads of 1.1 and 1.2 is UL213's.

How to fix: Write `1.0`, `1.1` or `1.2`, or omit the attribute for 1.0.
"""
CODE = "UL211"
NAME = "urdf-version"
SEVERITY = "error"
TARGETS = {"mujoco": "warning", "pybullet": "warning", "yourdfpy": "warning", "urchin": "warning",
           "idyntree": "warning", "isaac": "warning", "drake": "warning"}
# 1.1 and 1.2: urdfdom 6 reads them; urdf_parser_py and sdformat 12 (liburdfdom 3) refuse them
OLD_PARSERS = {"*": "off", "urdf_parser_py": "error", "gazebo": "error"}
FAIL = """<robot name="r" version="1">
  <link name="a"/>
</robot>
"""
FAIL_AT = [(1, 1)]
PASS = """<robot name="r" version="1.0">
  <link name="a"/>
</robot>
"""
import re

from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model

def check(model: "Model", ctx: "Context") -> "Checked":
    v = model.root.get("version")
    if v is None:
        return
    m = re.fullmatch(r"(\d+)\.(\d+)", v)
    if not m:
        yield Report(model.root, f"robot version '{v}' must be 'major.minor' (e.g. 1.0)")
    elif int(m.group(1)) != 1 or int(m.group(2)) > 2:
        yield Report(model.root, (f"robot version '{v}' is not supported (urdfdom 6 knows 1.0, 1.1 and "
                                  "1.2)"))
    elif int(m.group(2)) > 0:
        yield Report(model.root, (f"robot version '{v}': urdf_parser_py and Gazebo's sdformat 12 read "
                                  "only 1.0 and refuse the model (\"only version 1.0 is supported\")"),
                     targets=OLD_PARSERS)
