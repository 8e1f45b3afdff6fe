"""The document is not a robot: its root is not `<robot>`, or it has no `<link>`.

Why: A URDF needs a `<robot name=...>` root with at least one link; parsers reject anything
else.

How to fix: Fix the root element or add a link. Macro-only xacro libraries are not models and
are not reported; list a file under `models` only if it is an entry point.
"""
CODE = "UL006"
NAME = "not-a-robot"
SEVERITY = "error"
ORIGIN = "expansion"
FAIL = """<robot name="empty">
</robot>
"""
FAIL_AT = [(1, 1)]
PASS = """<robot name="one">
  <link name="a"/>
</robot>
"""
