"""The model must have exactly one root link (a link that is no joint's child).

Why: No root means every link is somebody's child: the joints form a closed loop. Several roots
mean separate trees. URDF parsers refuse both (Pinocchio 4.1.0 rejects two roots, PyBullet 3.2.7
crashes); MuJoCo 4.0.0 loads a second tree as another body on the world (a warning for `mujoco`;
measured). Links that no joint touches at all are reported
by UL104 instead.

How to fix: Connect the extra trees with a joint (often a `fixed` joint to the main base), or
break the loop.
"""
CODE = "UL101"
NAME = "single-root"
SEVERITY = "error"
FAIL = """<robot name="r">
  <link name="a"/><link name="b"/><link name="c"/><link name="d"/>
  <joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>
  <joint name="j2" type="fixed"><parent link="c"/><child link="d"/></joint>
</robot>
"""
FAIL_AT = [(2, 35)]
PASS = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>
</robot>
"""


from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model


def check(model: "Model", ctx: "Context") -> "Checked":
    links = model.top_links()
    names = [lk.get("name") for lk in links if lk.get("name")]
    if not names:
        return
    children = model.parents_of_links()
    parents_of_joints: dict[str, list[Any]] = {}
    for j in model.top_joints():
        p = j.find("parent")
        if p is not None and p.get("link"):
            parents_of_joints.setdefault(p.get("link"), []).append(j)
    roots = [n for n in dict.fromkeys(names) if n not in children]
    # isolated links (no joint at all) are UL104's business
    tree_roots = [n for n in roots if n in parents_of_joints or len(names) == 1]
    undefined_parents = [p for p in parents_of_joints if p not in model.links]
    if not roots and undefined_parents:
        return  # the tree hangs off a link that is not defined: UL103 reports it
    if not roots:
        yield Report(model.root, ("no root link: every link is the child of a joint, so the joints form "
                                  "a closed loop; make one link the base (no joint names it as child)"))
        return
    if len(tree_roots) > 1:
        # the main tree is the largest; every other root is reported where it is defined
        def size(n: str, seen: set[str] | None = None) -> int:
            seen = seen if seen is not None else set()
            if n in seen:
                return 0
            seen.add(n)
            total = 1
            for j in parents_of_joints.get(n, []):
                c = j.find("child")
                if c is not None and c.get("link"):
                    total += size(c.get("link"), seen)
            return total
        ordered = sorted(tree_roots, key=lambda n: -size(n))
        main = ordered[0]
        for n in ordered[1:]:
            yield Report(model.links[n], (f"link '{n}' is a second root (the main tree starts at "
                                          f"'{main}'); connect it with a joint or remove it"), targets={"mujoco": "warning"})
