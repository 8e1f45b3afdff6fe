"""A visual refers to a material by name, but no material of that name with a colour or texture is
defined.

Why: the visual is drawn in a default colour: urdfdom 6.0.0 and iDynTree 15.1.0 warn, the
other consumers measured (MuJoCo 4.0.0, Pinocchio 4.1.0, PyBullet 3.2.7, the Python parsers,
sdformat 12.3, the Isaac importer) load it silently. A warning for every target but `drake`:
Drake 1.51.1 rejects it ("Material 'nowhere' not previously defined", measured by
bench/consumers/harness.py); a material without a name, colour or texture stays an error.

How to fix: Define the material at the top level, or fix the name.

Fix: safe, when the name has a single close "did you mean" candidate: `--fix`
writes it where the name is written.
"""
CODE = "UL502"
NAME = "material-undefined"
SEVERITY = "error"
FAIL = """<robot name="r">
  <link name="a"><visual><geometry><box size="1 1 1"/></geometry><material name="blu"/></visual></link>
</robot>
"""
FAIL_AT = [(2, 66)]
PASS = """<robot name="r">
  <material name="blue"><color rgba="0 0 1 1"/></material>
  <link name="a"><visual><geometry><box size="1 1 1"/></geometry><material name="blue"/></visual></link>
</robot>
"""
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, did_you_mean, reference_fixes

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._schema import urdf_iter


def check(model: "Model", ctx: "Context") -> "Checked":
    defined = set()
    for m in urdf_iter(model, "material"):
        if m.get("name") and (m.find("color") is not None or m.find("texture") is not None):
            defined.add(m.get("name"))
    for v in urdf_iter(model, "visual"):
        for m in v.findall("material"):
            n = m.get("name")
            if m.find("color") is None and m.find("texture") is None:
                if not n:
                    yield Report(m, "<material> without a name, colour or texture")
                elif n not in defined:
                    fix = reference_fixes([(m, "name", n)], defined).get((m, "name"))
                    yield Report(m, (f"material '{n}' is used but never defined (drawn in a default "
                                     "colour)" + did_you_mean(n, defined)), severity="warning", fix=fix,
                                 targets={"drake": "error"})
