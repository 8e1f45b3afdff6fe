"""An SRDF `disable_collisions` pair names a link the robot does not have.

Why: MoveIt skips the pair with a warning, so the pair it was meant to silence is checked
again: the allowed collision matrix is stale, typically after a link was renamed, and
planning reports collisions between links that always touch (or it slows down on pairs that
can never collide).

Consumers: ros (MoveIt) only: the other consumers do not read SRDF files.

How to fix: Rename the link in the pair, or regenerate the collision matrix with the MoveIt
Setup Assistant.

Fix: unsafe, when the name has one close candidate among the robot's links (the element renamed
in the xacro): `--fix --unsafe-fixes` renames it on the reported line, verified by re-linting.
"""
CODE = "UL752"
NAME = "srdf-stale-collision-pair"
SEVERITY = "warning"
TARGETS = {"*": "off", "ros": "warning"}
from urdf_lint.rules._config import PAIRS_SRDF_EXAMPLE, example_robot
FAIL = example_robot(("j1", "base", "l1"), ("j2", "l1", "link_2"), links=("base", "l1", "link_2"))
PASS = FAIL.replace("link_2", "l2")
EXAMPLE_FILES = {"config/r.srdf": PAIRS_SRDF_EXAMPLE}
EXAMPLE_AT = "config/r.srdf"
FAIL_AT = [(3, 3)]
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._config import closest, rename_fix, srdfs


def check(model: "Model", ctx: "Context") -> "Checked":
    for doc in srdfs(ctx):
        for el in doc.root.iterfind("disable_collisions"):
            stale = [el.get(a) for a in ("link1", "link2") if el.get(a) and
                     el.get(a) not in model.links]
            if not stale:
                continue
            near, rel = closest(model, stale[0], model.links)
            yield Report(doc.at(el), f"stale disable_collisions pair ({el.get('link1')}, "
                         f"{el.get('link2')}): {' and '.join(repr(s) for s in stale)} "
                         f"{'is not a link' if len(stale) == 1 else 'are not links'} of robot "
                         f"'{model.name}'" + near, related=rel,
                             fix=rename_fix(doc.at(el), stale[0], model.links, doc))
