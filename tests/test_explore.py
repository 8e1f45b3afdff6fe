"""Issue 39, branch coverage: the variants that take the xacro branches the default args
leave out are linted, and what only they find is reported once, labelled with the args that
reach it; ``--coverage`` says which branches stay out and why."""
from __future__ import annotations

import json
import os
from pathlib import Path

from conftest import age, make_package, run_cli

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
INERTIAL = ('<inertial><mass value="{m}"/><inertia ixx="1e-3" ixy="0" ixz="0" iyy="2e-3" '
            'iyz="0" izz="3e-3"/></inertial>')
# a defect behind each kind of branch; none is reached at the defaults
ROBOT = f"""<?xml version="1.0"?>
<robot name="r" {X}>
  <xacro:arg name="sim" default="false"/>
  <xacro:arg name="gripper" default="none"/>
  <xacro:arg name="camera" default="none"/>
  <xacro:arg name="hand" default="plain"/>
  <xacro:arg name="size" default="small"/>
  <xacro:property name="limits" value="${{xacro.load_yaml('$(find robot)/config/$(arg size)/limits.yaml')}}"/>
  <link name="base"/>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/>
    <limit effort="1" velocity="${{limits['velocity']}}" lower="-1" upper="1"/>
  </joint>
  <link name="arm"/>
  <xacro:if value="$(arg sim)">
    <link name="sim_link">{INERTIAL.format(m=-1)}</link>
    <joint name="sim_j" type="fixed"><parent link="base"/><child link="sim_link"/></joint>
    <xacro:if value="${{'$(arg gripper)' == 'robotiq'}}">
      <joint name="nested_j" type="fixed"><parent link="base"/><child link="no_nested"/></joint>
    </xacro:if>
  </xacro:if>
  <xacro:if value="${{'$(arg gripper)' == 'robotiq'}}">
    <joint name="grip_j" type="fixed"><parent link="base"/><child link="no_grip"/></joint>
  </xacro:if>
  <xacro:if value="${{'$(arg camera)' in ['d435', 'd455']}}">
    <joint name="cam_j" type="fixed"><parent link="base"/><child link="no_cam"/></joint>
  </xacro:if>
  <xacro:include filename="$(find robot)/urdf/hands/$(arg hand).xacro"/>
  <xacro:if value="false">
    <link name="never"/>
  </xacro:if>
</robot>
"""
FILES = {
    "urdf/robot.urdf.xacro": ROBOT,
    "urdf/hands/plain.xacro": f'<?xml version="1.0"?>\n<robot {X}/>\n',
    "urdf/hands/fancy.xacro": f"""<?xml version="1.0"?>
<robot {X}>
  <joint name="hand_j" type="fixed"><parent link="base"/><child link="no_hand"/></joint>
</robot>
""",
    "config/small/limits.yaml": "velocity: 1.0\n",
    "config/big/limits.yaml": "velocity: -2.0\n",
}
FILE = "urdf/robot.urdf.xacro"
# (line, code) -> the label of the args that reach it
EXPECTED = {
    (13, "UL304"): "size:=big",                 # a YAML folder chosen by an arg
    (17, "UL602"): "sim:=true",                 # a boolean arg
    (20, "UL103"): "gripper:=robotiq sim:=true",   # nested conditions
    (24, "UL103"): "gripper:=robotiq",          # a compared literal
    (27, "UL103"): "camera:=d435",              # an `in` list
}


def _check(pkg: Path, *args: str, coverage: bool = True):
    more = ("--coverage",) if coverage else ()
    p = run_cli("check", ".", "--no-cache", "--format", "json", *more, *args, cwd=pkg)
    assert p.returncode in (0, 1), p.stderr
    return json.loads(p.stdout)


def test_a_defect_behind_each_kind_of_branch_is_found_and_labelled(tmp_path):
    pkg = make_package(tmp_path, "robot", FILES)
    doc = _check(pkg)
    got = {(f["line"], f["code"]): f["message"] for f in doc["findings"]
           if f["file"].endswith(FILE)}
    for (line, code), label in EXPECTED.items():
        assert (line, code) in got, (line, code, sorted(got))
        assert got[(line, code)].endswith(f"(only with {label})"), got[(line, code)]
    hand = [f for f in doc["findings"] if f["file"].endswith("hands/fancy.xacro")]
    assert [f["code"] for f in hand] == ["UL103"]          # an include chosen by an arg
    assert hand[0]["message"].endswith("(only with hand:=fancy)")
    # once each: a finding of several variants is reported with one label
    assert len([f for f in doc["findings"] if f["line"] == 24]) == 1
    # the branch no arg reaches: an information finding, and the coverage says why
    assert got[(30, "UL014")] and "(only with" not in got[(30, "UL014")]
    [cov] = doc["coverage"]
    assert cov["taken_at_defaults"] < cov["taken"] == cov["branches"] - 1
    assert [(r["line"], r["why"]) for r in cov["not_taken"]] == [(30, "unreachable")]


def test_a_finding_at_the_defaults_is_not_repeated_per_variant(tmp_path):
    files = dict(FILES)
    files[FILE] = ROBOT.replace('<link name="arm"/>',
                                f'<link name="arm">{INERTIAL.format(m=0)}</link>')
    pkg = make_package(tmp_path, "robot", files)
    doc = _check(pkg, coverage=False)
    at = [f for f in doc["findings"] if f["file"].endswith(FILE) and f["line"] == 15]
    assert at and all("(only with" not in f["message"] for f in at), at
    assert len({f["code"] for f in at}) == len(at)


def test_opt_out_and_per_arg_control(tmp_path):
    pkg = make_package(tmp_path, "robot", FILES)
    off = _check(pkg, "--explore", "false")
    assert not [f for f in off["findings"] if "(only with" in f["message"]]
    # an arg that must never change, and an arg whose values are listed
    doc = _check(pkg, "--explore-arg", "sim=", "--explore-arg", "camera=d455")
    labels = {f["message"].rpartition("(only with ")[2] for f in doc["findings"]
              if "(only with" in f["message"]}
    assert not any("sim:=" in x for x in labels), labels
    assert "camera:=d455)" in labels and "camera:=d435)" not in labels
    [cov] = doc["coverage"]
    assert {r["line"]: r["why"] for r in cov["not_taken"]}[16] == "its args are fixed"
    (pkg / "pyproject.toml").write_text('[tool.urdf-lint]\nexplore-exclude = ["urdf/*"]\n')
    assert not [f for f in _check(pkg)["findings"] if "(only with" in f["message"]]


def test_the_budget_cuts_exploration_short_and_says_so(tmp_path):
    pkg = make_package(tmp_path, "robot", FILES)
    p = run_cli("check", ".", "--no-cache", "--explore-budget", "0.125", "--coverage",
                "--statistics", cwd=pkg)
    assert "explore budget cut exploration short" in p.stderr, p.stderr
    assert "never taken: budget" in p.stdout, p.stdout
    assert "branches " in p.stdout and "robot.urdf.xacro" in p.stdout


def test_the_branches_read_from_the_source(tmp_path):
    """Static: the conditions, the args they read (also through a property or a macro
    parameter), the literals they compare with and the files an arg-built path names."""
    from urdf_lint.discovery import branches
    from urdf_lint.discovery.packages import PackageResolver
    pkg = make_package(tmp_path, "robot", FILES)
    (pkg / "urdf/macro.xacro").write_text(f"""<?xml version="1.0"?>
<robot {X}>
  <xacro:arg name="use_gazebo" default="false"/>
  <xacro:property name="gz" value="$(arg use_gazebo)"/>
  <xacro:macro name="m" params="hand">
    <xacro:if value="${{hand}}"><link name="h"/></xacro:if>
  </xacro:macro>
  <xacro:m hand="$(arg with_hand)"/>
  <xacro:unless value="${{gz}}"><link name="g"/></xacro:unless>
</robot>
""")
    resolver = PackageResolver.build([str(tmp_path)])
    a = branches.analyse([str(pkg / FILE), str(pkg / "urdf/macro.xacro")], resolver)
    conds = {c.line: c for c in a.conds}
    assert conds[19].parent and conds[19].parent[1] == 16
    assert conds[26].compared == {"camera": ["d435", "d455"]}
    assert conds[6].bare == "with_hand" and conds[6].in_macro
    assert conds[9].args == ("use_gazebo",) and conds[9].kind == "unless"
    assert conds[30].constant is False
    values = a.values()
    assert values["sim"] == ["true"] and values["gripper"] == ["robotiq"]
    assert values["hand"] == ["fancy"] and values["size"] == ["big"]
    assert branches.guesses(conds[9], a.defaults, values) == [{"use_gazebo": "false"}] or \
        a.defaults["use_gazebo"] == "false"


def test_the_yaml_files_a_load_yaml_names_are_read_from_the_source(tmp_path):
    """Static: the YAML a ``load_yaml`` reads, through a property holding ``$(find pkg)/...``
    (defined in another file), a ``${...}`` join of literals and properties, a relative path
    (from the call's file and from the property's), ``package://``; an arg or a macro
    parameter leaves the path out, and nothing is read of a call that cannot be told."""
    from urdf_lint.discovery import branches
    from urdf_lint.discovery.packages import PackageResolver
    pkg = make_package(tmp_path, "robot", {
        "urdf/paths.xacro": f"""<?xml version="1.0"?>
<robot {X}>
  <xacro:property name="cfg" value="$(find robot)/config"/>
  <xacro:property name="inertial_config" value="${{cfg + '/inertial.yaml'}}"/>
  <xacro:property name="near" value="limits/near.yaml"/>
</robot>
""",
        "urdf/robot.urdf.xacro": f"""<?xml version="1.0"?>
<robot {X}>
  <xacro:arg name="size" default="small"/>
  <xacro:macro name="m" params="file">
    <xacro:property name="i" value="${{xacro.load_yaml(inertial_config)}}"/>
    <link name="a" type="${{xacro.load_yaml(near)['t']}}"/>
    <xacro:property name="p" value="${{xacro.load_yaml('package://robot/config/p.yaml')}}"/>
    <xacro:property name="q" value="${{xacro.load_yaml(file)}}"/>
    <xacro:property name="s" value="${{xacro.load_yaml('$(arg size).yaml')}}"/>
  </xacro:macro>
  <origin xyz="${{xacro.load_yaml(cfg + '/origin.yaml')['xyz']}}"/>
</robot>
"""})
    resolver = PackageResolver.build([str(tmp_path)])
    files = [str(pkg / "urdf/robot.urdf.xacro"), str(pkg / "urdf/paths.xacro")]
    got = branches.yaml_reads([branches.yaml_sources(f, resolver) for f in files], resolver)
    root = os.path.realpath(pkg)
    assert got == {f"{root}/config/inertial.yaml", f"{root}/config/origin.yaml",
                   f"{root}/config/p.yaml", f"{root}/urdf/limits/near.yaml"}, got


def test_the_budget_is_shared_round_robin_and_variant_findings_are_labelled_once():
    """In process: every model's first variant before any model's second; a finding of two
    variants is added once, with the smaller variant's args; one at the defaults never."""
    from urdf_lint.core.findings import Problem
    from urdf_lint.core.jobs import ModelReport
    from urdf_lint.discovery.branches import Analysis
    from urdf_lint.run import explore
    plans = [explore.ModelPlan(f"/r/{n}.xacro", [ModelReport(f"/r/{n}.xacro", {})], Analysis(),
                               variants=[{"a": "1"}, {"a": "1", "b": "x"}, {"c": "y"}])
             for n in ("m1", "m2")]
    jobs = explore.select(plans, 0.25, 8)            # 2 variants for the run
    assert [(j.entry, j.args) for j in jobs] == [("/r/m1.xacro", {"a": "1"}),
                                                 ("/r/m2.xacro", {"a": "1"})]
    assert [p.kept for p in plans] == [1, 1]
    jobs = explore.select(plans, 1.0, 2)             # at least MIN_MODELS: all 6
    assert len(jobs) == 6 and [p.kept for p in plans] == [3, 3]
    at_default = Problem.at("UL601", "no inertial", ("/r/m1.xacro", 3, 1))
    behind = Problem.at("UL103", "child link 'x' is not defined", ("/r/m1.xacro", 9, 5))
    plans[0].base[0].problems = [at_default]
    reports = [ModelReport("/r/m1.xacro", {"a": "1", "b": "x"}, problems=[at_default, behind]),
               ModelReport("/r/m1.xacro", {"a": "1"}, problems=[at_default, behind])]
    cov = explore.merge(plans[:1], reports)
    got = [p.message for p in plans[0].base[0].problems]
    assert got == ["no inertial", "child link 'x' is not defined (only with a:=1)"]
    assert list(cov) == [plans[0].label]
    assert cov[plans[0].label]["variants"] == [{"a": "1"}, {"a": "1", "b": "x"}]


def test_diff_shows_a_change_inside_a_branch_the_defaults_do_not_take(tmp_path):
    """Both revisions explore alike: a defect a change brings into the `sim` branch is
    introduced, labelled; the findings both revisions share are not."""
    import subprocess

    def git(*args):
        subprocess.run(["git", *args], cwd=tmp_path, check=True, capture_output=True)
    pkg = make_package(tmp_path, "robot", FILES)
    git("init", "-q")
    git("add", "-A")
    git("-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "base")
    f = pkg / FILE
    f.write_text(f.read_text().replace('<mass value="-1"/>', '<mass value="-3"/>'))
    p = run_cli("diff", "HEAD", "--format", "json", "--no-cache", cwd=tmp_path)
    assert p.returncode in (0, 1), p.stderr
    [m] = json.loads(p.stdout)["models"]
    new = [x["message"] for x in m["findings_introduced"]]
    assert len(new) == 1 and "mass -3" in new[0] and new[0].endswith("(only with sim:=true)"), m
    [gone] = [x["message"] for x in m["findings_fixed"]]
    assert "mass -1" in gone and gone.endswith("(only with sim:=true)"), m


def test_explore_keys_per_models_entry(tmp_path):
    """``explore`` and ``explore-args`` in a ``[[models]]`` entry apply to that model only,
    over the config's ``explore-args`` arg by arg."""
    files = dict(FILES)
    files["urdf/other.urdf.xacro"] = ROBOT.replace('name="r"', 'name="o"')
    files["pyproject.toml"] = """[tool.urdf-lint]
explore-args = {gripper = []}

[[tool.urdf-lint.models]]
path = "urdf/robot.urdf.xacro"
explore-args = {sim = [], camera = ["d455"]}

[[tool.urdf-lint.models]]
path = "urdf/other.urdf.xacro"
explore = false
"""
    pkg = make_package(tmp_path, "robot", files)
    doc = _check(pkg)
    labels = {f["message"].rpartition("(only with ")[2] for f in doc["findings"]
              if "(only with" in f["message"] and f["file"].endswith(FILE)}
    assert "camera:=d455)" in labels and "size:=big)" in labels, labels
    assert not any(x.startswith(("sim:=", "gripper:=")) or "camera:=d435" in x
                   for x in labels), labels
    assert not [f for f in doc["findings"] if f["file"].endswith("other.urdf.xacro")
                and "(only with" in f["message"]]
    [cov] = doc["coverage"]    # the other model is not explored
    assert cov["entry"].endswith(FILE)
    whys = {r["line"]: r["why"] for r in cov["not_taken"]}
    assert whys[16] == whys[23] == "its args are fixed", whys
    # the command line wins over the entry for the args it names
    doc = _check(pkg, "--explore-arg", "camera=d435")
    labels = {f["message"].rpartition("(only with ")[2] for f in doc["findings"]
              if "(only with" in f["message"] and f["file"].endswith(FILE)}
    assert "camera:=d435)" in labels and "camera:=d455)" not in labels, labels
    assert not any(x.startswith("sim:=") for x in labels), labels


def test_a_bad_explore_key_in_a_models_entry_is_a_config_error(tmp_path):
    from urdf_lint.config.schema import ConfigError, load_config
    (tmp_path / "r.xacro").write_text("<robot/>")
    for bad, said in (('explore = "no"', "(expected 'explore' to be true or false)"),
                      ('explore-args = {sim = "true"}', "(expected 'explore-args' to be a list"),
                      ('explor = false', "(did you mean 'explore'?)")):
        cfg = tmp_path / "urdf-lint.toml"
        cfg.write_text(f'[[models]]\npath = "r.xacro"\n{bad}\n')
        try:
            load_config(cfg)
        except ConfigError as e:
            assert said in str(e), str(e)
        else:
            raise AssertionError(f"accepted: {bad}")


def test_statistics_give_the_branches_taken_per_model_in_text_and_json(tmp_path):
    pkg = make_package(tmp_path, "robot", FILES)
    text = run_cli("check", ".", "--no-cache", "--statistics", cwd=pkg).stdout
    doc = _check(pkg, "--statistics", coverage=False)
    (row,) = [r for r in doc if "model" in r]
    [cov] = _check(pkg)["coverage"]
    assert row == {"model": cov["model"], "entry": "urdf/robot.urdf.xacro",
                   "branches": cov["branches"], "taken": cov["taken"],
                   "taken_at_defaults": cov["taken_at_defaults"],
                   "variants": len(cov["variants"]), "cut_by_budget": 0}
    assert row["taken_at_defaults"] < row["taken"] == row["branches"] - 1
    assert (f"branches {row['taken']}/{row['branches']} taken ({row['taken_at_defaults']} at "
            f"the defaults, {row['variants']} variant(s)): {cov['model']}") in text, text
    # the counts per rule stay as they were, first
    assert all("code" in r and "count" in r for r in doc[:-1])
    off = _check(pkg, "--statistics", "--explore", "false", coverage=False)
    assert not [r for r in off if "model" in r]


def _git(*args, cwd):
    import subprocess
    subprocess.run(["git", "-c", "user.email=t@t", "-c", "user.name=t", *args], cwd=cwd,
                   check=True, capture_output=True)


def test_a_change_only_an_explored_variant_reads_relints_its_model(tmp_path):
    """``--changed-since`` and the hook: the only changed file is the hand ``hand:=fancy``
    includes, or a file included inside a branch the defaults leave out; its model is linted
    (explored), not reported as a file no model uses."""
    files = dict(FILES)
    files[FILE] = ROBOT.replace('  <xacro:if value="false">', '''  <xacro:if value="$(arg sim)">
    <xacro:include filename="gazebo.xacro"/>
  </xacro:if>
  <xacro:if value="false">''')
    files["urdf/gazebo.xacro"] = f'<?xml version="1.0"?>\n<robot {X}/>\n'
    pkg = make_package(tmp_path, "robot", files)
    _git("init", "-q", cwd=pkg)
    _git("add", "-A", cwd=pkg)
    _git("commit", "-qm", "init", cwd=pkg)
    fancy = pkg / "urdf/hands/fancy.xacro"
    fancy.write_text(fancy.read_text().replace("hand_j", "hand_joint"))
    doc = _check(pkg, "--changed-since", "HEAD", coverage=False)
    assert [m["entry"] for m in doc["models"]] == [FILE]
    hand = [f for f in doc["findings"] if f["file"].endswith("hands/fancy.xacro")]
    assert [(f["code"], f["message"].endswith("(only with hand:=fancy)")) for f in hand] == \
        [("UL103", True)], hand
    p = run_cli("hook", "--", "urdf/hands/fancy.xacro", cwd=pkg)
    assert p.returncode == 1 and "hand_joint" in p.stdout, (p.stdout, p.stderr)
    assert "is not used by any model" not in p.stderr, p.stderr
    _git("checkout", "-q", "--", ".", cwd=pkg)
    (pkg / "urdf/gazebo.xacro").write_text(
        f'<?xml version="1.0"?>\n<robot {X}>\n  <link name="gz"/>\n</robot>\n')
    doc = _check(pkg, "--changed-since", "HEAD", coverage=False)
    assert [m["entry"] for m in doc["models"]] == [FILE]
    # the model's branch findings come with it; with exploration off it is not linted
    off = _check(pkg, "--changed-since", "HEAD", "--explore", "false", coverage=False)
    assert off["models"] == []


# franka_description's pattern: the inertials come from a YAML file whose path a property holds
# (`$(find pkg)/config/inertial.yaml`), loaded lazily by a property only a macro reads, and that
# macro is called only under `gazebo:=true`: no default pass reads the YAML
LAZY_YAML = {
    "urdf/utils.xacro": f"""<?xml version="1.0"?>
<robot {X}>
  <xacro:property name="inertial_config" value="$(find arm)/config/inertial.yaml"/>
  <xacro:property name="inertial" value="${{xacro.load_yaml(inertial_config)}}"/>
  <xacro:macro name="inertial_props" params="name inertial:=^">
    <xacro:property name="i" value="${{inertial[name]}}" lazy_eval="false"/>
    <inertial>
      <mass value="${{i.mass}}"/>
      <inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/>
    </inertial>
  </xacro:macro>
</robot>
""",
    "urdf/arm.xacro": f"""<?xml version="1.0"?>
<robot {X}>
  <xacro:macro name="arm" params="prefix gazebo:=false">
    <xacro:include filename="$(find arm)/urdf/utils.xacro"/>
    <link name="${{prefix}}base"/>
    <link name="${{prefix}}link1">
      <xacro:if value="${{gazebo}}">
        <xacro:inertial_props name="link1"/>
      </xacro:if>
    </link>
    <joint name="${{prefix}}joint1" type="fixed">
      <parent link="${{prefix}}base"/><child link="${{prefix}}link1"/>
    </joint>
  </xacro:macro>
</robot>
""",
    "config/inertial.yaml": "link0:\n  mass: 1.0\nlink1:\n  mass: 2.0\n",
}
for _name in ("a", "b"):   # two models: a change re-lints each model that may read it
    LAZY_YAML[f"urdf/{_name}.urdf.xacro"] = f"""<?xml version="1.0"?>
<robot name="{_name}" {X}>
  <xacro:arg name="gazebo" default="false"/>
  <xacro:include filename="$(find arm)/urdf/arm.xacro"/>
  <xacro:arm prefix="{_name}_" gazebo="$(arg gazebo)"/>
</robot>
"""
LAZY_MASS_LINE = 4     # of config/inertial.yaml: link1's mass


def lazy_yaml_repo(root: Path) -> Path:
    """The package of :data:`LAZY_YAML`, committed in a git repository of its own."""
    pkg = make_package(root, "arm", LAZY_YAML)
    _git("init", "-q", cwd=pkg)
    _git("add", "-A", cwd=pkg)
    _git("commit", "-qm", "init", cwd=pkg)
    return pkg


def test_a_yaml_only_an_explored_variant_loads_through_a_property_relints(tmp_path):
    """franka_description: link1's mass made negative in a YAML file that only ``gazebo:=true``
    loads, through ``load_yaml(inertial_config)`` where the property holds
    ``$(find arm)/config/inertial.yaml``. The hook and ``--changed-since`` re-lint every model
    that may read it (both, not only the first) and report the error at its YAML line; they
    said "0 model(s) affected" and passed."""
    pkg = lazy_yaml_repo(tmp_path)
    yaml = pkg / "config/inertial.yaml"
    yaml.write_text(yaml.read_text().replace("mass: 2.0", "mass: -2.0"))
    p = run_cli("hook", "--", "config/inertial.yaml", cwd=pkg)
    assert p.returncode == 1, (p.stdout, p.stderr)
    assert "2 model(s) affected" in p.stderr, p.stderr
    assert "UL602 link 'a_link1': mass -2 must not be negative" in p.stdout, p.stdout
    assert f"value from config/inertial.yaml:{LAZY_MASS_LINE}" in p.stdout, p.stdout
    doc = _check(pkg, "--changed-since", "HEAD", coverage=False)
    assert sorted(m["entry"] for m in doc["models"]) == ["urdf/a.urdf.xacro",
                                                        "urdf/b.urdf.xacro"], doc["models"]
    [f] = [f for f in doc["findings"] if f["code"] == "UL602"]
    assert f["value_from"][:2] == ["config/inertial.yaml", LAZY_MASS_LINE], f
    assert f["message"].endswith("(only with gazebo:=true)"), f
    # read by the default pass (gazebo on by default): its recorded inputs name the YAML,
    # with exploration off too
    for name in ("a", "b"):
        xacro = pkg / f"urdf/{name}.urdf.xacro"
        xacro.write_text(xacro.read_text().replace('default="false"', 'default="true"'))
    _git("commit", "-qam", "gazebo by default", cwd=pkg)
    yaml.write_text(yaml.read_text().replace("mass: -2.0", "mass: -3.0"))
    off = _check(pkg, "--changed-since", "HEAD", "--explore", "false", coverage=False)
    assert sorted(m["entry"] for m in off["models"]) == ["urdf/a.urdf.xacro",
                                                        "urdf/b.urdf.xacro"], off["models"]


def test_the_default_pass_and_the_exploration_pass_share_their_workers(tmp_path, monkeypatch):
    """Issue 34: exploration lints its variants on the workers of the default pass (forked,
    preloaded and sandboxed once per run), and finds what it found with a pool of its own."""
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.run.pipeline import RunRequest, run_check
    from urdf_lint.runner import pool
    pkg = make_package(tmp_path, "robot", FILES)
    forked: list[int] = []
    real = pool.Worker.__init__

    def counting(self, *a, **k):
        forked.append(1)
        real(self, *a, **k)
    monkeypatch.setattr(pool.Worker, "__init__", counting)
    cfg = load_config(None)
    resolver = build_resolver([str(pkg)], cfg, {})
    result = run_check(RunRequest([str(pkg)], cfg, resolver, jobs_n=1))
    assert result.coverage, "nothing was explored"
    assert any("only with" in f.message for f in result.findings), result.findings
    assert len(forked) == 1, f"{len(forked)} workers forked for one run at -j1"


def test_a_run_whose_variants_read_a_file_of_their_own_is_remembered(tmp_path):
    """The run memo keeps a whole unchanged run when it knows what every input was when read.
    A file only an explored variant reads (franka's inertial YAML under ``gazebo:=true``) was
    added to its model's inputs without that record, so no run of such a robot was ever
    remembered: every warm ``check`` linted again (0.26 s instead of 0.16 s on the corpus)."""
    pkg = lazy_yaml_repo(tmp_path)
    yaml = pkg / "config/inertial.yaml"
    yaml.write_text(yaml.read_text().replace("mass: 2.0", "mass: -2.0"))
    assert run_cli("check", ".", cwd=pkg).returncode == 1      # (makes the cache folder)
    age(pkg)     # (the memo trusts no input changed in its last seconds)
    runs = [run_cli("check", ".", "--format", "json", "-v", cwd=pkg) for _ in range(2)]
    assert all(p.returncode == 1 for p in runs), [p.stderr for p in runs]
    said = ["nothing changed since the last identical run" in p.stderr for p in runs]
    assert said == [False, True], [p.stderr for p in runs]
    docs = [json.loads(p.stdout) for p in runs]
    assert docs[1]["findings"] == docs[0]["findings"]
    assert any(f["message"].endswith("(only with gazebo:=true)") for f in docs[1]["findings"])


def test_every_models_first_variant_is_linted_during_the_default_pass(tmp_path, monkeypatch):
    """Issue 34: a model's first variant is planned as soon as its default report arrives and
    linted on the default pass's workers, while the other models are still linted; the end of
    the pass lints only the rest. No job is linted twice, and the run finds what exploring
    after the pass finds (in process: no workers, nothing early)."""
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.core.jobs import job_key
    from urdf_lint.run.pipeline import RunRequest, run_check
    from urdf_lint.run.worker import RunPool
    files = dict(FILES)
    files["urdf/other.urdf.xacro"] = ROBOT.replace('name="r"', 'name="o"', 1)
    pkg = make_package(tmp_path, "robot", files)
    passes: list[list] = []
    added: list = []
    run, add = RunPool.run, RunPool.add

    def runs(self, jobs):
        passes.append(list(jobs))
        return run(self, jobs)

    def adds(self, jobs):
        added.extend(jobs)
        return add(self, jobs)
    monkeypatch.setattr(RunPool, "run", runs)
    monkeypatch.setattr(RunPool, "add", adds)
    cfg = load_config(None)

    def check(**kw):
        return run_check(RunRequest([str(pkg)], cfg, build_resolver([str(pkg)], cfg, {}), **kw))
    result = check(jobs_n=2)
    assert sorted(j.entry.rsplit("/", 1)[1] for j in added) == ["other.urdf.xacro",
                                                                "robot.urdf.xacro"]
    assert all(j.args for j in added)
    later = passes[1] if len(passes) > 1 else []
    linted = [job_key(j) for j in added + later]
    assert later and len(linted) == len(set(linted))        # each variant once
    alone = check(in_process=True)

    def shown(r):
        return sorted((f.file, f.line, f.code, f.message) for f in r.findings)
    assert shown(result) == shown(alone)
    assert any("(only with" in m for *_, m in shown(result))
    assert result.coverage == alone.coverage


def test_first_variants_wait_for_the_next_pass_when_the_default_pass_has_one_worker(
        monkeypatch):
    """A default pass the work gave one worker (on a machine with more cores) does not take
    the early first variants: the pass after it may start more workers for them."""
    import os
    from urdf_lint.core.jobs import LintJob
    from urdf_lint.run.worker import RunPool

    class Pool:
        def __init__(self, n):
            self.workers, self.added = [object()] * n, []

        def add(self, jobs):
            self.added += jobs
    monkeypatch.setattr(os, "cpu_count", lambda: 2)
    job = [LintJob("/r.urdf.xacro", {"sim": "true"})]
    for jobs_n, workers, taken in ((None, 1, False), (None, 2, True), (1, 1, True),
                                   (2, 1, False)):
        runs = RunPool(None, jobs_n)    # type: ignore[arg-type]
        runs.pool = Pool(workers)       # type: ignore[assignment]
        runs.add(job)
        assert bool(runs.pool.added) is taken, (jobs_n, workers)
