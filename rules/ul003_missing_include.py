"""An `xacro:include` names a file that does not exist.

Why: xacro stops at a missing include, so the model cannot be built.

How to fix: Fix the path: relative names resolve against the including file, `$(find pkg)` and
`package://pkg` against the package. Mark a genuinely optional include with `optional="true"`.
"""
CODE = "UL003"
NAME = "missing-include"
SEVERITY = "error"
ORIGIN = "expansion"
FAIL = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="no_such_file.xacro"/>
  <link name="a"/>
</robot>
"""
FAIL_AT = [(2, 3)]
PASS = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="no_such_file.xacro" optional="true"/>
  <link name="a"/>
</robot>
"""
