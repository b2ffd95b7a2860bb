"""Interactive markers between nodes: the tutorials' servers on kame (rosrun) driven by a
feedback published as rviz publishes it, their update, KEEP_ALIVE and latched update_full as a
client sees them; and Debian's interactive_markers server (ROS 1, 1.12) followed by kame's
client model (rviz's display)."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from collections.abc import Iterator
from pathlib import Path

import pytest

from ..support import SYSTEM_PYTHON, Proc, free_port, have_debian_ros, kame_command, ros_env, wait_for_master
from ..turtlesim.sim import BIN

RVIZ_LIKE_CLIENT = """
    import rospy
    from visualization_msgs.msg import InteractiveMarkerFeedback, InteractiveMarkerInit, InteractiveMarkerUpdate
    from kame.interactive_markers.client_state import ClientState
    rospy.init_node('rviz_like')
    ns = '/simple_marker'
    client = ClientState()
    updates = []
    rospy.Subscriber(ns + '/update', InteractiveMarkerUpdate, lambda m: (updates.append(m), client.update(m)))
    init = rospy.wait_for_message(ns + '/update_full', InteractiveMarkerInit, 30)
    while not init.markers:  # the server's first init, before its marker was applied
        init = rospy.wait_for_message(ns + '/update_full', InteractiveMarkerInit, 30)
    client.init(init)
    print('init', init.server_id, init.seq_num, [m.name for m in init.markers], flush=True)
    print('controls', [(c.name, c.interaction_mode) for c in init.markers[0].controls], flush=True)
    while not rospy.is_shutdown() and not any(u.type == u.KEEP_ALIVE for u in updates):
        rospy.sleep(0.05)
    alive = [u for u in updates if u.type == u.KEEP_ALIVE][0]
    print('keep_alive', alive.server_id, alive.seq_num, flush=True)
    pub = rospy.Publisher(ns + '/feedback', InteractiveMarkerFeedback, queue_size=10)
    feedback = InteractiveMarkerFeedback(client_id='/rviz_like/InteractiveMarkers', marker_name='my_marker',
                                         control_name='move_x', event_type=InteractiveMarkerFeedback.POSE_UPDATE)
    feedback.header.frame_id = 'base_link'
    feedback.pose.position.x, feedback.pose.orientation.w = 2.0, 1.0
    while not rospy.is_shutdown() and pub.get_num_connections() == 0:
        rospy.sleep(0.05)
    pub.publish(feedback)
    rospy.sleep(1.0)
    print('markers', sorted(name for _, name in client.markers), flush=True)
"""

DEBIAN_SERVER = """
    import rospy
    from interactive_markers.interactive_marker_server import InteractiveMarkerServer
    from interactive_markers.menu_handler import MenuHandler
    from visualization_msgs.msg import InteractiveMarker, InteractiveMarkerControl
    rospy.init_node('debian_server')
    server = InteractiveMarkerServer('debian_markers')
    menu = MenuHandler()
    menu.insert('First Entry')
    for index, name in enumerate(('first', 'second')):
        marker = InteractiveMarker(name=name, scale=1.0)
        marker.header.frame_id = 'base_link'
        marker.pose.position.x = float(index)
        marker.pose.orientation.w = 1.0
        marker.controls.append(InteractiveMarkerControl(name='move_x', interaction_mode=3))
        server.insert(marker)
        server.applyChanges()
    menu.apply(server, 'first')
    server.applyChanges()
    pose = marker.pose
    pose.position.y = 4.0
    server.setPose('second', pose)
    server.applyChanges()
    print('served', flush=True)
    rospy.spin()
"""

KAME_CLIENT_OF_DEBIAN = """
    import rospy
    from visualization_msgs.msg import InteractiveMarkerInit, InteractiveMarkerUpdate
    from kame.rviz.interactive import InteractiveMarkers
    rospy.init_node('kame_rviz_model')
    display = InteractiveMarkers(options={'Update Topic': '/debian_markers/update'})
    rospy.Subscriber('/debian_markers/update', InteractiveMarkerUpdate, lambda m: display.receive([m], 0.0))
    init = rospy.wait_for_message('/debian_markers/update_full', InteractiveMarkerInit, 30)
    display.receive_side('/debian_markers/update_full', [init], 0.0)
    rospy.sleep(1.2)  # a KEEP_ALIVE or two
    markers = display.client.markers
    print('seq', display.client.servers['/debian_server'].seq_num, 'problem', repr(display.client.problem), flush=True)
    for (server, name), marker in sorted(markers.items()):
        print(server, name, marker.pose.position.x, marker.pose.position.y,
              [e.title for e in marker.menu_entries], flush=True)
"""


@pytest.fixture()
def env(tmp_path: Path) -> Iterator[dict[str, str]]:
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    environment = ros_env(tmp_path, uri)
    master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), environment)
    try:
        wait_for_master(uri, proc=master)
        yield environment
    finally:
        master.stop()


def test_simple_marker_by_rosrun_serves_and_takes_rvizs_feedback(env: dict[str, str]) -> None:
    server = Proc([str(BIN / "rosrun"), "interactive_marker_tutorials", "simple_marker.py"], env)
    try:
        out = Proc([sys.executable, "-c", textwrap.dedent(RVIZ_LIKE_CLIENT)], env).finish(60)[0]
        assert "init /simple_marker 1 ['my_marker']" in out, out
        assert "controls [('', 0), ('move_x', 3)]" in out
        assert "keep_alive /simple_marker 1" in out
        assert "markers ['my_marker']" in out
        server.wait_line("my_marker is now at 2.0, 0.0, 0.0", timeout=30)
    finally:
        server.stop()


def test_basic_controls_serves_every_marker(env: dict[str, str]) -> None:
    server = Proc([str(BIN / "rosrun"), "interactive_marker_tutorials", "basic_controls.py"], env)
    try:
        out = Proc([sys.executable, "-c", textwrap.dedent("""
            import rospy
            from visualization_msgs.msg import InteractiveMarkerInit
            rospy.init_node('peek')
            init = rospy.wait_for_message('/basic_controls/update_full', InteractiveMarkerInit, 30)
            while not init.markers:
                init = rospy.wait_for_message('/basic_controls/update_full', InteractiveMarkerInit, 30)
            by_name = {m.name: m for m in init.markers}
            print(sorted(by_name))
            print([e.title for e in by_name['context_menu'].menu_entries])
            import numpy as np
            from kame.rviz.interactive import InteractiveMarkers
            from kame.rviz.scene import Scene

            class Frames:  # base_link and moving_frame where they are at the start
                fixed_frame = 'base_link'
                def transform(self, frame_id):
                    return np.eye(4)
                def names(self):
                    return ['base_link', 'moving_frame']
                def parent(self, frame_id):
                    return None

            display = InteractiveMarkers(options={'Update Topic': '/basic_controls/update'})
            display.receive_side('/basic_controls/update_full', [init], 0.0)
            scene = Scene()
            display.build(scene, Frames(), 0.0)
            print('status', display.status.level, display.status.text)
            print('drawn', sum(1 for h in display.handles if len(h.triangles)), 'of', len(display.handles))
        """)], env).finish(60)[0]
        assert "status Ok" in out, out
        # 45 controls, each with something to grab (the menu-only one: rviz's "Options" button)
        drawn, total = (int(n) for n in out.split("drawn ")[1].split()[::2])
        assert (drawn, total) == (45, 45), out
        assert "'button', 'chess_piece', 'context_menu', 'moving', 'pan_tilt', 'quadrocopter'" in out, out
        assert "['First Entry', 'Second Entry', 'Submenu', 'First Entry', 'Second Entry']" in out
    finally:
        server.stop()


def test_debians_server_feeds_kames_display_model(env: dict[str, str]) -> None:
    if not have_debian_ros():
        pytest.skip("Debian's ROS 1 is not installed")
    probe = subprocess.run([SYSTEM_PYTHON, "-c", "import interactive_markers.interactive_marker_server"],
                           capture_output=True, env=env)
    if probe.returncode != 0:
        pytest.skip("Debian's python3-interactive-markers is not installed (scripts/install-ros-peers.sh)")
    server = Proc([SYSTEM_PYTHON, "-c", textwrap.dedent(DEBIAN_SERVER)], env)
    try:
        server.wait_line("served", timeout=30)
        out = Proc([sys.executable, "-c", textwrap.dedent(KAME_CLIENT_OF_DEBIAN)], env).finish(60)[0]
        assert "seq 4 problem ''" in out, out
        assert "/debian_server first 0.0 0.0 ['First Entry']" in out
        assert "/debian_server second 1.0 4.0 []" in out
    finally:
        server.stop()


def test_a_debian_client_moves_kames_marker_and_sees_shutdown_erase_it(env: dict[str, str]) -> None:
    """Debian's rospy (ROS's own visualization_msgs) as rviz's side of the wire: kame's update_full
    read, a POSE_UPDATE published to kame's server, the erase of shutdown() seen."""
    if not have_debian_ros():
        pytest.skip("Debian's ROS 1 is not installed")
    probe = subprocess.run([SYSTEM_PYTHON, "-c", "import visualization_msgs.msg"], capture_output=True, env=env)
    if probe.returncode != 0:
        pytest.skip("Debian's python3-visualization-msgs is not installed (scripts/install-ros-peers.sh)")
    server = Proc([sys.executable, "-c", textwrap.dedent("""
        import rospy
        from interactive_markers.interactive_marker_server import *
        from visualization_msgs.msg import InteractiveMarkerControl
        rospy.init_node('kame_server')
        server = InteractiveMarkerServer('kame_markers')
        marker = InteractiveMarker(name='m', scale=1.0)
        marker.header.frame_id = 'base_link'
        marker.pose.orientation.w = 1.0
        marker.controls.append(InteractiveMarkerControl(name='move_x', interaction_mode=3))
        moved = []
        server.insert(marker, lambda f: moved.append(f) if f.event_type == f.POSE_UPDATE else None)
        server.applyChanges()
        print('serving', server.size(), server.empty(), flush=True)
        while not rospy.is_shutdown() and not moved:
            rospy.sleep(0.05)
        server.applyChanges()
        print('moved', moved[0].client_id, server.get('m').pose.position.y, flush=True)
        rospy.sleep(0.5)
        server.shutdown()
        print('shut down', server.empty(), flush=True)
        rospy.sleep(2.0)
    """)], env)
    try:
        server.wait_line("serving 1 False", timeout=30)
        out = Proc([SYSTEM_PYTHON, "-c", textwrap.dedent("""
            import rospy
            from visualization_msgs.msg import InteractiveMarkerFeedback, InteractiveMarkerInit
            from visualization_msgs.msg import InteractiveMarkerUpdate
            rospy.init_node('debian_rviz')
            updates = []
            rospy.Subscriber('/kame_markers/update', InteractiveMarkerUpdate, updates.append)
            init = rospy.wait_for_message('/kame_markers/update_full', InteractiveMarkerInit, 30)
            print('init', init.server_id, [m.name for m in init.markers], flush=True)
            pub = rospy.Publisher('/kame_markers/feedback', InteractiveMarkerFeedback, queue_size=10)
            while pub.get_num_connections() == 0:
                rospy.sleep(0.05)
            feedback = InteractiveMarkerFeedback(client_id='/debian_rviz/InteractiveMarkers', marker_name='m',
                                                 control_name='move_x', event_type=1)
            feedback.header.frame_id = 'base_link'
            feedback.pose.position.y, feedback.pose.orientation.w = 1.5, 1.0
            pub.publish(feedback)
            deadline = rospy.get_time() + 20
            while rospy.get_time() < deadline and not any(u.erases for u in updates):
                rospy.sleep(0.05)
            print('poses', [(p.name, p.pose.position.y) for u in updates for p in u.poses], flush=True)
            print('erases', [e for u in updates for e in u.erases], flush=True)
            print('keep alive', any(u.type == u.KEEP_ALIVE for u in updates), flush=True)
        """)], env).finish(60)[0]
        assert "init /kame_server ['m']" in out, out
        assert "poses [('m', 1.5)]" in out and "erases ['m']" in out and "keep alive True" in out, out
        server.wait_line("moved /debian_rviz/InteractiveMarkers 1.5", timeout=10)
        server.wait_line("shut down True", timeout=10)
    finally:
        server.stop()
