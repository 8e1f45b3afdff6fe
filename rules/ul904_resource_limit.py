"""Expansion hit a limit: the time limit, the memory limit, or endless macro recursion.

Each model is expanded in a worker with a time limit (``timeout``, default 30 s) and a memory
limit (``memory-mb``, default 2048); the other models are still linted. A macro that calls
itself without a stopping condition ends here too.
"""
CODE = "UL904"
NAME = "resource-limit"
SEVERITY = "error"
ORIGIN = "expansion"
FAIL = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="again"><xacro:again/></xacro:macro>
  <xacro:again/>
  <link name="a"/>
</robot>
"""
FAIL_AT = [(2, 29)]
PASS = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="once"><link name="a"/></xacro:macro>
  <xacro:once/>
</robot>
"""
