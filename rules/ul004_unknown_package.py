"""`$(find pkg)` or `package://pkg` names a package that none of the searched places holds.

Why: Anything below that package (includes, YAML, meshes) cannot be read, on this machine or in
CI.

How to fix: urdf-lint needs no ROS: it finds packages from `package.xml` files under the linted
paths and the repository, then `AMENT_PREFIX_PATH` and `ROS_PACKAGE_PATH`. Map others with
`--package-path name=dir` or `package-paths` in the config.
"""
CODE = "UL004"
NAME = "unknown-package"
SEVERITY = "error"
ORIGIN = "expansion"
FAIL = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find no_such_package)/urdf/x.xacro"/>
  <link name="a"/>
</robot>
"""
FAIL_AT = [(2, 3)]
PASS = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find example_pkg)/urdf/parts.xacro"/>
  <link name="a"/>
</robot>
"""
EXAMPLE_FILES = {"urdf/parts.xacro": '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"/>\n'}
