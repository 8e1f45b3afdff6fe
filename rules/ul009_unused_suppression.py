"""An inline `urdf-lint:` suppression comment that suppresses nothing (like ruff's RUF100).

Why: Stale suppressions hide future problems at that place.

How to fix: Remove the comment, or narrow it to the code that still fires.

Fix: safe, for `disable-next` and `disable-file`: `--fix` deletes the comment (its whole line
when it is alone there). A `disable` range is left to you, with its `enable`.
"""
CODE = "UL009"
NAME = "unused-suppression"
SEVERITY = "warning"
ORIGIN = "engine"
FAIL = """<robot name="r">
  <!-- urdf-lint: disable-next UL302 -->
  <link name="a"/>
</robot>
"""
FAIL_AT = [(2, 3)]
PASS = """<robot name="r">
  <link name="a"/>
  <link name="b"/>
  <!-- urdf-lint: disable-next UL103 -->
  <joint name="j" type="fixed"><parent link="a"/><child link="c"/></joint>
</robot>
"""
