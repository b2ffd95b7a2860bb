"""The rqt window's plugin menu and perspective, without a window."""

from __future__ import annotations

from pathlib import Path

import pytest

from kame.rqt.perspective import (
    DockedPlugin,
    Perspective,
    PerspectiveError,
    dock_title,
    dumps,
    find_plugin,
    loads,
    menu,
    next_instance,
    perspective_path,
)


def test_the_plugins_menu_is_grouped_as_rqt_groups_it() -> None:
    groups = {group: [p.title for p in entries] for group, entries in menu().items()}
    assert groups["Introspection"] == ["Node Graph"]
    assert groups["Logging"] == ["Console", "Logger Level"]
    assert "Plot" in groups["Visualization"]
    assert list(groups) == sorted(groups)


def test_a_plugin_is_found_by_any_of_its_names() -> None:
    for name in ("rqt_plot", "plot", "Plot", "rqt_plot/Plot", " RQT_PLOT "):
        assert find_plugin(name).id == "rqt_plot"
    assert find_plugin("Node Graph").id == "rqt_graph"
    with pytest.raises(PerspectiveError, match=r"no plugin named 'rqt_bogus'.*rqt_graph"):
        find_plugin("rqt_bogus")


def test_instances_are_numbered_from_one_reusing_freed_numbers() -> None:
    docked = [DockedPlugin("rqt_plot", 1), DockedPlugin("rqt_plot", 3), DockedPlugin("rqt_console", 1)]
    assert next_instance(docked, "rqt_plot") == 2
    assert next_instance(docked, "rqt_graph") == 1
    assert DockedPlugin("rqt_plot", 2).key == "rqt_plot#2"
    plot = find_plugin("rqt_plot")
    assert (dock_title(plot, 1), dock_title(plot, 2)) == ("Plot", "Plot (2)")


def test_a_perspective_round_trips_and_bad_ones_are_refused() -> None:
    perspective = Perspective((DockedPlugin("rqt_plot", 2, {"series": ["/turtle1/pose/x"]}),
                               DockedPlugin("rqt_console", 1)), geometry="AAEC", state="AwQF")
    assert loads(dumps(perspective)) == perspective
    for text, why in (("{", "JSON"), ("[]", "format"), ('{"format": "other"}', "format"),
                      ('{"format": "kame-rqt-perspective/1", "plugins": [{"plugin": "rqt_x", "instance": 1}]}',
                       "unknown plugin"),
                      ('{"format": "kame-rqt-perspective/1", "plugins": [{"plugin": "rqt_plot"}]}', "entry"),
                      ('{"format": "kame-rqt-perspective/1", "plugins": [{"plugin": "rqt_plot", "instance": 1}, '
                       '{"plugin": "rqt_plot", "instance": 1}]}', "twice")):
        with pytest.raises(PerspectiveError, match=why):
            loads(text)


def test_the_perspective_lives_under_ros_home() -> None:
    assert perspective_path({"ROS_HOME": "/tmp/rh"}, Path("/home/u")) == Path("/tmp/rh/kame/rqt_gui.json")
    assert perspective_path({}, Path("/home/u")) == Path("/home/u/.ros/kame/rqt_gui.json")
