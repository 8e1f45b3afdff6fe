"""An expression reads an environment variable that is not allow-listed.

Why: In CI the environment holds secrets (tokens, keys), and a description under review must not
be able to copy them into its output. `$(env X)` and `$(optenv X)` only read variables in
`env-allow` (plus ROS_DISTRO and a few ROS ones); otherwise the value is not substituted.
`$(env X)` of such a variable is an error (xacro itself fails where X is unset). `$(optenv X
default)` gets its default: where X is unset that is exactly what xacro makes, and nothing is
said; where X is set, the output differs from xacro's in this environment, a warning (once per
file and variable).

How to fix: Pass the value as a xacro arg, or add the variable to `env-allow` if it is safe to
read.
"""
CODE = "UL901"
NAME = "env-read"
SEVERITY = "error"
ORIGIN = "expansion"
FAIL = """<robot name="r$(env URDF_LINT_EXAMPLE_SECRET)" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="a"/>
</robot>
"""
FAIL_AT = [(1, 1)]
PASS = """<robot name="r$(optenv URDF_LINT_EXAMPLE_UNSET _default)" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="a"/>
</robot>
"""
