"""Two different model files in the repository declare the same robot name.

Tools that key on the robot name (Gazebo spawners, MoveIt configs, robot_state_publisher
namespaces, dashboards) then mix the two up; it is usually a copy-paste left-over. Arg sets of
one file may share a name; different entry files should not. This is a repository-level check.
"""
CODE = "UL106"
NAME = "duplicate-robot-name"
SEVERITY = "info"
ORIGIN = "repository"
FAIL = """<robot name="visual">
  <link name="a"/>
</robot>
"""
PASS = """<robot name="unique_name_for_this_example">
  <link name="a"/>
</robot>
"""
EXAMPLE_FILES = {"urdf/other.urdf": '<robot name="visual">\n  <link name="a"/>\n</robot>\n'}
