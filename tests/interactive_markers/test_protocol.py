"""interactive_markers' protocol as pure code: the server's update/init sequencing, erases,
poses and feedback callbacks; the client's init-then-updates order and gaps; the menu model."""

from __future__ import annotations

from typing import Any

from kame.interactive_markers.client_state import ClientState
from kame.interactive_markers.menu import MenuHandler
from kame.interactive_markers.server_state import ServerState
from visualization_msgs.msg import (
    InteractiveMarker,
    InteractiveMarkerFeedback,
    InteractiveMarkerInit,
    InteractiveMarkerUpdate,
    MenuEntry,
)


def _marker(name: str, x: float = 0.0) -> Any:
    marker = InteractiveMarker(name=name, scale=1.0)
    marker.header.frame_id = "base_link"
    marker.pose.position.x = x
    marker.pose.orientation.w = 1.0
    return marker


def test_changes_wait_for_apply_and_each_update_counts() -> None:
    server = ServerState("/node")
    server.insert(_marker("a"))
    assert server.size() == 0 and server.get("a").name == "a"
    update = server.apply_changes()
    assert (update.type, update.seq_num, update.server_id) == (InteractiveMarkerUpdate.UPDATE, 1, "/node")
    assert [m.name for m in update.markers] == ["a"] and server.apply_changes() is None
    pose = _marker("a", 2.0).pose
    assert server.set_pose("a", pose) and not server.set_pose("nobody", pose)
    update = server.apply_changes()
    assert update.seq_num == 2 and [(p.name, p.pose.position.x, p.header.frame_id) for p in update.poses] == [
        ("a", 2.0, "base_link")]
    init = server.init_message()
    assert (init.seq_num, [m.pose.position.x for m in init.markers]) == (2, [2.0])
    keep_alive = server.keep_alive()
    assert (keep_alive.type, keep_alive.seq_num) == (InteractiveMarkerUpdate.KEEP_ALIVE, 2)
    assert server.erase("a") and server.get("a") is None
    update = server.apply_changes()
    assert update.erases == ["a"] and server.size() == 0 and not server.init_message().markers


def test_feedback_moves_the_marker_and_calls_the_types_callback_first() -> None:
    server = ServerState("/node")
    calls: list[tuple[str, int]] = []
    server.insert(_marker("a"), lambda f: calls.append(("default", f.event_type)))
    server.set_callback("a", lambda f: calls.append(("click", f.event_type)), InteractiveMarkerFeedback.BUTTON_CLICK)
    server.apply_changes()
    feedback = InteractiveMarkerFeedback(client_id="/rviz/IM", marker_name="a",
                                         event_type=InteractiveMarkerFeedback.POSE_UPDATE)
    feedback.pose.position.x, feedback.pose.orientation.w = 3.0, 1.0
    feedback.header.frame_id = "elsewhere"
    server.feedback(feedback, 10.0)(feedback)
    update = server.apply_changes()
    # a marker stamped 0 keeps its own frame: the feedback's pose is taken as in it
    assert [(p.pose.position.x, p.header.frame_id) for p in update.poses] == [(3.0, "base_link")]
    click = InteractiveMarkerFeedback(client_id="/rviz/IM", marker_name="a",
                                      event_type=InteractiveMarkerFeedback.BUTTON_CLICK)
    server.feedback(click, 10.1)(click)
    other = InteractiveMarkerFeedback(client_id="/other", marker_name="a", event_type=click.event_type)
    assert server.feedback(other, 10.5) is None  # another client within the second: ignored
    assert server.feedback(other, 11.2) is not None
    assert calls == [("default", 1), ("click", 3)]
    assert server.feedback(InteractiveMarkerFeedback(marker_name="gone"), 20.0) is None


def test_the_client_applies_init_then_the_updates_after_it_and_waits_after_a_gap() -> None:
    server, client = ServerState("/s"), ClientState()
    server.insert(_marker("a"))
    first = server.apply_changes()
    server.insert(_marker("b"))
    second = server.apply_changes()
    client.update(first)
    client.update(second)
    assert client.markers == {}  # nothing before the init
    client.init(InteractiveMarkerInit(server_id="/s", seq_num=1, markers=[_marker("a")]))
    assert sorted(name for _, name in client.markers) == ["a", "b"]
    server.erase("a")
    client.update(server.apply_changes())
    assert sorted(name for _, name in client.markers) == ["b"]
    server.set_pose("b", _marker("b", 5.0).pose)
    server.apply_changes()  # lost
    server.insert(_marker("c"))
    client.update(server.apply_changes())
    assert "expected update 4, got 5" in client.problem
    assert sorted(name for _, name in client.markers) == ["b"]  # waiting for a new init
    client.init(server.init_message())
    assert sorted(name for _, name in client.markers) == ["b", "c"]
    assert client.markers[("/s", "b")].pose.position.x == 5.0
    client.update(server.keep_alive())
    assert client.servers["/s"].seq_num == 5


def test_the_menu_handler_writes_entries_and_routes_menu_select() -> None:
    server, menu = ServerState("/s"), MenuHandler()
    chosen: list[int] = []
    first = menu.insert("First Entry", callback=lambda f: chosen.append(f.menu_entry_id))
    sub = menu.insert("Submenu")
    inner = menu.insert("Inner", parent=sub, callback=lambda f: chosen.append(f.menu_entry_id))
    hidden = menu.insert("Hidden")
    assert menu.insert("orphan", parent=99) is None
    menu.setCheckState(first, MenuHandler.CHECKED)
    menu.setVisible(hidden, False)
    server.insert(_marker("a"))
    assert menu.apply(server, "a") and not menu.apply(server, "nobody")
    update = server.apply_changes()
    entries = [(e.id, e.parent_id, e.title, e.command_type) for e in update.markers[0].menu_entries]
    assert entries == [(1, 0, "[x] First Entry", MenuEntry.FEEDBACK), (2, 0, "Submenu", 0), (3, 2, "Inner", 0)]
    for entry in (inner, first):
        select = InteractiveMarkerFeedback(marker_name="a", menu_entry_id=entry,
                                           event_type=InteractiveMarkerFeedback.MENU_SELECT)
        server.feedback(select, 100.0 + entry)(select)
    assert chosen == [3, 1] and menu.getCheckState(first) == MenuHandler.CHECKED
