"""Issue 33: right on robots it has never seen. Each test writes a fixture that reproduces a
pattern of a fresh description repository: args that default through ``$(optenv)``, a hand
that checks its own version with ``xacro.error``, an ``empty.urdf`` placeholder, ``$(find)`` in
a plugin's text, a sibling package outside git."""
from __future__ import annotations

import json

from conftest import make_package, run_cli
from stock_xacro import stock_xacro

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'

# a stock mobile base: every arg defaults through $(optenv), the extras through a placeholder
MOBILE = f"""<?xml version="1.0"?>
<robot name="mobile" {X}>
  <xacro:arg name="laser_enabled" default="$(optenv MOBILE_LASER_ENABLED false)"/>
  <xacro:arg name="urdf_extras" default="$(optenv MOBILE_URDF_EXTRAS empty.urdf)"/>
  <xacro:property name="wheel_radius" value="$(optenv MOBILE_WHEEL_RADIUS 0.1)"/>
  <xacro:include filename="wheel.xacro"/>
  <link name="base_link"/>
  <xacro:wheel side="left"/>
  <xacro:wheel side="right"/>
  <xacro:if value="$(arg laser_enabled)">
    <link name="laser"/>
  </xacro:if>
  <xacro:include filename="$(arg urdf_extras)"/>
</robot>
"""
WHEEL = f"""<?xml version="1.0"?>
<robot {X}>
  <xacro:macro name="wheel" params="side">
    <link name="${{side}}_wheel$(optenv MOBILE_LASER_ENABLED)">
      <inertial><mass value="1"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    </link>
    <joint name="${{side}}_wheel_joint$(optenv MOBILE_LASER_ENABLED)" type="fixed">
      <parent link="base_link"/><child link="${{side}}_wheel$(optenv MOBILE_LASER_ENABLED)"/>
    </joint>
  </xacro:macro>
</robot>
"""
# the placeholder of a stock mobile base: a comment in an empty <robot>
EMPTY = f"""<?xml version="1.0"?>
<robot {X}>
  <!-- a placeholder: set MOBILE_URDF_EXTRAS to the file of your robot's extras -->
</robot>
"""
UNSET = {"MOBILE_LASER_ENABLED": "", "MOBILE_URDF_EXTRAS": "", "MOBILE_WHEEL_RADIUS": ""}


def _mobile(tmp_path):
    return make_package(tmp_path, "mobile_description", {
        "urdf/mobile.urdf.xacro": MOBILE, "urdf/wheel.xacro": WHEEL, "urdf/empty.urdf": EMPTY})


def _check(cwd, *args, env=None):
    # (at the defaults: these fixtures pin what the environment does to one variant; branch
    # exploration, tests/test_explore.py, would add the laser that optenv switches on)
    p = run_cli("check", ".", "--no-cache", "--isolated", "--format", "json", "--explore",
                "false", *args, cwd=cwd, env=env)
    assert p.returncode in (0, 1), p.stderr
    return json.loads(p.stdout), p


def _unset(monkeypatch, names=UNSET):
    """``names`` unset in this process, so in the runs (run_cli adds to os.environ)."""
    for k in names:
        monkeypatch.delenv(k, raising=False)


def test_optenv_of_an_unset_variable_is_stock_xacro(tmp_path, monkeypatch):
    """Item 2: the variables unset, `$(optenv VAR default)` gives what stock xacro gives:
    no UL901, the check passes (it was 6 errors on this fixture), and `expand` writes stock
    xacro's bytes."""
    _unset(monkeypatch)
    pkg = _mobile(tmp_path)
    doc, p = _check(pkg)
    assert [f for f in doc["findings"] if f["code"] == "UL901"] == [], doc["findings"]
    assert p.returncode == 0, doc["findings"]
    entry = str(pkg / "urdf/mobile.urdf.xacro")
    ours = run_cli("expand", entry)
    rc, stock, err = stock_xacro(entry, {}, {"mobile_description": pkg})
    assert rc == 0 and ours.returncode == 0, (err, ours.stderr)
    assert ours.stdout == stock


def test_optenv_of_a_set_variable_warns_once_per_file(tmp_path, monkeypatch):
    """Item 2: set but not allow-listed, the default is used where xacro would read the value:
    a warning (not an error) naming the variable, once per file however often it is read,
    and never its value; allow-listed, it is read and nothing is said."""
    _unset(monkeypatch)
    pkg = _mobile(tmp_path)
    env = {"MOBILE_LASER_ENABLED": "s3cret-true"}
    doc, p = _check(pkg, env=env)
    ul901 = [f for f in doc["findings"] if f["code"] == "UL901"]
    assert sorted((f["file"], f["severity"]) for f in ul901) == [
        ("urdf/mobile.urdf.xacro", "warning"), ("urdf/wheel.xacro", "warning")], ul901
    assert all("MOBILE_LASER_ENABLED" in f["message"] for f in ul901)
    assert not [f for f in ul901 if "MOBILE_URDF_EXTRAS" in f["message"]]
    assert "s3cret" not in p.stdout + p.stderr
    assert p.returncode == 0, doc["findings"]
    doc, _ = _check(pkg, "--env-allow", "MOBILE_LASER_ENABLED", env={"MOBILE_LASER_ENABLED": "false"})
    assert [f for f in doc["findings"] if f["code"] == "UL901"] == [], doc["findings"]


def test_a_set_variable_is_not_served_from_the_cache(tmp_path, monkeypatch):
    """Item 2: whether a variable `$(optenv)` looked up is set is part of what a cached result
    depends on: set, the warning appears (not the result cached while it was unset), and it
    goes when the variable is unset again."""
    _unset(monkeypatch)
    pkg = _mobile(tmp_path)
    runs = []
    for value in (None, "1", "1", None):
        env = {"MOBILE_LASER_ENABLED": value} if value else {}
        p = run_cli("check", ".", "--isolated", "--format", "json", "--explore", "false",
                    cwd=pkg, env=env)
        doc = json.loads(p.stdout)
        runs.append(([m["cached"] for m in doc["models"]],
                     sorted(f["code"] for f in doc["findings"])))
    assert runs == [([False], []), ([False], ["UL901"] * 2), ([True], ["UL901"] * 2),
                    ([False], [])], runs


def test_env_of_an_unset_variable_stays_an_error(tmp_path, monkeypatch):
    """Item 2: `$(env VAR)` unset makes stock xacro fail: still a located UL901 error."""
    monkeypatch.delenv("MOBILE_SERIAL", raising=False)
    pkg = make_package(tmp_path, "p", {"urdf/r.urdf.xacro": f'<robot name="r" {X}>\n'
                                       '  <link name="base_$(env MOBILE_SERIAL)"/>\n</robot>\n'})
    doc, p = _check(pkg)
    (f,) = [f for f in doc["findings"] if f["code"] == "UL901"]
    assert (f["severity"], f["line"], p.returncode) == ("error", 2, 1)
    assert stock_xacro(str(pkg / "urdf/r.urdf.xacro"), {}, {})[0] != 0


HAND = f"""<?xml version="1.0"?>
<robot name="hand" {X}>
  <xacro:arg name="hand_type" default="three_finger"/>
  <xacro:arg name="hand_version" default="2"/>
  <xacro:macro name="check_hand" params="type version">
    <xacro:if value="${{type == 'three_finger' and version != 3}}">
      ${{xacro.error('hand type', type, 'needs version 3, got', version)}}
    </xacro:if>
    <xacro:if value="${{version == 2}}">
      ${{xacro.warning('version 2 is deprecated')}}${{xacro.message('checked', type)}}
    </xacro:if>
  </xacro:macro>
  <link name="palm"/>
  <xacro:check_hand type="$(arg hand_type)" version="$(arg hand_version)"/>
</robot>
"""


def test_xacro_error_is_a_located_error(tmp_path):
    """Item 3: `${xacro.error(...)}` (stock xacro prints it and exits 0) is a located error
    with its message, at the check in the macro with the call; `xacro.warning` a warning;
    `xacro.message` nothing. The run fails on the error; with matching args it passes."""
    pkg = make_package(tmp_path, "hand_description", {"urdf/hand.urdf.xacro": HAND})
    rc, _, err = stock_xacro(str(pkg / "urdf/hand.urdf.xacro"), {}, {})
    assert rc == 0 and "needs version 3" in err
    doc, p = _check(pkg)
    got = sorted((f["code"], f["severity"], f["line"], f["message"]) for f in doc["findings"])
    assert got == [
        ("UL008", "warning", 9, "xacro: version 2 is deprecated"),
        ("UL013", "error", 6, "xacro.error: hand type three_finger needs version 3, got 2")], got
    (e,) = [f for f in doc["findings"] if f["code"] == "UL013"]
    assert e["file"] == "urdf/hand.urdf.xacro" and [c[1] for c in e["chain"]] == [14], e
    assert p.returncode == 1
    text = run_cli("check", ".", "--no-cache", "--isolated", cwd=pkg)
    assert "checked three_finger" not in text.stdout + text.stderr
    (pkg / "urdf/hand.urdf.xacro").write_text(HAND.replace('default="2"', 'default="3"'))
    doc, p = _check(pkg)
    assert doc["findings"] == [] and p.returncode == 0, doc["findings"]


def test_a_placeholder_included_through_a_default_is_no_model(tmp_path, monkeypatch):
    """Item 4: `empty.urdf`, included through an arg's or a property's default so that "no
    extras" is the default, is not linted as a robot (it was UL006 and UL201 errors): by the
    include graph (a default naming a file, through `$(find)` or `$(optenv)`), and, for a
    `<robot>` empty by design (no name, no element), also when nothing names it."""
    pkg = make_package(tmp_path, "base_description", {
        "urdf/base.urdf.xacro": f"""<robot name="base" {X}>
  <xacro:arg name="extras" default="$(find base_description)/urdf/extras/empty.urdf"/>
  <xacro:property name="accessories" value="$(optenv BASE_ACCESSORIES accessories.urdf)"/>
  <link name="base_link"/>
  <xacro:include filename="$(arg extras)"/>
  <xacro:include filename="${{accessories}}"/>
</robot>
""",
        # named (not empty by design): a fragment only because the defaults include it
        "urdf/extras/empty.urdf": f'<?xml version="1.0"?>\n<robot name="extras" {X}>\n</robot>\n',
        "urdf/accessories.urdf": '<?xml version="1.0"?>\n<robot name="accessories">\n</robot>\n',
        "urdf/generated/macros.urdf": EMPTY,   # the expansion of a macro-only file
    })
    monkeypatch.delenv("BASE_ACCESSORIES", raising=False)
    doc, p = _check(pkg)
    assert doc["findings"] == [] and p.returncode == 0, doc["findings"]
    assert [m["entry"] for m in doc["models"]] == ["urdf/base.urdf.xacro"], doc["models"]
    # named explicitly, a file is linted as a model
    p = run_cli("check", "urdf/extras/empty.urdf", "--no-cache", "--isolated", "--format",
                "json", cwd=pkg)
    assert "UL006" in {f["code"] for f in json.loads(p.stdout)["findings"]}


def test_find_in_element_text_is_an_undeclared_dependency(tmp_path):
    """Item 5: `$(find pkg)` in an element's text (a controllers file handed to a plugin)
    names an undeclared dependency: UL012 at that line. A macro file read from another
    package is reported in the linted package too (the `$(find)` of its include, or the
    macro call of a `package://` include), never in the other package's files."""
    repo = tmp_path / "repo"
    make_package(repo, "bot_control", {"config/controllers.yaml": "a: 1\n"})
    make_package(repo, "arm_description", {"urdf/arm.xacro": f"""<robot {X}>
  <xacro:macro name="arm" params="parent">
    <link name="arm"/>
    <joint name="arm_joint" type="fixed"><parent link="${{parent}}"/><child link="arm"/></joint>
  </xacro:macro>
</robot>
"""})
    make_package(repo, "bot_description", {
        "urdf/bot.urdf.xacro": f"""<robot name="bot" {X}>
  <link name="base_link"/>
  <!-- $(find bot_control) in a comment is no use -->
  <gazebo>
    <plugin filename="libgz_ros2_control-system.so" name="gz_ros2_control::GazeboSimROS2ControlPlugin">
      <parameters>$(find bot_control)/config/controllers.yaml</parameters>
    </plugin>
  </gazebo>
</robot>
""",
        "urdf/arm_bot.urdf.xacro": f"""<robot name="arm_bot" {X}>
  <link name="base_link"/>
  <xacro:include filename="package://arm_description/urdf/arm.xacro"/>
  <xacro:arm parent="base_link"/>
</robot>
"""})
    doc, _ = _check(repo)
    got = {(f["message"].split("'")[1], f["file"], f["line"], f["col"])
           for f in doc["findings"] if f["code"] == "UL012"}
    assert got == {("bot_control", "bot_description/urdf/bot.urdf.xacro", 6, 19),
                   ("arm_description", "bot_description/urdf/arm_bot.urdf.xacro", 4, 3)}, \
        doc["findings"]


def test_package_path_hint_for_files_outside_git(tmp_path):
    """Item 9: outside git, `check FILE` and `expand FILE` say which `--package-path` finds a
    sibling package, as `check DIR` does (from the workspace and from inside the package)."""
    ws = tmp_path / "ws"
    make_package(ws, "parts", {"urdf/parts.xacro": f'<robot {X}><xacro:macro name="m"/></robot>\n'})
    make_package(ws, "arm", {"urdf/arm.urdf.xacro": f"""<robot name="arm" {X}>
  <xacro:include filename="$(find parts)/urdf/parts.xacro"/>
  <link name="base"/>
</robot>
"""})
    for cwd, target in ((ws, "arm"), (ws, "arm/urdf/arm.urdf.xacro"),
                        (ws / "arm", "urdf/arm.urdf.xacro"), (ws / "arm" / "urdf", "arm.urdf.xacro")):
        cmds = [("check", target, "--no-cache", "--isolated")]
        cmds += [("expand", target)] if target.endswith(".xacro") else []
        for cmd in cmds:
            p = run_cli(*cmd, cwd=cwd)
            said = p.stdout + p.stderr
            assert p.returncode == 1 and "UL004" in said, (cmd, p.stderr)
            assert "--package-path parts=" in said, (cwd, cmd, said)
