"""An include, `load_yaml` or mesh resolves (after symlinks) outside the package roots and the
linted repository.

Why: urdf-lint never reads such files: a description under review must not be able to pull
`/etc/passwd` or a CI secret into its output or a recording.

How to fix: Keep files inside the package, or map the other package with `--package-path`.
"""
CODE = "UL902"
NAME = "outside-roots"
SEVERITY = "error"
ORIGIN = "expansion"
FAIL = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="/etc/hostname"/>
  <link name="a"/>
</robot>
"""
FAIL_AT = [(2, 3)]
PASS = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="parts.xacro"/>
  <link name="a"/>
</robot>
"""
EXAMPLE_FILES = {"urdf/parts.xacro": '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"/>\n'}
