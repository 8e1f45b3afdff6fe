"""A `<ros2_control>` sensor of a Gazebo hardware plugin names no sensor of the robot's `<gazebo>` blocks.

Why: gz_ros2_control (`gz_ros2_control/GazeboSimSystem`, and its old name
`ign_ros2_control/IgnitionSystem`) and gazebo_ros2_control (`gazebo_ros2_control/GazeboSystem`)
give a `<ros2_control>` `<sensor>` its state interfaces by finding the simulator's sensor of
the same name: the `<sensor name="...">` of an IMU or force-torque sensor in a `<gazebo
reference="link">` block. With no sensor of that name the interfaces are never exported
(gazebo_ros2_control logs "Error retrieving sensor"), and the broadcaster reading them
(`imu_sensor_broadcaster`, `force_torque_sensor_broadcaster`) fails to activate at start-up.

Only these Gazebo plugins are checked: for real or mock hardware a sensor's name and its
`frame_id` parameter belong to the hardware plugin, not to the robot's tree
(`ros2_control_demos` examples 4, 5 and 7 name a `tcp_fts_sensor` that is no link or joint),
and a `<gpio>` names a group of I/O interfaces of the hardware (`flange_analog_IOs`,
`reactivate_gripper`), not a robot element: neither is checked. A warning, not an error: the
simulator looks the name up in the whole world, so a sensor of the world file would also serve.

Consumers: ros and gazebo (the simulated robot started through ros2_control).

How to fix: Name the `<ros2_control>` sensor after the `<gazebo>` sensor it reads (the "did you
mean" candidate), or add the sensor to the link's `<gazebo reference>` block.
"""
CODE = "UL716"
NAME = "ros2-control-sensor"
SEVERITY = "warning"
TARGETS = {"*": "off", "ros": "warning", "gazebo": "warning"}
_GAZEBO = """  <gazebo reference="l1">
    <sensor name="imu_sensor" type="imu"><update_rate>100</update_rate></sensor>
  </gazebo>
  <ros2_control name="sim" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <sensor name="imu"><state_interface name="orientation.x"/></sensor>
  </ros2_control>
"""
from urdf_lint.rules._config import example_robot
FAIL = example_robot(("joint1", "base", "l1"), tail=_GAZEBO)
FAIL_AT = [(10, 5)]
PASS = FAIL.replace('<sensor name="imu">', '<sensor name="imu_sensor">')
from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report, did_you_mean

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model

PLUGINS = ("gz_ros2_control/GazeboSimSystem", "ign_ros2_control/IgnitionSystem",
           "gazebo_ros2_control/GazeboSystem")


def simulated(rc: Any) -> bool:
    """Whether a ``<ros2_control>`` block's hardware is one of the Gazebo plugins."""
    plugin = rc.find("hardware/plugin")
    return plugin is not None and (plugin.text or "").strip() in PLUGINS


def check(model: "Model", ctx: "Context") -> "Checked":
    blocks = [rc for rc in model.root.iterfind("ros2_control") if simulated(rc)]
    if not blocks:
        return
    have = {s.get("name"): s for g in model.root.iterfind("gazebo")
            for s in g.iter("sensor") if s.get("name")}
    for rc in blocks:
        for s in rc.iterfind("sensor"):
            name = s.get("name")
            if not name or name in have:
                continue
            yield Report(s, f"ros2_control '{rc.get('name')}' sensor '{name}' is no sensor of the "
                         f"robot's <gazebo> blocks: the simulator exports no interface for it"
                         + did_you_mean(name, have))
