"""The description reports an error of its own: `${xacro.error('...')}` ran while expanding
(a hand that checks its type and version match, an arm that refuses an unknown variant).

Why: xacro prints the message and goes on (it exits 0), so the build step succeeds and the
robot it made is the one its authors said is wrong; the message is lost in the build log.
`${xacro.warning('...')}` is reported as a warning (UL008), `${xacro.fatal('...')}` stops the
expansion (UL002), `${xacro.message('...')}` is only printed.

How to fix: Do what the message asks (pass matching args), or remove the check if it no
longer holds.
"""
CODE = "UL013"
NAME = "description-error"
SEVERITY = "error"
ORIGIN = "expansion"
FAIL = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="version" value="2"/>
  <xacro:if value="${version != 1}">
    ${xacro.error('this hand needs version 1, got', version)}
  </xacro:if>
  <link name="a"/>
</robot>
"""
FAIL_AT = [(3, 3)]
PASS = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="version" value="1"/>
  <xacro:if value="${version != 1}">
    ${xacro.error('this hand needs version 1, got', version)}
  </xacro:if>
  <link name="a"/>
</robot>
"""
