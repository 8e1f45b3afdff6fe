"""An SRDF `disable_collisions` pair that has no effect: one of its links has no collision geometry, or the same pair is written again.

Why: MoveIt does not compute adjacency at run time. Its allowed collision matrix starts with
every pair of links that have collision geometry enabled and disables exactly the
`disable_collisions` pairs of the SRDF (the `reason` is documentation only): an `Adjacent` pair
is needed, not redundant, because MoveIt would not skip those two links otherwise. Adjacency is
the MoveIt Setup Assistant's: it writes `Adjacent` for two links joined by a joint, or by a
chain of links without geometry, when both have collision geometry. So the only pairs MoveIt
never uses are those naming a link without collision geometry (MoveIt never checks that link;
the Setup Assistant never writes such a pair: a leftover from a link whose `<collision>` was
removed) and a pair written twice. Information: harmless, but it hides what the matrix really
disables. A pair naming a link the robot does not have is UL752's.

Consumers: ros (MoveIt) only: the other consumers do not read SRDF files.

How to fix: Delete the line, or regenerate the collision matrix with the MoveIt Setup Assistant.
"""
CODE = "UL757"
NAME = "srdf-redundant-collision-pair"
SEVERITY = "info"
TARGETS = {"*": "off", "ros": "info"}
from urdf_lint.rules._config import example_robot, PAIRS_SRDF_EXAMPLE
_BOX = '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'
FAIL = example_robot(("j1", "base", "l1"), ("j2", "l1", "l2"), links=("base", "l1", "l2")).replace(
    '<link name="base"/><link name="l1"/>',
    f'<link name="base">{_BOX}</link><link name="l1">{_BOX}</link>')
PASS = FAIL.replace('<link name="l2"/>', f'<link name="l2">{_BOX}</link>')
EXAMPLE_FILES = {"config/r.srdf": PAIRS_SRDF_EXAMPLE}
EXAMPLE_AT = "config/r.srdf"
FAIL_AT = [(3, 3)]
from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._config import srdfs


def check(model: "Model", ctx: "Context") -> "Checked":
    for doc in srdfs(ctx):
        seen: dict[Any, Any] = {}
        for el in doc.root.iterfind("disable_collisions"):
            a, b = el.get("link1"), el.get("link2")
            if a not in model.links or b not in model.links:
                continue                          # UL752
            pair = frozenset((a, b))
            bare = [n for n in (a, b) if model.links[n].find("collision") is None]
            if bare:
                yield Report(doc.at(el), f"disable_collisions ({a}, {b}) has no effect: link "
                             f"'{bare[0]}' has no collision geometry, so MoveIt never checks it",
                             related=model.links[bare[0]])
            elif pair in seen:
                yield Report(doc.at(el), f"disable_collisions ({a}, {b}) is written again "
                             f"(line {doc.at(seen[pair]).line}): MoveIt uses it once",
                             related=model.links[a])
            seen.setdefault(pair, el)
