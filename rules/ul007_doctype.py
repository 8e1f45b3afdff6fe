"""A DOCTYPE or entity declaration in a robot description.

Why: URDF needs no DTD. Entities can read local files or expand to gigabytes ("billion laughs"),
so urdf-lint never loads DTDs or resolves entities, refuses entity declarations, and reports any
DOCTYPE.

How to fix: Remove the declaration.
"""
CODE = "UL007"
NAME = "doctype"
SEVERITY = "error"
ORIGIN = "expansion"
FAIL = """<?xml version="1.0"?>
<!DOCTYPE robot [<!ENTITY secret SYSTEM "file:///etc/passwd">]>
<robot name="r">
  <link name="&secret;"/>
</robot>
"""
FAIL_AT = [(2, 1)]
PASS = """<?xml version="1.0"?>
<robot name="r">
  <link name="a"/>
</robot>
"""
