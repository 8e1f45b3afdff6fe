"""A configuration file tied to the robot (SRDF, controller or MoveIt YAML) cannot be read: it is not valid YAML or XML, or a `.srdf.xacro` does not expand.

Why: MoveIt or the controller_manager fails on it at launch; urdf-lint cannot check it against
the robot either, so its other findings (UL710-UL798) are missing for this file.

Consumers: ros only: the other consumers do not read these files.

How to fix: Fix the syntax at the reported line (the message quotes the parser).
"""
CODE = "UL799"
NAME = "config-unreadable"
SEVERITY = "warning"
ORIGIN = "engine"
TARGETS = {"*": "off", "ros": "warning", "gazebo": "warning"}
FAIL = """<robot name="r">
  <link name="base"/>
</robot>
"""
PASS = FAIL
EXAMPLE_FILES = {"config/r_controllers.yaml": """controller_manager:
  ros__parameters:
    update_rate: 100
   bad: 1
"""}
PASS_FILES = {"config/r_controllers.yaml": EXAMPLE_FILES["config/r_controllers.yaml"].replace(
    "   bad: 1\n", "")}
EXAMPLE_AT = "config/r_controllers.yaml"
FAIL_AT = [(4, 4)]
