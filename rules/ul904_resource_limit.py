"""Expansion hit a limit: the time limit, the memory limit, or endless macro recursion.

Why: Each model is expanded in a worker with a time limit and a memory limit so that one hostile
or broken model cannot hang or exhaust the run; the other models are still linted.

How to fix: Give a recursive macro a stopping condition, or raise `timeout` (default 30 s) /
`memory-mb` (default 2048) for a genuinely huge model.
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
