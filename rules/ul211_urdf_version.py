"""`<robot version=...>` is not `major.minor`, or is a version the URDF parsers do not support.

Why: urdfdom supports 1.0 and 1.1 and refuses `version="1"`, `"2"` or `"foo"`.

How to fix: Write `1.0` or `1.1`, or omit the attribute for 1.0.
"""
CODE = "UL211"
NAME = "urdf-version"
SEVERITY = "error"
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


def check(model, ctx):
    v = model.root.get("version")
    if v is None:
        return
    m = re.fullmatch(r"(\d+)\.(\d+)", v)
    if not m:
        yield model.root, f"robot version '{v}' must be 'major.minor' (e.g. 1.0)"
    elif int(m.group(1)) != 1 or int(m.group(2)) > 1:
        yield model.root, f"robot version '{v}' is not supported (URDF parsers know 1.0 and 1.1)"
