"""The launch model, pure: XML in, LaunchConfig out (typing, scoping, substitution, errors)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from kame.launch import plan
from kame.launch.errors import LaunchError, PackageNotFound
from kame.launch.loader import LaunchLoader, LoaderHost
from kame.launch.model import LaunchConfig
from kame.launch.substitution import Substituter, collect
from kame.launch.values import convert_value

PACKAGES = {"demo": "/pkgs/demo"}


def _find(name: str) -> str:
    if name not in PACKAGES:
        raise PackageNotFound(name)
    return PACKAGES[name]


HOST = LoaderHost({"HOME": "/home/u", "X": "x-value"}, _find, lambda argv: (0, " ".join(argv) + "\n"),
                  lambda name: f"{name}_anon")


def load(tmp_path: Path, xml: str, argv: tuple[str, ...] = (), **files: str) -> LaunchConfig:
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    main = tmp_path / "main.launch"
    main.write_text(xml)
    config = LaunchConfig()
    LaunchLoader(config, HOST).load(str(main), argv)
    return config


def params(config: LaunchConfig) -> dict[str, Any]:
    return {k: p.value for k, p in config.params.items()}


@pytest.mark.parametrize(("text", "kind", "value"), [
    ("1.5", "auto", 1.5), ("010", "auto", 10), (" 7 ", "auto", 7), ("1_000", "auto", "1_000"),
    ("True", "auto", True), ("false", "auto", False), ("0x10", "auto", "0x10"), ("1e3", "auto", "1e3"),
    ("yes", "auto", "yes"), ("nan", "auto", "nan"), ("[1, 2]", "auto", "[1, 2]"), ("1.2.3", "auto", "1.2.3"),
    ("5", "str", "5"), ("5", "double", 5.0), ("1", "bool", True), ("FALSE", "boolean", False),
    ("{a: 1}", "yaml", {"a": 1}), ("[1, x]", "yaml", [1, "x"]),
])
def test_param_typing(text: str, kind: str, value: Any) -> None:
    got = convert_value(text, kind)
    assert got == value and type(got) is type(value)


@pytest.mark.parametrize(("text", "message"), [
    ("yes", "yes is not a 'bool' type"), ("maybe", "maybe is not a 'bool' type"),
])
def test_bool_refusals(text: str, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        convert_value(text, "bool")


SUBST = Substituter({"X": "x-value"}, _find, lambda name: f"{name}_anon")


@pytest.mark.parametrize(("text", "args", "expected"), [
    ("$(find demo)/launch/a.launch", {}, "/pkgs/demo/launch/a.launch"),
    ("$(env X)", {}, "x-value"),
    ("$(optenv NOPE)", {}, ""),
    ("$(optenv NOPE a default)", {}, "a default"),
    ("$(optenv X dflt)", {}, "x-value"),
    ("$(anon n) $(anon n)", {}, "n_anon n_anon"),
    ("$(arg a)-$(arg b)", {"a": "1", "b": "2"}, "1-2"),
    ("$(find demo) $(arg p)", {"p": "demo"}, "/pkgs/demo demo"),
    ("$(dirname)/x", {}, "/launch/dir/x"),
    ("$(eval arg('rate') * 2)", {"rate": "7"}, "14"),
    ("$(eval rate * 2)", {"rate": "7"}, "14"),
    ("$(eval 2 ** int(arg('n')))", {"n": "3"}, "8"),
    ("$(eval optenv('NOPE', 'a') == 'a')", {}, "True"),
    ("$(eval flag and true)", {"flag": "true"}, "True"),
    ("$(eval pi > 3)", {}, "True"),
    ("plain", {}, "plain"),
])
def test_substitution(text: str, args: dict[str, str], expected: str) -> None:
    assert SUBST.resolve(text, args, "/launch/dir/main.launch") == expected


@pytest.mark.parametrize(("text", "message"), [
    ("$(env NOPE)", "environment variable 'NOPE' is not set"),
    ("$(foo bar)", "Unknown substitution command [foo bar]. Valid commands are ['find', 'env', 'optenv', "
                   "'dirname', 'anon', 'arg']"),
    ("$(find $(arg p))", "Dollar signs '$' cannot be inside of substitution args"),
    ("$(arg (x)", "Invalid left parenthesis '(' in substitution args [$(arg (x)]"),
    ("$(eval __import__('os'))", "$(eval ...) may not contain double underscore expressions"),
    ("$(eval open('/etc/passwd'))", "NameError"),
])
def test_substitution_errors(text: str, message: str) -> None:
    with pytest.raises(LaunchError) as info:
        SUBST.resolve(text, {}, "/f.launch")
    assert message in str(info.value)


def test_collect() -> None:
    assert collect("a $(find x)/b $(arg y) $x") == ["find x", "arg y"]


def test_scoping_params_remaps_env(tmp_path: Path) -> None:
    config = load(tmp_path, """<launch>
      <arg name="use_g" default="true"/>
      <param name="top" value="1"/>
      <env name="E" value="outer"/>
      <remap from="a" to="b"/>
      <group ns="g1" if="$(arg use_g)">
        <param name="p" value="7"/>
        <param name="~priv" value="9"/>
        <remap from="chatter" to="/chat2"/>
        <node name="talker" pkg="demo" type="talker.py" args="--x 'a b'">
          <param name="rate" value="3"/>
          <remap from="a" to="c"/>
          <env name="E" value="inner"/>
          <rosparam>{k: v, nested: {d: 1.5}}</rosparam>
        </node>
      </group>
      <group ns="skipped" unless="$(arg use_g)"><node name="n" pkg="demo" type="x"/></group>
      <node name="after" pkg="demo" type="x"/>
      <remap from="late" to="ignored"/>
    </launch>""")
    assert params(config) == {"/top": 1, "/g1/p": 7, "/g1/talker/priv": 9, "/g1/talker/rate": 3,
                              "/g1/talker/k": "v", "/g1/talker/nested/d": 1.5}
    talker, after = config.nodes
    assert (talker.namespace, talker.resolved_name) == ("/g1/", "/g1/talker")
    assert talker.remap_args == [("chatter", "/chat2"), ("a", "c")]
    assert talker.env_args == [("E", "outer"), ("E", "inner")]
    assert after.remap_args == [("a", "b")] and after.resolved_name == "/after"
    assert plan.node_command(talker, ["/bin/talker"]) == [
        "/bin/talker", "--x", "a b", "chatter:=/chat2", "a:=c", "__name:=talker"]
    env = plan.node_env(talker, {"ROS_NAMESPACE": "/old", "PATH": "/bin"}, "http://m:1/")
    assert env == {"PATH": "/bin", "ROS_MASTER_URI": "http://m:1/", "ROS_NAMESPACE": "/g1", "E": "inner"}
    assert "ROS_NAMESPACE" not in plan.node_env(after, {"ROS_NAMESPACE": "/old"}, "http://m:1/")


def test_include_args_and_rosparam(tmp_path: Path) -> None:
    (tmp_path / "p.yaml").write_text("gain: 2\nlist: [1, 2]\n/abs: here\nangle: !degrees 180\n")
    config = load(tmp_path, f"""<launch>
      <arg name="robot" default="r1"/>
      <include file="{tmp_path}/inc.launch" ns="$(arg robot)">
        <arg name="q" value="$(arg robot)_q"/>
      </include>
      <rosparam command="load" file="{tmp_path}/p.yaml" ns="cfg"/>
      <rosparam param="scalar">42</rosparam>
      <rosparam subst_value="true">s: $(arg robot)</rosparam>
      <rosparam>raw: $(arg robot)</rosparam>
    </launch>""", ("robot:=r2",), **{"inc.launch": """<launch>
      <arg name="q"/><arg name="opt" default="o"/>
      <param name="q" value="$(arg q)"/><param name="opt" value="$(arg opt)"/>
      <node name="n" pkg="demo" type="x" clear_params="true"/>
    </launch>"""})
    p = params(config)
    assert p["/r2/q"] == "r2_q" and p["/r2/opt"] == "o"
    assert p["/cfg/gain"] == 2 and p["/cfg/list"] == [1, 2] and p["/abs"] == "here"
    assert p["/cfg/angle"] == pytest.approx(3.14159265)
    assert p["/scalar"] == 42 and p["/s"] == "r2" and p["/raw"] == "$(arg robot)"
    assert config.clear_params == ["/r2/n/"]
    assert [Path(f).name for f in config.files] == ["main.launch", "inc.launch"]


def test_pass_all_args(tmp_path: Path) -> None:
    config = load(tmp_path, f"""<launch><arg name="a" default="1"/><arg name="b" default="2"/>
      <include file="{tmp_path}/inc.launch" pass_all_args="true"><arg name="b" value="3"/></include>
    </launch>""", **{"inc.launch": '<launch><arg name="a"/><arg name="b"/>'
                                   '<param name="x" value="$(arg a)$(arg b)"/></launch>'})
    assert params(config) == {"/x": 13}


def test_unknown_tags_and_attributes_warn(tmp_path: Path) -> None:
    config = load(tmp_path, '<launch><node name="n" pkg="demo" type="x" bogus="1"/><frob/></launch>')
    main = tmp_path / "main.launch"
    assert config.errors == [f"[{main}] unknown <node> attribute 'bogus'", "unrecognized tag frob"]


@pytest.mark.parametrize(("xml", "message", "line"), [
    ('<launch>\n<node pkg="demo" type="x"/></launch>', "<node> tag is missing required attribute: 'name'", 2),
    ('<launch>\n\n<arg name="a" value="1" default="2"/></launch>',
     "<arg> tag must have one and only one of value/default.", 3),
    ('<launch><arg name="a" default="1"/>\n<arg name="a" default="1"/></launch>',
     "arg 'a' has already been declared", 2),
    ('<launch>\n<param name="p" value="1" textfile="/x"/></launch>',
     "<param> tag must have one and only one of value/textfile/binfile.", 2),
    ('<launch>\n<param name="p" value="$(arg req_arg)"/></launch>', "requires the 'req_arg' arg to be set", 2),
    ('<launch>\n<group if="yes"/></launch>', "yes is not a 'bool' type", 2),
    ('<launch>\n<group if="true" unless="false"/></launch>', "cannot set both 'if' and 'unless' on the same tag", 2),
    ('<launch>\n<param name="p" value="$(env NOPE)"/></launch>', "environment variable 'NOPE' is not set", 2),
    ('<launch>\n<param name="p" value="$(find nopkg)"/></launch>', "nopkg", 2),
    ('<launch>\n<rosparam>a: [1, 2</rosparam></launch>', "Error within YAML block", 2),
    # these ended in a RecursionError traceback: an alias to its own enclosing node, and YAML
    # nested deeper than the parser's recursion
    ('<launch>\n<rosparam>a: &amp;x {b: *x}</rosparam></launch>', "a value cannot contain itself", 2),
    ('<launch>\n<rosparam>a: &amp;x [*x]</rosparam></launch>', "a value cannot contain itself", 2),
    ('<launch>\n<rosparam>a: ' + '[' * 3000 + ']' * 3000 + '</rosparam></launch>', "nested too deeply", 2),
    ('<launch>\n<node name="a" pkg="demo" type="x"/><node name="a" pkg="demo" type="x"/></launch>',
     "roslaunch file contains multiple nodes named [/a]", 2),
    ('<launch>\n<node name="a" pkg="demo" type="x">\n</launch>', "Invalid roslaunch XML syntax: mismatched tag", 3),
    ('<!DOCTYPE l [<!ENTITY e "x">]><launch/>', "DOCTYPE and entity declarations are not accepted", 1),
    ("<nolaunch/>", "Invalid roslaunch XML syntax: no root <launch> tag", 1),
    # was a RecursionError traceback
    ('<launch>\n' + "<group>" * 3000 + "</group>" * 3000 + "</launch>",
     "Invalid roslaunch XML syntax: elements nested more than 200 deep", 2),
])
def test_errors_name_file_and_line(tmp_path: Path, xml: str, message: str, line: int) -> None:
    with pytest.raises(LaunchError) as info:
        load(tmp_path, xml)
    assert message in str(info.value)
    assert info.value.where == f"{tmp_path / 'main.launch'}:{line}"


def test_include_errors(tmp_path: Path) -> None:
    inc = tmp_path / "inc.launch"
    with pytest.raises(LaunchError, match=r"included file \[.*inc.launch\] requires the 'q' arg to be set"):
        load(tmp_path, f'<launch><include file="{inc}"/></launch>',
             **{"inc.launch": '<launch><param name="p" value="$(arg q)"/></launch>'})
    with pytest.raises(LaunchError, match=r"unused args \[zz\] for include of"):
        load(tmp_path, f'<launch><include file="{inc}"><arg name="zz" value="1"/></include></launch>',
             **{"inc.launch": "<launch/>"})
    with pytest.raises(LaunchError, match="include cycle") as info:
        load(tmp_path, f'<launch><include file="{inc}"/></launch>',
             **{"inc.launch": f'<launch>\n<include file="{tmp_path}/main.launch"/></launch>'})
    assert info.value.where == f"{inc}:2"


def test_command_textfile_binfile_params(tmp_path: Path) -> None:
    (tmp_path / "t.txt").write_text("some text")
    (tmp_path / "b.bin").write_bytes(b"\x00\x01")
    config = load(tmp_path, f"""<launch>
      <param name="cmd" command="echo hi"/>
      <param name="text" textfile="{tmp_path}/t.txt"/>
      <param name="bin" binfile="{tmp_path}/b.bin"/>
    </launch>""")
    assert params(config) == {"/cmd": "echo hi\n", "/text": "some text", "/bin": b"\x00\x01"}


def test_test_tags_and_machines(tmp_path: Path) -> None:
    config = load(tmp_path, """<launch>
      <machine name="here" address="localhost" default="true"/>
      <test test-name="t1" pkg="demo" type="t.py" time-limit="5" retry="2"/>
      <node name="n" pkg="demo" type="x"/>
    </launch>""")
    (test,) = config.tests
    assert (test.name, test.test_name, test.time_limit, test.retry) == ("t1", "t1", 5.0, 2)
    assert config.nodes[0].machine_name == "here"
    assert plan.node_list(config) == ["/n", "/t1"]
    with pytest.raises(LaunchError, match="<test> tags cannot have 'respawn' attribute"):
        load(tmp_path, '<launch><test test-name="t" pkg="demo" type="t" respawn="true"/></launch>')


def test_summary_and_dump(tmp_path: Path) -> None:
    config = load(tmp_path, """<launch>
      <param name="long" value="abcdefghijklmnopqrstuvwxyz"/>
      <param name="multi" type="str" value="a&#10;b"/>
      <param name="d" type="yaml" value="{a: 1, b: [2, 3]}"/>
      <group ns="g"><node name="n" pkg="demo" type="x" clear_params="true"/></group>
      <node name="m" pkg="demo" type="y"/>
    </launch>""")
    assert plan.summary(config) == (
        "\nSUMMARY\n========\n\nCLEAR PARAMETERS\n * /g/n/\n\nPARAMETERS\n"
        " * /d: {'a': 1, 'b': [2,...\n * /long: abcdefghijklmnopq...\n * /multi: <...>\n\n"
        "NODES\n  /\n    m (demo/y)\n  /g/\n    n (demo/x)\n")
    assert plan.dump_params(config) == ("/d:\n  a: 1\n  b:\n  - 2\n  - 3\n/long: abcdefghijklmnopqrstuvwxyz\n"
                                        "/multi: 'a\n\n  b'\n\n")


def test_a_long_include_chain_is_a_launch_error(tmp_path: Path) -> None:
    # 400 files each including the next ended in a RecursionError traceback.
    files = {f"c{i}.launch": f'<launch><include file="{tmp_path}/c{i + 1}.launch"/></launch>' for i in range(400)}
    files["c400.launch"] = '<launch><param name="p" value="1"/></launch>'
    with pytest.raises(LaunchError, match="launch files nested too deeply"):
        load(tmp_path, f'<launch><include file="{tmp_path}/c0.launch"/></launch>', **files)
    # a moderate chain and moderate nesting still load
    files = {f"d{i}.launch": f'<launch><include file="{tmp_path}/d{i + 1}.launch"/></launch>' for i in range(20)}
    files["d20.launch"] = "<launch>" + "<group>" * 50 + '<param name="p" value="1"/>' + "</group>" * 50 + "</launch>"
    assert params(load(tmp_path, f'<launch><include file="{tmp_path}/d0.launch"/></launch>', **files)) == {"/p": 1}


def test_a_yaml_alias_bomb_is_refused_not_expanded(tmp_path: Path) -> None:
    # Nine levels of nine references (387 million values once expanded) used to hang roslaunch.
    lines = ["l0: &l0 [" + ", ".join(["lol"] * 9) + "]"]
    lines += [f"l{n}: &l{n} [{', '.join([f'*l{n - 1}'] * 9)}]" for n in range(1, 9)]
    bomb = "\n".join(lines) + "\n"
    with pytest.raises(LaunchError, match=r"bomb.yaml contains invalid YAML:\nYAML aliases expand this value"):
        load(tmp_path, f'<launch><rosparam command="load" file="{tmp_path}/bomb.yaml"/></launch>',
             **{"bomb.yaml": bomb})
    flow = ("{" + bomb.strip().replace("\n", ", ") + "}").replace("&", "&amp;")
    with pytest.raises(LaunchError, match="YAML aliases expand this value"):
        load(tmp_path, f'<launch><param name="p" type="yaml" value="{flow}"/></launch>')
