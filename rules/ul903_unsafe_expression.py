"""An expression uses something the safe evaluator does not allow.

Why: urdf-lint evaluates `${...}` and `$(eval ...)` with an allow-list (arithmetic, math,
comparisons, conditionals, comprehensions, string/list/dict methods, YAML data and `xacro.*`
helpers) so that a description cannot run code. Attribute access to anything starting with `_`,
`type`/`vars`/`getattr`, methods of non-value objects, huge powers and repetitions are refused.

How to fix: Rewrite the expression with allowed operations; real descriptions never need the
refused ones.
"""
CODE = "UL903"
NAME = "unsafe-expression"
SEVERITY = "error"
ORIGIN = "expansion"
FAIL = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="${''.__class__}"/>
</robot>
"""
FAIL_AT = [(2, 3)]
PASS = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="${'base'.upper()}"/>
</robot>
"""
