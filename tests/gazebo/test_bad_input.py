"""Bad input never crashes the simulator: each is one GazeboError naming the file or element and
saying why, and the world keeps running; what kame leaves out is a warning; a diverging model is
put back with a warning."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from tests.gazebo import require_engine

require_engine()

from kame.gazebo import GazeboError, Pose, Resources, State, World  # noqa: E402  (MuJoCo loads once require_engine has checked it can)

GROUND = "<include><uri>model://ground_plane</uri></include>"


def sdf(body: str) -> str:
    return f'<sdf version="1.6"><world name="w">{body}</world></sdf>'


def refused(text: str, resources: Resources | None = None) -> str:
    with pytest.raises(GazeboError) as caught:
        World.from_sdf(text, resources, source="bad.world")
    return str(caught.value)


def test_malformed_xml_names_the_file_and_line() -> None:
    message = refused('<sdf version="1.6">\n<world name="w">\n<model name="m"></world></sdf>')
    assert message.startswith("bad.world: malformed XML: mismatched tag: line 3")


def test_entities_and_doctypes_are_refused() -> None:
    message = refused('<?xml version="1.0"?>\n<!DOCTYPE sdf [<!ENTITY big "x">]>\n<sdf version="1.6"/>')
    assert "bad.world:2: DOCTYPE and entity declarations are not accepted" in message


@pytest.mark.parametrize(("body", "expected"), [
    ('<model name="m"><pose>1 2 three 0 0 0</pose></model>', "<pose> at bad.world:1: expected a number, not 'three'"),
    ('<model name="m"><pose>1 2 3</pose></model>', "<pose> at bad.world:1: expected 6 numbers, not '1 2 3'"),
    ('<model name="m"><pose>nan 0 0 0 0 0</pose></model>', "a pose must be finite"),
    ("<model><link name='l'/></model>", "<model> at bad.world:1: a <model> needs a name"),
    ('<model name="m"><link name="a"/><joint name="j" type="revolute"><parent>a</parent><child>b</child>'
     '</joint></model>', "no frame, link or joint named 'b' in model 'm'"),
    ('<model name="m"><link name="a"><pose relative_to="b">0 0 0 0 0 0</pose></link>'
     '<link name="b"><pose relative_to="a">0 0 0 0 0 0</pose></link></model>', "in a cycle"),
    ('<model name="m"><link name="a"><inertial><mass>-1</mass></inertial></link></model>',
     "a link's mass must be above 0, not -1.0"),
    ('<model name="m"><link name="a"><collision name="c"><geometry><mesh><uri>/nowhere/rock.stl</uri></mesh>'
     '</geometry></collision></link></model>', "mesh /nowhere/rock.stl: cannot read /nowhere/rock.stl: No such file"),
    ('<model name="m"/><model name="m"/>', "a second model named 'm'"),
    ("<physics><max_step_size>0</max_step_size></physics>", "max_step_size must be above 0"),
])
def test_bad_sdf_is_one_clear_error(body: str, expected: str) -> None:
    assert expected in refused(sdf(body))


def test_a_missing_model_names_the_uri_and_the_path(tmp_path: Path) -> None:
    message = refused(sdf("<include><uri>model://no_such_model</uri></include>"), Resources((str(tmp_path),)))
    assert "<include> at bad.world:1: model://no_such_model not found in GAZEBO_MODEL_PATH" in message
    assert str(tmp_path) in message


def test_a_missing_package_names_it() -> None:
    body = ('<model name="m"><link name="a"><visual name="v"><geometry><mesh><uri>package://nopkg/m.dae</uri>'
            '</mesh></geometry></visual></link></model>')
    message = refused(sdf(body), Resources(find_package=lambda package: None))
    assert "package [nopkg] not found for package://nopkg/m.dae" in message


def test_a_malformed_mesh_names_its_file(tmp_path: Path) -> None:
    (tmp_path / "broken.stl").write_bytes(b"solid x\nfacet nonsense\n")
    body = (f'<model name="m"><link name="a"><visual name="v"><geometry><mesh><uri>{tmp_path}/broken.stl</uri>'
            '</mesh></geometry></visual></link></model>')
    assert f"cannot read {tmp_path}/broken.stl" in refused(sdf(body)) or "has no triangles" in refused(sdf(body))


def test_what_kame_cannot_simulate_is_left_out_with_a_warning() -> None:
    world = World.from_sdf(sdf("""<model name="m"><link name="a">
      <collision name="hills"><geometry><heightmap><uri>x.png</uri></heightmap></geometry></collision>
      <visual name="box"><geometry><box><size>1 1 1</size></box></geometry></visual></link>
      <link name="b"/><joint name="u" type="universal"><parent>a</parent><child>b</child></joint></model>
      <actor name="walker"/>"""))
    warnings = world.take_warnings()
    assert any("heightmap geometry is not simulated by kame; left out" in w for w in warnings)
    assert any("'universal' joints are not simulated by kame; joint 'u' is fixed instead" in w for w in warnings)
    assert any("<actor> is not simulated" in w for w in warnings)
    assert world.take_warnings() == []
    world.step(10)


@pytest.mark.parametrize(("urdf", "expected"), [
    ("<robot name='r'><link name='a'/>", "malformed XML"),
    ("<robot name='r'><link name='a'/><joint name='j' type='revolute'><parent link='a'/></joint></robot>",
     "a <joint> needs a name, a <parent link=...> and a <child link=...>"),
    ("<robot name='r'><link name='a'/><joint name='j' type='hinge'><parent link='a'/><child link='a'/></joint>"
     "</robot>", "unknown joint type 'hinge'"),
    ("<robot name='r'><link name='a'/><joint name='j' type='fixed'><parent link='a'/><child link='b'/></joint>"
     "</robot>", "joint 'j' names link 'b', which the robot does not have"),
    ("<robot name='r'><link name='a'><visual><geometry><capsule/></geometry></visual></link></robot>",
     "unknown URDF geometry <capsule>"),
    ("<sdf version='1.6'/>", "expected a URDF <robot>, not <sdf>"),
    ("<robot name='r'><link name='a'><inertial><mass value='x'/></inertial></link></robot>",
     "expected a number, not 'x'"),
])
def test_bad_urdf_is_refused_and_the_world_runs_on(urdf: str, expected: str) -> None:
    world = World.from_sdf(sdf(GROUND))
    with pytest.raises(GazeboError, match="robot_description") as caught:  # the message names the source
        world.spawn_urdf(urdf, "r", source="robot_description")
    assert expected in str(caught.value)
    assert world.model_names() == ["ground_plane"]
    world.step(10)


def test_a_model_spawned_inside_another_is_refused_and_the_world_unchanged() -> None:
    world = World.from_sdf(sdf(f"{GROUND}<include><uri>model://box</uri></include>"))
    world.step(100)
    with pytest.raises(GazeboError, match="model 'inside' would be inside model 'box'"):
        world.spawn_sdf('<sdf version="1.6"><model name="x"><link name="l"><collision name="c"><geometry><sphere>'
                        '<radius>0.3</radius></sphere></geometry></collision></link></model></sdf>', "inside",
                        Pose((0.0, 0.0, 0.5)))
    with pytest.raises(GazeboError, match="would be inside model 'ground_plane'"):
        world.spawn_urdf("<robot name='r'><link name='a'><collision><geometry><box size='1 1 1'/></geometry>"
                         "</collision></link></robot>", "buried", Pose((5.0, 0.0, -2.0)))
    assert world.model_names() == ["ground_plane", "box"]
    world.step(100)
    assert world.sim_time == pytest.approx(0.2)


@pytest.mark.parametrize("call", [
    lambda w: w.apply_body_wrench("box::link", (math.nan, 0.0, 0.0)),
    lambda w: w.apply_body_wrench("box::link", (0.0, 0.0, 0.0), (0.0, math.inf, 0.0)),
    lambda w: w.set_model_state("box", State(Pose((math.nan, 0.0, 0.0)))),
    lambda w: w.set_model_state("box", State(Pose(), (0.0, 0.0, math.nan))),
    lambda w: w.set_link_state("box::link", State(Pose(), (0.0, 0.0, 0.0), (math.inf, 0.0, 0.0))),
    lambda w: w.spawn_sdf('<sdf version="1.6"><model name="n"><link name="l"/></model></sdf>', "n",
                          Pose((0.0, math.nan, 0.0))),
])
def test_nan_values_are_refused_with_a_clear_error(call: object) -> None:
    world = World.from_sdf(sdf(f"{GROUND}<include><uri>model://box</uri></include>"))
    with pytest.raises(GazeboError, match="must be finite numbers, not NaN or infinite"):
        call(world)  # type: ignore[operator]
    world.step(10)
    assert math.isfinite(world.model_state("box").pose.position[2])


def test_unknown_names_are_refused() -> None:
    world = World.from_sdf(sdf(GROUND))
    for call, expected in ((lambda: world.model_state("nope"), "no model named 'nope'"),
                           (lambda: world.link_state("nope::link"), "no link named 'nope::link'"),
                           (lambda: world.joint_state("ground_plane::j"), "no joint named 'ground_plane::j'"),
                           (lambda: world.delete_model("nope"), "no model named 'nope'"),
                           (lambda: world.spawn_sdf('<sdf version="1.6"><model name="ground_plane"><link name="l"/>'
                                                    "</model></sdf>"), "already exists")):
        with pytest.raises(GazeboError, match=expected):
            call()


def test_a_diverging_model_is_put_back_with_a_warning(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                       capfd: pytest.CaptureFixture[str]) -> None:
    monkeypatch.chdir(tmp_path)  # where MuJoCo's default handler would write MUJOCO_LOG.TXT
    world = World.from_sdf(sdf(f"""{GROUND}<include><uri>model://box</uri><pose>0 0 0.5 0 0 0</pose></include>
      <include><uri>model://sphere</uri><pose>3 0 2 0 0 0</pose></include>"""))
    world.step(100)
    world.apply_body_wrench("sphere::link", (1e12, 0.0, 0.0), duration=0.01)
    world.step(50)
    (warning,) = world.take_warnings()
    assert warning.startswith("model sphere diverged at sim time") and "put back where it was spawned" in warning
    assert world.model_state("sphere").pose.position == pytest.approx((3.0, 0.0, 2.0), abs=0.05)
    assert world.model_state("box").pose.position == pytest.approx((0.0, 0.0, 0.5), abs=1e-3)  # untouched
    assert world.sim_time == pytest.approx(0.15)
    assert list(tmp_path.iterdir()) == [] and "WARNING" not in capfd.readouterr().out  # told once, by the World


def test_nan_in_the_engines_state_is_put_right_with_a_warning() -> None:
    world = World.from_sdf(sdf(f"""{GROUND}<include><uri>model://sphere</uri><pose>3 0 2 0 0 0</pose></include>
      <include><uri>model://box</uri><pose>0 0 0.5 0 0 0</pose></include>"""))
    world.step(10)
    sphere = world.model.body_jntadr[world.body_id("sphere::link")]
    world.data.qvel[world.model.jnt_dofadr[sphere]] = math.nan  # as a blown-up solve leaves it
    world.step(1)
    # MuJoCo's solver solves all contacts and bodies together: the NaN reached the box too, so both go back
    (warning,) = world.take_warnings()
    assert warning.startswith("model box, sphere diverged")
    assert world.model_state("sphere").pose.position == pytest.approx((3.0, 0.0, 2.0))
    assert world.model_state("box").pose.position == pytest.approx((0.0, 0.0, 0.5))
    world.step(100)
    assert all(math.isfinite(v) for v in world.model_state("sphere").pose.position)


@pytest.mark.parametrize(("sensor", "expected"), [
    ("<sensor name='s' type='ray'><ray><scan><horizontal><samples>nan</samples></horizontal></scan>"
     "<range><min>0</min><max>1</max></range></ray></sensor>", "expected a finite number, not 'nan'"),
    ("<sensor name='s' type='ray'><ray><scan><horizontal><samples>2.5</samples></horizontal></scan>"
     "<range><min>0</min><max>1</max></range></ray></sensor>", "expected a whole number, not 2.5"),
    ("<sensor name='s' type='ray'><ray><range><min>2</min><max>1</max></range></ray></sensor>",
     "needs 0 <= min < max"),
    ("<sensor name='s' type='camera'><camera><image><width>1e9</width></image></camera></sensor>",
     "an image of 1000000000x240 pixels cannot be rendered"),
    ("<sensor name='s' type='camera'><camera><horizontal_fov>4</horizontal_fov></camera></sensor>",
     "needs 0 < horizontal_fov < pi"),
])
def test_a_sensors_bad_configuration_is_a_clear_error(sensor: str, expected: str) -> None:
    text = sdf(f"<model name='m'><static>true</static><link name='l'>{sensor}</link></model>")
    try:
        world = World.from_sdf(text, source="bad.world")
        world.ray_scan(world.sensors()[0])
    except GazeboError as exc:
        assert expected in str(exc)
    else:
        raise AssertionError(f"no error for {sensor}")


def test_two_lights_of_one_name_are_refused() -> None:
    assert "light 'lamp'" in refused(sdf("<light name='lamp'/><light name='lamp'/>"))
