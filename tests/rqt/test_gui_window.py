"""The rqt window on a live turtlesim: the Plugins menu, docks of every tool (several of one),
closing a dock closes its plugin, and the perspective brings plugins, settings and docks back.
Offscreen here; rqt_window_child runs the same window offscreen and on a private Xvfb."""

from __future__ import annotations

import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from kame.rqt.perspective import loads
from tests.turtlesim.sim import Sim, turtlesim


@pytest.fixture(scope="module")
def sim(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Sim]:
    with turtlesim(tmp_path_factory.mktemp("rqt_gui")) as (live, _node):
        yield live


def test_plugins_dock_close_and_come_back(sim: Sim, qtbot, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    from kame.rqt.gui_window import RqtWindow
    from kame.rqt.plugins import PluginContext

    path = tmp_path / "rqt_gui.json"
    context = PluginContext(sim.uri)
    window = RqtWindow(context, path)
    qtbot.addWidget(window)
    window.show()
    groups = {a.text(): [x.text() for x in a.menu().actions()] for a in window.plugin_menu.actions()}
    assert groups == {"Configuration": ["Dynamic Reconfigure"], "Introspection": ["Node Graph"],
                      "Logging": ["Console", "Logger Level"],
                      "Services": ["Service Caller"], "Topics": ["Message Publisher", "Topic Monitor"],
                      "Visualization": ["Image View", "Plot"]}
    window.plugin_actions["rqt_plot"].trigger()  # Plugins > Visualization > Plot
    window.add_plugin("rqt_plot", settings={"series": ["/turtle1/pose/x"]})
    for name in ("Console", "rqt_graph", "rqt_logger_level"):
        window.add_plugin(name)
    assert sorted(window.docks) == ["rqt_console#1", "rqt_graph#1", "rqt_logger_level#1", "rqt_plot#1", "rqt_plot#2"]
    window.add_plugin("rqt_topic", settings={"watched": ["/turtle1/pose"]})
    window.add_plugin("rqt_publisher", settings={"publishers": [
        {"topic": "/turtle1/cmd_vel", "type": "geometry_msgs/Twist", "rate": 5.0, "expressions": {"linear/x": "1.0"}}]})
    for name in ("Service Caller", "Image View"):
        window.add_plugin(name)
    assert window.docks["rqt_plot#2"].windowTitle() == "Plot (2)"
    second = window.docks["rqt_plot#2"].handle.widget
    qtbot.waitUntil(lambda: second.curves["/turtle1/pose/x"].xData is not None, timeout=10_000)  # type: ignore[attr-defined]
    console = window.docks["rqt_console#1"].handle.widget
    qtbot.waitUntil(lambda: console.take is not None, timeout=10_000)  # type: ignore[attr-defined]
    # a plot tabbed behind another dock draws nothing until it is brought to the front
    window.tabifyDockWidget(window.docks["rqt_plot#2"], window.docks["rqt_console#1"])
    window.docks["rqt_console#1"].raise_()
    qtbot.waitUntil(lambda: second.visibleRegion().isEmpty(), timeout=5_000)
    curve = second.curves["/turtle1/pose/x"]  # type: ignore[attr-defined]
    shown, version = curve.xData, second.source.version  # type: ignore[attr-defined]
    qtbot.waitUntil(lambda: second.source.version != version, timeout=10_000)  # type: ignore[attr-defined]
    second.redraw()  # type: ignore[attr-defined]
    assert curve.xData is shown
    window.docks["rqt_plot#2"].raise_()
    qtbot.waitUntil(lambda: curve.xData is not shown, timeout=10_000)

    first = window.docks["rqt_plot#1"]
    node = first.handle.widget.source.node  # type: ignore[attr-defined]
    assert node.name.startswith("/rqt_gui_plot_1_") and not node.is_shutdown
    first.close()
    assert "rqt_plot#1" not in window.docks and node.is_shutdown
    assert window.add_plugin("rqt_plot").docked.key == "rqt_plot#1"  # the freed number again

    window.docks["rqt_console#1"].setFloating(True)
    window.close()
    saved = loads(path.read_text())
    assert [d.key for d in saved.plugins] == ["rqt_plot#2", "rqt_console#1", "rqt_graph#1", "rqt_logger_level#1",
                                              "rqt_topic#1", "rqt_publisher#1", "rqt_service_caller#1",
                                              "rqt_image_view#1", "rqt_plot#1"]
    settings = {d.key: dict(d.settings) for d in saved.plugins}
    assert settings["rqt_plot#2"] == {"series": ["/turtle1/pose/x"]}
    assert settings["rqt_topic#1"] == {"watched": ["/turtle1/pose"]}
    assert settings["rqt_publisher#1"] == {"publishers": [{"topic": "/turtle1/cmd_vel", "type": "geometry_msgs/Twist",
                                                           "rate": 5.0, "expressions": {
                                                               "linear/x": "1.0", "linear/y": "", "linear/z": "",
                                                               "angular/x": "", "angular/y": "", "angular/z": ""}}]}

    again = RqtWindow(context, path)
    qtbot.addWidget(again)
    assert again.load_perspective() == []
    again.show()
    assert sorted(again.docks) == sorted(d.key for d in saved.plugins)
    assert list(again.docks["rqt_plot#2"].handle.widget.curves) == ["/turtle1/pose/x"]  # type: ignore[attr-defined]
    assert again.docks["rqt_topic#1"].handle.widget.monitor.watched() == ["/turtle1/pose"]  # type: ignore[attr-defined]
    assert list(again.docks["rqt_publisher#1"].handle.widget.rows) == ["/turtle1/cmd_vel"]  # type: ignore[attr-defined]
    assert again.docks["rqt_console#1"].isFloating() and not again.docks["rqt_graph#1"].isFloating()
    assert saved.geometry and saved.state  # the window's size comes back: rqt_window_child, on a screen it fits
    again.close()


def test_the_rqt_command_lists_and_refuses(sim: Sim) -> None:
    from tests.turtlesim.sim import BIN

    listed = subprocess.run([str(BIN / "rqt"), "--list-plugins"], capture_output=True, text=True, timeout=60)
    assert listed.returncode == 0 and "rqt_plot/Plot  (Visualization > Plot)" in listed.stdout
    bad = subprocess.run([str(BIN / "rqt"), "--standalone", "rqt_bogus"], capture_output=True, text=True, timeout=60)
    assert bad.returncode == 2 and "no plugin named 'rqt_bogus'" in bad.stderr
    for command in (["rqt_topic", "--help"], ["rqt_image_view", "--help"], ["rosrun", "rqt_gui", "rqt_gui", "--help"],
                    ["rosrun", "rqt_service_caller", "rqt_service_caller", "--help"]):
        helped = subprocess.run([str(BIN / command[0]), *command[1:]], capture_output=True, text=True, timeout=60,
                                env=sim.env)
        assert helped.returncode == 0 and "--standalone" in helped.stdout, (command, helped.stderr)


@pytest.fixture(params=["offscreen", "xvfb"])
def qt_env(request: pytest.FixtureRequest, sim: Sim) -> Iterator[tuple[dict[str, str], str | None]]:
    """The sim's environment with Qt drawing offscreen, or on a private Xvfb (and its display)."""
    from tests.turtlesim.xserver import xvfb

    env = {k: v for k, v in sim.env.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM")}
    if request.param == "offscreen":
        yield dict(env, QT_QPA_PLATFORM="offscreen"), None
        return
    with xvfb() as display:
        yield dict(env, DISPLAY=display), display


def test_the_window_in_its_own_process_on_each_display(sim: Sim, qt_env: tuple[dict[str, str], str | None],
                                                       tmp_path: Path) -> None:
    from tests.support import REPO, Proc
    from tests.turtlesim.xserver import find_window

    env, display = qt_env
    path = tmp_path / "rqt_gui.json"
    child = Proc([sys.executable, "-m", "tests.rqt.rqt_window_child", sim.uri, str(path)], env, cwd=REPO,
                 stdin=subprocess.PIPE)
    try:
        shown = child.wait_line("shown", timeout=60)
        assert "700x500" in shown and "/turtlesim" in shown, shown
        if display is not None:
            assert "xcb" in shown
            window = find_window(display, "Default - rqt")
            assert window is not None and window.viewable and (window.width, window.height) == (700, 500)
        assert child.popen.stdin is not None
        child.popen.stdin.write("\n")
        child.popen.stdin.flush()
        again = child.wait_line("again", timeout=60)
        assert again.split() == ["again", "700x500", "docks", "rqt_console#1,rqt_graph#1", "problems", "[]"], again
        assert child.popen.wait(30) == 0
    finally:
        _, err = child.stop()
    assert "Traceback" not in err, err


def test_every_plugin_opens_and_closes_without_a_master(qtbot, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    from kame.rqt.gui_window import RqtWindow
    from kame.rqt.perspective import PLUGINS
    from kame.rqt.plugins import PluginContext
    from tests.support import free_port

    window = RqtWindow(PluginContext(f"http://127.0.0.1:{free_port()}/"), tmp_path / "p.json")
    qtbot.addWidget(window)
    window.show()
    for info in PLUGINS:
        window.add_plugin(info.id)
    assert len(window.docks) == len(PLUGINS)
    console = window.docks["rqt_console#1"].handle.widget
    assert console.status.text().startswith("waiting for the master at")  # type: ignore[attr-defined]
    topics = window.docks["rqt_topic#1"].handle.widget
    assert topics.status.text().startswith("cannot list topics")  # type: ignore[attr-defined]
    logger = window.docks["rqt_logger_level#1"].handle.widget
    qtbot.waitUntil(lambda: "cannot reach the master" in logger.status.text(), timeout=10_000)  # type: ignore[attr-defined]
    window.close()
    assert window.docks == {} and loads((tmp_path / "p.json").read_text()).plugins


def test_plugins_ask_again_once_the_master_is_up(qtbot, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    from kame.rqt.gui_window import RqtWindow
    from kame.rqt.plugins import PluginContext
    from tests.support import Proc, free_port, ros_env
    from tests.turtlesim.sim import BIN

    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    window = RqtWindow(PluginContext(uri), None)
    qtbot.addWidget(window)
    topics = window.add_plugin("rqt_topic").handle.widget
    services = window.add_plugin("rqt_service_caller").handle.widget
    assert topics.status.text().startswith("cannot list topics")  # type: ignore[attr-defined]
    started: list[Proc] = []
    try:
        with qtbot.waitSignal(window.master_up, timeout=20_000):
            started.append(Proc([str(BIN / "rosmaster"), "--core", "-p", str(port)], ros_env(tmp_path, uri)))
        assert topics.status.text() == "0 topics"  # type: ignore[attr-defined]
        qtbot.waitUntil(lambda: services.status.text() == "0 services", timeout=10_000)  # type: ignore[attr-defined]
    finally:
        window.close()
        for proc in started:
            proc.stop()


@pytest.mark.parametrize("size", [(1200, 800), (1600, 1000)])
def test_three_docks_keep_every_control_reachable(sim: Sim, qtbot, size: tuple[int, int]) -> None:  # type: ignore[no-untyped-def]
    """Node Graph, Plot and Console docked from the Plugins menu: every button, box and field of
    each lies inside its dock, the Console's Message column keeps its share of the table, and the
    graph is fitted in its view."""
    from PySide6.QtWidgets import QAbstractButton, QAbstractSpinBox, QComboBox, QLineEdit

    from kame.rqt.gui_window import RqtWindow
    from kame.rqt.plugins import PluginContext

    window = RqtWindow(PluginContext(sim.uri), None)
    qtbot.addWidget(window)
    for plugin in ("rqt_graph", "rqt_plot", "rqt_console"):
        window.plugin_actions[plugin].trigger()
    window.resize(*size)
    window.show()
    qtbot.waitExposed(window)
    graph = window.docks["rqt_graph#1"].handle.widget
    qtbot.waitUntil(lambda: graph.graphics is not None, timeout=10_000)  # type: ignore[attr-defined]
    for key, dock in window.docks.items():
        viewport = dock.widget().viewport()  # type: ignore[attr-defined]
        for kind in (QAbstractButton, QAbstractSpinBox, QComboBox, QLineEdit):
            for control in dock.handle.widget.findChildren(kind):
                if control.isVisibleTo(dock):
                    where = control.rect().translated(control.mapTo(viewport, control.rect().topLeft()))
                    assert viewport.rect().contains(where), f"{key}: {type(control).__name__} at {where}"
    table = window.docks["rqt_console#1"].handle.widget.table  # type: ignore[attr-defined]
    assert table.columnWidth(0) >= 0.24 * table.viewport().width()  # not an ellipsis
    shown = graph.view.mapToScene(graph.view.viewport().rect()).boundingRect()  # type: ignore[attr-defined]
    assert shown.contains(graph.graphics.itemsBoundingRect())  # type: ignore[attr-defined]
