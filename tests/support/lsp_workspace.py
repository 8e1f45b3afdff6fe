"""A workspace built from strings that lints in this process (``Workspace(root,
in_process=True)``: no worker is forked, nothing is started), so each language-server method
is tested under ``-m unit`` through its ``handle(services, params)``."""
from __future__ import annotations

import os
from pathlib import Path

import pytest
from lsprotocol import types

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
# a small robot: a macro library (with a doc comment) used by two models
ARM = f"""<?xml version="1.0"?>
<robot {X}>
  <!-- An arm link on a revolute elbow. -->
  <xacro:macro name="arm" params="prefix lower:=0.5 upper">
    <link name="${{prefix}}arm"/>
    <joint name="${{prefix}}elbow" type="revolute">
      <parent link="base"/><child link="${{prefix}}arm"/><axis xyz="0 0 1"/>
      <limit lower="${{lower}}" upper="${{upper}}" effort="1" velocity="1"/>
    </joint>
  </xacro:macro>
</robot>
"""
BOT = f"""<?xml version="1.0"?>
<robot name="bot" {X}>
  <xacro:include filename="arm.xacro"/>
  <xacro:property name="reach" value="1.5"/>
  <link name="base"/>
  <xacro:arm prefix="l_" upper="${{reach}}"/>
</robot>
"""
SHORT = f"""<?xml version="1.0"?>
<robot name="short" {X}>
  <xacro:include filename="arm.xacro"/>
  <link name="base"/>
  <xacro:arm prefix="s_" upper="0.2"/>
</robot>
"""

# issue 39: a defect behind a boolean arg and one behind a compared literal, none at the defaults
BRANCHY = f"""<?xml version="1.0"?>
<robot name="r" {X}>
  <xacro:arg name="sim" default="false"/>
  <xacro:arg name="gripper" default="none"/>
  <link name="base"/>
  <xacro:if value="$(arg sim)">
    <link name="sim_link"><inertial><mass value="-1"/><inertia ixx="1e-3" ixy="0" ixz="0"
      iyy="2e-3" iyz="0" izz="3e-3"/></inertial></link>
    <joint name="sim_j" type="fixed"><parent link="base"/><child link="sim_link"/></joint>
  </xacro:if>
  <xacro:if value="${{'$(arg gripper)' == 'robotiq'}}">
    <joint name="grip_j" type="fixed"><parent link="base"/><child link="no_grip"/></joint>
  </xacro:if>
</robot>
"""


class Editor:
    """The language server's services over a package written from strings; ``open`` makes a
    file an editor buffer (unsaved text), ``lint`` lints every model in process."""

    def __init__(self, root: Path):
        from urdf_lint.lsp.services import Services
        from urdf_lint.lsp.state import Workspace
        self.root = root
        self.ws = Workspace(str(root), pool_size=1, in_process=True)
        self.sv = Services(self.ws)

    def path(self, name: str) -> str:
        return os.path.realpath(self.root / "urdf" / name)

    def uri(self, name: str) -> str:
        return Path(self.path(name)).as_uri()

    def open(self, name: str, text: str | None = None) -> str:
        p = self.path(name)
        self.ws.buffers[p] = (text if text is not None else Path(p).read_text()).encode()
        return p

    def lint(self) -> set:
        return self.ws.lint()

    def at(self, name: str, needle: str, offset: int = 0) -> types.Position:
        """The position ``offset`` characters into the first ``needle`` of the file's text."""
        p = self.path(name)
        text = self.ws.buffers[p].decode() if p in self.ws.buffers else Path(p).read_text()
        i = text.index(needle) + offset
        line = text.count("\n", 0, i)
        return types.Position(line, i - (text.rfind("\n", 0, i) + 1))

    def doc(self, name: str) -> types.TextDocumentIdentifier:
        return types.TextDocumentIdentifier(uri=self.uri(name))


@pytest.fixture
def editor(tmp_path, monkeypatch):
    """A factory: ``editor({"bot.urdf.xacro": text, ...})`` writes a package ``pkg`` holding
    the files under ``urdf/`` and returns its :class:`Editor` (closed after the test)."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    monkeypatch.delenv("URDF_LINT_CACHE_DIR", raising=False)
    made: list[Editor] = []

    def make(files: dict[str, str]) -> Editor:
        pkg = tmp_path / "pkg"
        (pkg / "urdf").mkdir(parents=True, exist_ok=True)
        (pkg / "package.xml").write_text("<package><name>pkg</name></package>\n")
        for name, text in files.items():
            (pkg / "urdf" / name).write_text(text)
        ed = Editor(pkg)
        made.append(ed)
        return ed
    yield make
    for ed in made:
        ed.ws.close()
