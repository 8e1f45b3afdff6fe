"""What the rules about a robot's configuration files share (UL710-UL749 ros2_control and
controllers, UL750-UL799 SRDF and MoveIt): the files tied to the model (``ctx.configs``, each
with ``kind``, ``path``, ``root`` and ``at(node)``: an Origin at its own line), the controllers
of a controller YAML, the interfaces ``<ros2_control>`` declares, and the SRDF's tree walks."""
from __future__ import annotations

import re
from typing import TYPE_CHECKING, Any, Iterable, Iterator, Mapping, Sequence

from urdf_lint.engine.api import Request, did_you_mean, number, rename_at, single_candidate

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.engine.api import ConfigDoc, Context, Model, YNode

# (lower, upper, velocity, effort, acceleration) of a joint's <limit>
Limits = tuple[float | None, float | None, float | None, float | None, float | None]

SUBST = re.compile(r"\$\((var|arg|env|optenv|find)\s[^)]*\)")


def targets(severity: str, gazebo: bool = False) -> dict[str, str]:
    """The TARGETS table of a configuration rule: ``severity`` for ros (and gazebo)."""
    return {"*": "off", "ros": severity, **({"gazebo": severity} if gazebo else {})}


def docs(ctx: Context, *kinds: str) -> list[ConfigDoc]:
    return [d for d in getattr(ctx, "configs", ()) if d.kind in kinds]


def srdfs(ctx: Context) -> list[ConfigDoc]:
    return docs(ctx, "srdf")


# -- the robot ---------------------------------------------------------------------------------
def joint_limits(model: Model, name: str) -> Limits:
    """(lower, upper, velocity, effort, acceleration) of a joint's ``<limit>`` (None where it
    does not say, or the joint is not limited in position: continuous)."""
    j: Any = model.joints.get(name)   # an lxml element, or None
    lim = j.find("limit") if j is not None else None
    if lim is None:
        return None, None, None, None, None
    ranged = j.get("type") in ("revolute", "prismatic")
    return (number(lim.get("lower", "0")) if ranged else None,
            number(lim.get("upper", "0")) if ranged else None,
            number(lim.get("velocity")), number(lim.get("effort")),
            number(lim.get("acceleration")))


def parent_of(model: Model) -> dict[str, tuple[Any, str | None]]:
    """child link -> (joint, parent link) of the robot's tree."""
    out: dict[str, tuple[Any, str | None]] = {}
    for j in model.top_joints():
        p, c = j.find("parent"), j.find("child")
        if p is not None and c is not None and c.get("link"):
            out.setdefault(c.get("link"), (j, p.get("link")))
    return out


def ros2_control_joints(model: Model) -> dict[str, tuple[Any, set[str], set[str]]]:
    """joint name -> (``<ros2_control>`` joint element, command interfaces, state interfaces),
    over every ``<ros2_control>`` block."""
    out: dict[str, tuple[Any, set[str], set[str]]] = {}
    for rc in model.root.iterfind("ros2_control"):
        for j in rc.iter("joint"):
            n = j.get("name")
            if not n:
                continue
            _, cmd, st = out.get(n, (j, set(), set()))
            cmd |= {c.get("name") for c in j.iter("command_interface") if c.get("name")}
            st |= {s.get("name") for s in j.iter("state_interface") if s.get("name")}
            out[n] = (j, cmd, st)
    return out


def resolve_name(ctx: Context, name: str) -> tuple[str, bool]:
    """(the name with the launch substitutions the model's xacro args give (``$(var
    tf_prefix)`` with the arg ``tf_prefix``, given or its default), whether one was left)."""
    args: dict[str, str] = getattr(ctx, "config_args", {})

    def sub(m: re.Match[str]) -> str:
        word = m.group(0)[2:-1].split()
        if word[0] in ("var", "arg") and len(word) == 2 and word[1] in args:
            return args[word[1]]
        return m.group(0)
    got = SUBST.sub(sub, name)
    return got, bool(SUBST.search(got))


# -- controller YAML ---------------------------------------------------------------------------
def controllers(doc: ConfigDoc) -> list[tuple[str, str, YNode]]:
    """(name, type or "", the node of its ``ros__parameters``) of every controller a
    ros2_control controller YAML configures (types from ``controller_manager`` or the
    controller's own ``type``)."""
    root = doc.root
    if root is None or not isinstance(root.value, dict):
        return []
    root = _unwrap(root)
    cm = root.get("controller_manager")
    cm = cm.get("ros__parameters") if cm is not None else None
    types: dict[str, str] = {}
    for name, node in (cm.items() if cm is not None else ()):
        t = node.get("type") if isinstance(node.value, dict) else None
        if t is not None and isinstance(t.value, str):
            types[name] = t.value
    out: list[tuple[str, str, YNode]] = []
    for name, node in root.items():
        if name == "controller_manager":
            continue
        params = node.get("ros__parameters")
        if params is None:
            continue
        t = params.get("type")
        out.append((name, types.get(name) or (t.value if t is not None else "") or "", params))
    return out


def _unwrap(root: YNode) -> YNode:
    """The document below a ``/**:`` or namespace wrapper holding the controllers."""
    if root.get("controller_manager") is None:
        for _, v in root.items():
            if isinstance(v.value, dict) and v.get("controller_manager") is not None:
                return v
    return root


def names(node: YNode | None) -> list[YNode]:
    """The string scalars of a node (``joint: j1`` and ``joints: [j1, j2]`` alike)."""
    return [n for n in (node.seq() if node is not None else ()) if isinstance(n.value, str)]


# command interfaces, state interfaces per well-known controller type (the type's package and
# class, as the controller_manager names it); None: read from its parameters
_POS, _VEL, _EFF = "position", "velocity", "effort"
KNOWN_TYPES: dict[str, tuple[tuple[str, ...] | None, tuple[str, ...] | None]] = {
    "joint_trajectory_controller/JointTrajectoryController": (None, None),
    "forward_command_controller/ForwardCommandController": (None, ()),
    "forward_command_controller/MultiInterfaceForwardCommandController": (None, ()),
    "position_controllers/JointGroupPositionController": ((_POS,), ()),
    "velocity_controllers/JointGroupVelocityController": ((_VEL,), ()),
    "effort_controllers/JointGroupEffortController": ((_EFF,), ()),
    "position_controllers/GripperActionController": ((_POS,), (_POS,)),
    "effort_controllers/GripperActionController": ((_EFF,), (_POS,)),
    "parallel_gripper_action_controller/GripperActionController": ((_POS,), (_POS,)),
    "diff_drive_controller/DiffDriveController": ((_VEL,), None),
    "joint_state_broadcaster/JointStateBroadcaster": ((), ()),
}
JOINT_KEYS = ("joints", "joint", "left_wheel_names", "right_wheel_names")


def controller_joints(params: YNode) -> list[YNode]:
    """The joint-name scalars a controller's parameters list (``joints``, ``joint``, the
    wheels of a diff drive)."""
    return [n for k in JOINT_KEYS for n in names(params.get(k))]


def needed_interfaces(ctype: str, params: YNode
                      ) -> tuple[tuple[str, ...], tuple[str, ...]] | None:
    """(command interfaces, state interfaces) a well-known controller type needs for each of
    its joints, or None for a type urdf-lint does not know (its joints are still checked)."""
    if ctype not in KNOWN_TYPES:
        return None
    cmd, st = KNOWN_TYPES[ctype]
    if ctype.startswith("joint_trajectory"):
        cmd = tuple(n.value for n in names(params.get("command_interfaces")))
        st = tuple(n.value for n in names(params.get("state_interfaces")))
    elif ctype.startswith("forward_command_controller"):
        iface = params.get("interface_name")
        cmd = (iface.value,) if iface is not None and isinstance(iface.value, str) else \
            tuple(n.value for n in names(params.get("command_interfaces")))
    elif ctype.startswith("diff_drive"):
        fb = params.get("position_feedback")
        st = (_VEL,) if fb is not None and fb.value is False else (_POS,)
    return tuple(cmd or ()), tuple(st or ())


# -- SRDF --------------------------------------------------------------------------------------
def groups(root: Any) -> dict[str, Any]:
    """name -> ``<group>`` element of an SRDF (top level)."""
    return {g.get("name"): g for g in root if getattr(g, "tag", None) == "group" and g.get("name")}


def group_joints(model: Model, root: Any, name: str, seen: set[str] | None = None) -> list[str]:
    """The joints a group contains, as MoveIt computes them: its joints, the parent joints of
    its links, the joints along its chains, its subgroups' (unknown names skipped)."""
    seen = set() if seen is None else seen
    g = groups(root).get(name)
    if g is None or name in seen:
        return []
    seen.add(name)
    par = parent_of(model)
    out: list[str] = []
    for el in g:
        tag = getattr(el, "tag", None)
        if tag == "joint" and el.get("name") in model.joints:
            out.append(el.get("name"))
        elif tag == "link" and el.get("name") in par:
            out.append(par[el.get("name")][0].get("name"))
        elif tag == "chain":
            out += [j.get("name") for j in chain(model, el.get("base_link"), el.get("tip_link"))
                    or ()]
        elif tag == "group":
            out += group_joints(model, root, el.get("name"), seen)
    return list(dict.fromkeys(out))


def chain(model: Model, base: str | None, tip: str | None) -> list[Any] | None:
    """The joints from ``base`` down to ``tip`` (a list), or None when ``tip`` is not below
    ``base``."""
    par = parent_of(model)
    out: list[Any] = []
    link, steps = tip, 0
    while link != base:
        up = par.get(link) if link is not None else None
        if up is None or steps > len(par):
            return None
        out.append(up[0])
        link = up[1]
        steps += 1
    return list(reversed(out))


def moving_joint(model: Model, name: str) -> bool:
    j = model.joints.get(name)
    return j is not None and j.get("type") not in ("fixed", None)


def named_joints(ctx: Context) -> Iterator[tuple[ConfigDoc, YNode, str, str]]:
    """(config doc, YAML node of a joint name, the name, what names it) for every joint a
    controller YAML, ``initial_positions.yaml`` or ``moveit_controllers.yaml`` names."""
    for doc in docs(ctx, "controllers"):
        for name, _, params in controllers(doc):
            for n in controller_joints(params):
                yield doc, n, n.value, f"controller '{name}'"
    for doc in docs(ctx, "initial-positions"):
        pos = doc.root.get("initial_positions") if doc.root is not None else None
        for name, node in (pos.items() if pos is not None else ()):
            yield doc, node, name, "initial_positions.yaml"
    for doc, name, node in moveit_controllers(ctx):
        for n in names(node.get("joints")):
            yield doc, n, n.value, f"MoveIt controller '{name}'"


# -- MoveIt's joint_limits.yaml ----------------------------------------------------------------
def limit_entries(ctx: Context) -> Iterator[tuple[ConfigDoc, str, YNode]]:
    """(doc, joint name, its YAML node) of every ``joint_limits:`` entry of the MoveIt
    ``joint_limits.yaml`` files tied to the model."""
    for doc in docs(ctx, "joint-limits"):
        jl = doc.root.get("joint_limits") if doc.root is not None else None
        for name, node in (jl.items() if jl is not None else ()):
            if isinstance(node.value, dict):
                yield doc, name, node


def scalar(node: YNode | None) -> float | None:
    """A YAML node's number (None for anything else, booleans too)."""
    if node is None or isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
        return None
    return float(node.value)


def closest(model: Model, name: str, table: Mapping[str, Any]) -> tuple[str, Any]:
    """(" (did you mean 'x'?)" or "", the element to relate the finding to: the closest of
    ``table`` (the robot's joints or links), else the robot)."""
    near = did_you_mean(name, table)
    return near, table[near.split("'")[1]] if near else model.root


def rename_fix(at: Any, name: str, table: Iterable[str], doc: ConfigDoc) -> Request | None:
    """The unsafe fix renaming ``name`` at ``at`` (an SRDF or YAML line) to the one name of
    ``table`` close to it that ``doc`` does not name already (the element renamed in the xacro:
    'panda_joint3' becomes 'panda_joint_3', not 'panda_joint2', which the file still names), or
    None. The request (``rename_at``) is resolved at the line the finding is reported at
    (``at``), by the engine."""
    named = doc_names(doc)
    new = single_candidate(name, [n for n in table if n not in named], 0.75)
    return rename_at(name, new) if new else None


def doc_names(doc: ConfigDoc) -> set[str]:
    """Every name a configuration file writes: SRDF attribute values, YAML keys and strings."""
    if not hasattr(doc, "_names"):
        out: set[str] = set()
        root = doc.root
        if hasattr(root, "iter"):        # an SRDF element tree
            for el in root.iter():
                out.update(getattr(el, "attrib", {}).values())
        else:
            todo = [root] if root is not None else []
            while todo:
                n = todo.pop()
                if isinstance(n.value, dict):
                    out.update(n.value)
                    todo.extend(n.value.values())
                elif isinstance(n.value, list):
                    todo.extend(n.value)
                elif isinstance(n.value, str):
                    out.add(n.value)
        doc._names = out   # type: ignore[attr-defined]  # a memo on the document
    got: set[str] = doc._names   # type: ignore[attr-defined]  # (set above)
    return got


def moveit_controllers(ctx: Context) -> Iterator[tuple[ConfigDoc, str, YNode]]:
    """(doc, controller name, its node) of every controller ``moveit_controllers.yaml`` files
    give ``moveit_simple_controller_manager``."""
    for doc in docs(ctx, "moveit-controllers"):
        mscm = doc.root.get("moveit_simple_controller_manager") if doc.root is not None else None
        for name, node in (mscm.items() if mscm is not None else ()):
            yield doc, name, node


def actuated(model: Model, name: str) -> bool:
    """Whether a joint is moved on its own: a moving joint that mimics no other."""
    return moving_joint(model, name) and model.joints[name].find("mimic") is None


# -- the rules' FAIL/PASS examples -------------------------------------------------------------
LIMIT = 'lower="-1" upper="1" effort="10" velocity="1"'
ROS2_CONTROL_EXAMPLE = """  <ros2_control name="sys" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="joint1"><command_interface name="position"/><state_interface name="position"/></joint>
  </ros2_control>
"""
ARM_SRDF_EXAMPLE = """<robot name="r">
  <group name="arm">
    <chain base_link="base" tip_link="l2"/>
  </group>
</robot>
"""
PAIRS_SRDF_EXAMPLE = """<robot name="r">
  <disable_collisions link1="base" link2="l1" reason="Adjacent"/>
  <disable_collisions link1="l1" link2="l2" reason="Adjacent"/>
</robot>
"""


def moveit_controllers_example(*joints: str) -> str:
    """A ``moveit_controllers.yaml`` whose one trajectory controller drives ``joints``."""
    return ("moveit_simple_controller_manager:\n  controller_names:\n    - arm_controller\n"
            "  arm_controller:\n    type: FollowJointTrajectory\n    joints:\n"
            + "".join(f"      - {j}\n" for j in joints))


LIMITS_EXAMPLE_FILES = {"config/r.srdf": """<robot name="r">
</robot>
""", "config/joint_limits.yaml": """joint_limits:
  joint1:
    has_velocity_limits: true
    max_velocity: 0.5
    has_acceleration_limits: true
    max_acceleration: 1.0
"""}


def example_robot(*joints: tuple[str, ...], links: Sequence[str] = ("base", "l1"),
                  tail: str = "") -> str:
    """The URDF of a rule's example: robot 'r' with ``links`` on one line, a revolute joint
    about z per (name, parent, child[, its ``<limit>`` attributes]) of ``joints``, ``tail``."""
    out = ['<robot name="r">', "  " + "".join(f'<link name="{n}"/>' for n in links)]
    for name, parent, child, *lim in joints:
        out += [f'  <joint name="{name}" type="revolute"><parent link="{parent}"/>'
                f'<child link="{child}"/>',
                f'    <axis xyz="0 0 1"/><limit {lim[0] if lim else LIMIT}/></joint>']
    return "\n".join(out) + "\n" + tail + "</robot>\n"


def forward_controller_example(joint: str) -> str:
    """A controller YAML configuring a forward position controller of ``joint``."""
    return f"""controller_manager:
  ros__parameters:
    forward_position_controller:
      type: forward_command_controller/ForwardCommandController

forward_position_controller:
  ros__parameters:
    joints:
      - {joint}
    interface_name: position
"""
