"""An expression uses something the safe evaluator does not allow.

urdf-lint evaluates ``${...}`` and ``$(eval ...)`` with an allow-list: arithmetic, math,
comparisons, conditionals, comprehensions, string/list/dict methods, YAML data and ``xacro.*``
helpers. Attribute access to anything starting with ``_``, ``type``/``vars``/``getattr``, and
methods of non-value objects are refused, as are huge powers and repetitions. Real descriptions
never need them.
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
