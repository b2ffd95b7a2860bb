"""The pure pieces of gazebo_ros on kame: gzserver's command line, plugin parameters as gazebo_ros
reads them, poses relative to another entity, spawn_model's -package_to_model, model kinds."""

from __future__ import annotations

import math

import pytest

from kame.gazebo.description import Plugin
from kame.gazebo.poses import Pose
from kame.gazebo.xmltree import parse
from kame.gazebo_ros import relative
from kame.gazebo_ros.command_line import CommandLineError
from kame.gazebo_ros.command_line import parse as parse_command_line
from kame.gazebo_ros.plugins.parameters import Parameters, PluginParameterError


def test_empty_world_launch_command_line() -> None:
    # what empty_world.launch passes with paused:=true verbose:=true (the empty command_arg2 included)
    options = parse_command_line(["-u", "", "--verbose", "-e", "ode", "worlds/empty.world"])
    assert (options.paused, options.verbose, options.physics) == (True, True, "ode")
    assert options.world == "worlds/empty.world"
    assert parse_command_line([]).world == "worlds/empty.world"
    plugins = parse_command_line(["-s", "libgazebo_ros_api_plugin.so", "-s", "libother.so", "--seed=7", "w.world"])
    assert plugins.foreign_plugins() == ["libother.so"] and plugins.seed == 7
    assert parse_command_line(["--iters", "10"]).iterations == 10


@pytest.mark.parametrize("args", [["--bogus"], ["-e"], ["--iters", "many"], ["--iters", "-1"]])
def test_bad_command_lines_say_why(args: list[str]) -> None:
    with pytest.raises(CommandLineError, match="Error"):
        parse_command_line(args)


def plugin(body: str) -> Plugin:
    element = parse(f'<plugin name="p" filename="libx.so">{body}</plugin>', "<test>")
    return Plugin("p", "libx.so", "robot", "", "", element)


def test_parameters_read_as_gazebo_ros_reads_them() -> None:
    p = Parameters(plugin("<wheelSeparation>0.5</wheelSeparation><legacyMode>false</legacyMode>"
                          "<xyzOffset>1 2 3</xyzOffset><robotNamespace>/r1/</robotNamespace>"), "DiffDrive(ns = //)")
    assert p.number("wheelSeparation", 0.34) == 0.5
    assert p.flag("legacyMode", True) is False
    assert p.vector("xyzOffset", (0, 0, 0)) == (1.0, 2.0, 3.0)
    assert p.namespace() == "r1"
    assert p.number("wheelDiameter", 0.15) == 0.15
    assert p.flag("publishWheelTF", False) is False
    assert p.notes == ["DiffDrive(ns = //): missing <wheelDiameter> default is 0.15",
                       "DiffDrive(ns = //): missing <publishWheelTF> default is 0"]


@pytest.mark.parametrize("body", ["<updateRate>fast</updateRate>", "<updateRate>nan</updateRate>"])
def test_a_parameter_that_is_no_number_is_an_error_naming_it(body: str) -> None:
    with pytest.raises(PluginParameterError, match="<updateRate>"):
        Parameters(plugin(body), "GazeboRosLaser").number("updateRate", 10.0)


def test_relative_poses_round_trip() -> None:
    frame = Pose.from_xyz_rpy(1.0, 2.0, 0.5, 0.1, -0.2, 1.2)
    pose = Pose.from_xyz_rpy(-0.3, 0.7, 1.1, 0.5, 0.0, -0.4)
    back = relative.carried_into_world(relative.seen_from(pose, frame), frame)
    assert back.position == pytest.approx(pose.position)
    assert abs(sum(a * b for a, b in zip(back.orientation, pose.orientation, strict=True))) == pytest.approx(1.0)
    yawed = Pose.from_xyz_rpy(0, 0, 0, 0, 0, math.pi / 2)
    assert relative.seen_from(Pose((0.0, 1.0, 0.0)), yawed).position == pytest.approx((1.0, 0.0, 0.0))
    assert relative.normalized((0.0, 0.0, 0.0, 0.0)) == (0.0, 0.0, 0.0, 1.0)
    assert all(relative.is_inertial(n) for n in ("", "world", "map", "/map"))


def test_spawn_model_package_to_model_and_model_kinds() -> None:
    from kame.gazebo_ros.models import model_kind
    from kame.gazebo_ros.spawn_model import package_to_model

    urdf = '<robot name="r"><link name="l"><visual><geometry><mesh filename="package://p/m.stl"/></geometry>' \
           "</visual></link></robot>"
    assert 'filename="model://p/m.stl"' in package_to_model(urdf)
    assert model_kind(urdf) == "urdf"
    assert model_kind('<sdf version="1.6"><model name="m"/></sdf>') == "sdf"
    assert model_kind("<robot") is None and model_kind("<world/>") is None


def test_depth_cut_to_range_and_the_point_cloud_of_a_depth_camera() -> None:
    import numpy as np

    from kame.gazebo_ros.plugins.camera import depth_in_range, point_cloud_bytes

    depth = depth_in_range(np.array([[0.3, 2.0, 9.0], [np.inf, 4.0, 1.0]]), 0.4, 8.0)
    assert depth.dtype == np.float32
    assert np.isnan(depth[0, 0]) and np.isnan(depth[0, 2]) and np.isnan(depth[1, 0])  # near, far, nothing
    rgb = np.array([[[1, 2, 3], [10, 20, 30], [0, 0, 0]], [[0, 0, 0], [255, 128, 7], [9, 8, 7]]], dtype=np.uint8)
    f, cx, cy = 2.0, 1.0, 0.5
    points = np.frombuffer(point_cloud_bytes(depth, rgb, f, cx, cy), dtype="<f4").reshape(2, 3, 4)
    # pixel (row 1, column 2) at 1 m: x = (2 - cx) / f, y = (1 - cy) / f, z = 1, rgb packed 0x00RRGGBB
    assert points[1, 2, :3].tolist() == [0.5, 0.25, 1.0]
    assert points[1, 1, :3].tolist() == [0.0, 1.0, 4.0]
    assert points[1, 1, 3:].view("<u4")[0] == (255 << 16) | (128 << 8) | 7
    assert points[0, 1, 3:].view("<u4")[0] == (10 << 16) | (20 << 8) | 30
    assert np.isnan(points[0, 0, :3]).all()  # a cut depth is a NaN point (is_dense false)
