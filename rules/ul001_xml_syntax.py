"""The file is not well-formed XML, so nothing in it can be checked.

Why: Every tool that reads the description (xacro, urdfdom, Gazebo, RViz) stops at the first
syntax error.

How to fix: Fix the syntax at the reported line: an unclosed or mismatched tag, a stray
character, an undeclared namespace prefix (`drake:`, `xacro:` without `xmlns:xacro`), or a bad
XML declaration. When only a namespace prefix is undeclared, urdf-lint still lints the rest.
"""
CODE = "UL001"
NAME = "xml-syntax"
SEVERITY = "error"
ORIGIN = "expansion"
FAIL = """<robot name="r">
  <link name="a">
</robot>
"""
FAIL_AT = [(3, 9)]
PASS = """<robot name="r">
  <link name="a"/>
</robot>
"""
