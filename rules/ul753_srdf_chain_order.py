"""An SRDF chain's tip link is not below its base link in the robot's tree.

Why: MoveIt builds a chain group by walking from the tip up to the base; when the base is not
an ancestor of the tip (swapped ends, a link of another branch), the group is dropped ("Links
'a' and 'b' do not form a chain") and nothing can be planned for it.

Consumers: ros (MoveIt) only: the other consumers do not read SRDF files.

How to fix: Swap `base_link` and `tip_link`, or pick a base on the tip's path to the root.
"""
CODE = "UL753"
NAME = "srdf-chain-order"
SEVERITY = "error"
TARGETS = {"*": "off", "ros": "error"}
from urdf_lint.rules._config import example_robot
FAIL = example_robot(("j1", "base", "l2"), ("j2", "l2", "l1"), links=("base", "l1", "l2"))
PASS = example_robot(("j1", "base", "l1"), ("j2", "l1", "l2"), links=("base", "l1", "l2"))
EXAMPLE_FILES = {"config/r.srdf": """<robot name="r">
  <group name="arm">
    <chain base_link="l1" tip_link="l2"/>
  </group>
</robot>
"""}
EXAMPLE_AT = "config/r.srdf"
FAIL_AT = [(3, 5)]
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._config import chain, srdfs


def check(model: "Model", ctx: "Context") -> "Checked":
    for doc in srdfs(ctx):
        for el in doc.root.iterfind("group/chain"):
            base, tip = el.get("base_link"), el.get("tip_link")
            if base not in model.links or tip not in model.links:
                continue          # UL750 says so
            if chain(model, base, tip) is None:
                swapped = chain(model, tip, base) is not None
                yield Report(doc.at(el), f"chain of group '{el.getparent().get('name')}': tip "
                             f"'{tip}' is not below base '{base}'"
                             + (" (base and tip are swapped)" if swapped else ""),
                             related=model.links[tip])
