"""A small xacro arm for the preview's tests: a package with an STL mesh, a macro used twice,
a mimic joint, two findings on links (UL801 on base_link, UL601 on tool), a secret beside the
package that no page may read, and a started preview server (``serve``)."""
from __future__ import annotations

import contextlib
import http.client
from pathlib import Path

from support.repo_shapes import package_xml, stl_box

ROBOT = """<?xml version="1.0"?>
<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="len" default="0.4"/>
  <xacro:macro name="seg" params="name parent">
    <link name="${name}">
      <visual><geometry><mesh filename="package://arm_description/meshes/arm.stl"
        scale="0.5 0.5 4"/></geometry></visual>
      <collision><geometry><box size="0.05 0.05 0.4"/></geometry></collision>
      <inertial><mass value="1"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.001"/></inertial>
    </link>
    <joint name="${name}_joint" type="revolute">
      <parent link="${parent}"/><child link="${name}"/>
      <origin xyz="0 0 $(arg len)"/><axis xyz="0 1 0"/>
      <limit lower="-1.5" upper="1.5" effort="10" velocity="1"/>
    </joint>
  </xacro:macro>
  <link name="base_link">
    <visual><geometry><box size="0.3 0.3 0.1"/></geometry></visual>
  </link>
  <xacro:seg name="upper" parent="base_link"/>
  <xacro:seg name="lower" parent="upper"/>
  <link name="tool"/>
  <joint name="tool_joint" type="revolute">
    <parent link="lower"/><child link="tool"/><origin xyz="0 0 0.4"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
    <mimic joint="lower_joint" multiplier="1"/>
  </joint>
</robot>
"""


def make_robot(tmp: Path, extra_links: str = "") -> Path:
    """The package under ``tmp``; returns the entry file. ``extra_links`` goes before
    ``</robot>``."""
    pkg = tmp / "arm_description"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "meshes").mkdir()
    (pkg / "package.xml").write_text(package_xml("arm_description"))
    (pkg / "meshes" / "arm.stl").write_bytes(stl_box(0.1))
    (pkg / "meshes" / "unreferenced.stl").write_bytes(stl_box(0.1))
    (tmp / "secret.txt").write_text("TOKEN=hunter2\n")
    entry = pkg / "urdf" / "arm.urdf.xacro"
    entry.write_text(ROBOT.replace("</robot>", extra_links + "</robot>"))
    return entry


@contextlib.contextmanager
def serve(entry: Path, **options):
    """A started preview server of ``entry`` (its first expansion done), stopped after."""
    from urdf_lint.cli.common import ConfigOptions
    from urdf_lint.cli.preview import PreviewOptions, start
    from urdf_lint.run.worker import prestart
    prestart()
    o = PreviewOptions(path=str(entry), config=ConfigOptions(isolated=True), **options)
    server, session = start(o)
    server.start()
    session.watch(interval=0.1)
    try:
        yield server, session
    finally:
        session.stop()
        server.shutdown()
        server.server_close()


def get(server, path: str, headers: dict | None = None, method: str = "GET",
        host: str | None = None, body: bytes | None = None):
    """(status, body) of one raw request: ``headers`` exactly as given (Host included; a
    ``body`` adds its Content-Length)."""
    c = http.client.HTTPConnection("127.0.0.1", server.port, timeout=30)
    try:
        c.putrequest(method, path, skip_host=True, skip_accept_encoding=True)
        c.putheader("Host", host if host is not None else f"127.0.0.1:{server.port}")
        for k, v in (headers or {}).items():
            c.putheader(k, v)
        if body is not None:
            c.putheader("Content-Length", str(len(body)))
        c.endheaders(body)
        r = c.getresponse()
        return r.status, r.read()
    finally:
        c.close()
