"""rqt_reconfigure: the model (servers, rows, typed edits) without Qt, and the plugin's window
on the dynamic_reconfigure tutorial server: an edit reaches the server through set_parameters,
and a change made elsewhere (dynparam) shows in the window from parameter_updates."""

from __future__ import annotations

import importlib
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from types import ModuleType

import pytest

from kame.node.node import Node
from kame.reconfigure.encoding import decode_description, encode_description
from kame.rqt.reconfigure_model import EditError, ParamRow, parse, rows, servers, shown, values
from kame.rqt.ros_node import start_node
from tests.support import Proc, free_port, kame_command, ros_env, wait_for_master

TUTORIALS = Path(__file__).parents[1] / "dynamic_reconfigure" / "dynamic_tutorials"
SERVER = TUTORIALS / "nodes" / "server.py"


@pytest.fixture
def tutorial_rows(monkeypatch: pytest.MonkeyPatch) -> Iterator[list[ParamRow]]:
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(TUTORIALS))
    config: ModuleType = importlib.import_module("dynamic_tutorials.cfg.TutorialsConfig")
    yield rows(decode_description(encode_description(config)))
    for name in [m for m in sys.modules if m == "dynamic_tutorials" or m.startswith("dynamic_tutorials.")]:
        del sys.modules[name]


def test_servers_are_the_set_parameters_services() -> None:
    assert servers(["/rosout/get_loggers", "/b/set_parameters", "/a/x/set_parameters", "/set_parameters_not"]) == [
        "/a/x", "/b"]


def test_rows_follow_the_groups_with_ranges_and_choices(tutorial_rows: list[ParamRow]) -> None:
    by_name = {row.name: row for row in tutorial_rows}
    assert list(by_name) == ["int_param", "double_param", "str_param", "bool_param", "size", "speed", "label"]
    assert [by_name[n].group for n in ("int_param", "speed", "label")] == ["", "Limits", "Limits/Inner_Most"]
    assert by_name["int_param"].range_text() == "[0, 100]" and by_name["str_param"].range_text() == ""
    assert by_name["size"].range_text() == "Small=0, Medium=1, Large=2, ExtraLarge=3"
    assert values(tutorial_rows, {"size": 2, "int_param": 5, "unknown": 1}) == {"size": "Large (2)", "int_param": "5"}


def test_typed_text_becomes_the_parameters_value_or_says_why_not(tutorial_rows: list[ParamRow]) -> None:
    by_name = {row.name: row for row in tutorial_rows}
    assert parse(by_name["int_param"], " 70 ") == 70 and parse(by_name["double_param"], "0.25") == 0.25
    assert parse(by_name["bool_param"], "false") is False and parse(by_name["bool_param"], "Yes") is True
    assert parse(by_name["size"], "large") == 2 and parse(by_name["size"], "3") == 3
    assert parse(by_name["size"], shown(by_name["size"], 1)) == 1 and parse(by_name["str_param"], "hi") == "hi"
    for name, text, why in (("int_param", "2.5", "can't set parameter 'int_param'"),
                            ("bool_param", "maybe", "bool_param is a bool"),
                            ("size", "Huge", "size is one of Small=0"), ("size", "7", "size is one of")):
        with pytest.raises(EditError, match=why):
            parse(by_name[name], text)


@pytest.fixture
def live(tmp_path: Path) -> Iterator[tuple[dict[str, str], Proc, Node]]:
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = ros_env(tmp_path / "home", uri)
    env["ROS_PACKAGE_PATH"] = str(TUTORIALS)
    master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), env)
    server = None
    node = None
    try:
        wait_for_master(uri, proc=master)
        server = Proc([sys.executable, str(SERVER)], env)
        server.wait_line("Reconfigure Request: 50, 0.5,          Hello World, True, 1")
        node = start_node("reconfigure_test", {"master": uri}, env)
        yield env, server, node
    finally:
        if node is not None:
            node.shutdown("test over")
        if server is not None:
            server.stop()
        master.stop()


def test_the_window_edits_the_server_and_follows_its_updates(live: tuple[dict[str, str], Proc, Node],
                                                             qtbot) -> None:  # type: ignore[no-untyped-def]
    from kame.rqt.reconfigure_source import ReconfigureSource
    from kame.rqt.reconfigure_window import VALUE, ReconfigureWindow

    env, server, node = live
    holder: list[ReconfigureWindow] = []
    source = ReconfigureSource(node, lambda name: holder[0].server_changed.emit(name))
    window = ReconfigureWindow(source)
    holder.append(window)
    qtbot.addWidget(window)
    window.refresh_servers()
    qtbot.waitUntil(lambda: window.server_box.count() == 1, timeout=10_000)
    assert window.server_box.itemText(0) == "/dynamic_tutorials"
    window.choose("/dynamic_tutorials")
    qtbot.waitUntil(lambda: "size" in window.items and window.items["size"].text(VALUE) == "Medium (1)",
                    timeout=10_000)
    assert window.items["speed"].parent().text(0) == "Limits"
    window.set_value("int_param", "70")
    server.wait_line("Reconfigure Request: 70, 0.5,          Hello World, True, 1")
    window.set_value("size", "ExtraLarge")
    server.wait_line("Reconfigure Request: 70, 0.5,          Hello World, True, 3")
    qtbot.waitUntil(lambda: window.items["size"].text(VALUE) == "ExtraLarge (3)", timeout=10_000)
    window.set_value("bool_param", "perhaps")  # refused here: nothing is sent, the cell shows the server's value
    assert "bool_param is a bool" in window.status.text() and window.items["bool_param"].text(VALUE) == "True"
    dynparam = subprocess.run(kame_command("kame.cli.dynparam", "set", "/dynamic_tutorials", "double_param", "0.75"),
                              env=env, capture_output=True, text=True, timeout=60)
    assert dynparam.returncode == 0, dynparam.stderr
    qtbot.waitUntil(lambda: window.items["double_param"].text(VALUE) == "0.75", timeout=10_000)
    window.set_value("int_param", "500")  # above the .cfg's max: the server clamps, the window shows its value
    qtbot.waitUntil(lambda: window.items["int_param"].text(VALUE) == "100", timeout=10_000)
    window.close()
    source.stop()


def test_the_plugin_in_the_rqt_window_and_its_commands(live: tuple[dict[str, str], Proc, Node],
                                                       qtbot) -> None:  # type: ignore[no-untyped-def]
    from kame.rqt.gui_window import RqtWindow
    from kame.rqt.plugins import PluginContext
    from kame.rqt.reconfigure_window import VALUE
    from tests.turtlesim.sim import BIN

    env, _server, _node = live
    window = RqtWindow(PluginContext(env["ROS_MASTER_URI"]), None)
    qtbot.addWidget(window)
    dock = window.add_plugin("rqt_reconfigure", settings={"server": "/dynamic_tutorials"})  # as a perspective keeps it
    widget = dock.handle.widget
    qtbot.waitUntil(lambda: "str_param" in widget.items  # type: ignore[attr-defined]
                    and widget.items["str_param"].text(VALUE) == "Hello World", timeout=10_000)  # type: ignore[attr-defined]
    assert dock.handle.settings() == {"server": "/dynamic_tutorials"}
    window.close()
    listed = subprocess.run([str(BIN / "rqt"), "--list-plugins"], capture_output=True, text=True, timeout=60)
    assert "rqt_reconfigure/Param  (Configuration > Dynamic Reconfigure)" in listed.stdout
    for command in (["rqt_reconfigure", "--help"], ["rosrun", "rqt_reconfigure", "rqt_reconfigure", "--help"]):
        helped = subprocess.run([str(BIN / command[0]), *command[1:]], capture_output=True, text=True, timeout=60,
                                env=env)
        assert helped.returncode == 0 and "--standalone" in helped.stdout, (command, helped.stderr)
