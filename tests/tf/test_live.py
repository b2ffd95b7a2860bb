"""tf2_ros and tf on a running graph: kame programs broadcasting and listening, and interop with
Debian's real tf2 both ways (its C++ static_transform_publisher and Python broadcaster feeding
kame's Buffer; kame's broadcasters feeding Debian's tf2_ros listener and tf_echo). Every
process is stopped by its PID."""

from __future__ import annotations

import subprocess
import sys
import xmlrpc.client
from pathlib import Path

from .graph import DEBIAN_STATIC, DEBIAN_TF_ECHO, Graph, debian

TF2_BROADCASTER = """
    import math, sys, rospy, tf2_ros
    from geometry_msgs.msg import TransformStamped
    rospy.init_node('mover')
    moving = tf2_ros.TransformBroadcaster()
    def fixed(child, parent, x):
        t = TransformStamped()
        t.header.stamp = rospy.Time.now()
        t.header.frame_id, t.child_frame_id = parent, child
        t.transform.translation.x = x
        t.transform.rotation.w = 1.0
        return t
    # three static broadcasters in one process: all transforms stay in the one latched message,
    # the later laser replacing the earlier
    tf2_ros.StaticTransformBroadcaster().sendTransform([fixed('laser', 'base', 0.1)])
    tf2_ros.StaticTransformBroadcaster().sendTransform(fixed('camera', 'base', 0.5))
    static = tf2_ros.StaticTransformBroadcaster()
    static.sendTransform(fixed('laser', 'base', 0.25))
    rate = rospy.Rate(50)
    while not rospy.is_shutdown():
        t = fixed('base', 'world', 1.0)
        t.transform.rotation.z, t.transform.rotation.w = math.sin(0.5), math.cos(0.5)
        moving.sendTransform(t)
        rate.sleep()
"""

TF2_LISTENER = """
    import rospy, tf2_ros, tf2_geometry_msgs
    from geometry_msgs.msg import PointStamped
    from tf2_msgs.srv import FrameGraph
    rospy.init_node('looker')
    buffer = tf2_ros.Buffer()
    listener = tf2_ros.TransformListener(buffer)
    t = buffer.lookup_transform('world', 'laser', rospy.Time(0), rospy.Duration(10))
    print('laser', round(t.transform.translation.x, 6), round(t.transform.translation.y, 6), t.header.frame_id,
          t.child_frame_id, flush=True)
    c = buffer.lookup_transform('base', 'camera', rospy.Time(0), rospy.Duration(10))
    print('camera', c.transform.translation.x, flush=True)
    p = PointStamped()
    p.header.frame_id = 'camera'
    p.point.x = 1.0
    q = buffer.transform(p, 'base', rospy.Duration(5))
    print('point', q.header.frame_id, q.point.x, flush=True)
    try:
        buffer.lookup_transform('world', 'nowhere', rospy.Time(0), rospy.Duration(0.2))
    except tf2_ros.LookupException as e:
        print('lookup', e, flush=True)
    try:
        buffer.lookup_transform('world', 'laser', rospy.Time.now() + rospy.Duration(100), rospy.Duration(0.2))
    except tf2_ros.ExtrapolationException as e:
        print('extrapolation', str(e).split('.')[0], flush=True)
    yaml = rospy.ServiceProxy('/looker/tf2_frames', FrameGraph)().frame_yaml
    print(sorted(line for line in yaml.splitlines() if not line.startswith(' ')), yaml.count("broadcaster: '/mover'"),
          flush=True)
    print(buffer.all_frames_as_string(), flush=True)
"""


def test_kame_broadcasters_feed_kame_listener(graph: Graph) -> None:
    graph.kame(TF2_BROADCASTER)
    out = graph.finish(graph.kame(TF2_LISTENER))
    lines = out.splitlines()
    assert lines[0] == f"laser {1.0 + 0.25 * (1 - 2 * 0.479425538604203 ** 2):.6f} " \
        f"{0.25 * 2 * 0.479425538604203 * 0.8775825618903728:.6f} world laser"
    assert lines[1] == "camera 0.5"
    assert lines[2] == "point base 1.5"
    assert lines[3] == 'lookup "nowhere" passed to lookupTransform argument source_frame does not exist. '
    assert lines[4].startswith("extrapolation Lookup would require extrapolation 9")
    assert lines[5] == "['base: ', 'camera: ', 'laser: '] 3"
    assert {"Frame base exists with parent world.", "Frame laser exists with parent base.",
            "Frame camera exists with parent base."} <= set(lines[5:])


def test_tf_first_api_and_frames_service(graph: Graph) -> None:
    graph.kame("""
        import rospy, tf, math
        rospy.init_node('old_style')
        b = tf.TransformBroadcaster()
        rate = rospy.Rate(50)
        while not rospy.is_shutdown():
            b.sendTransform((2.0, 0.0, 0.0), tf.transformations.quaternion_from_euler(0, 0, math.pi / 2),
                            rospy.Time.now(), '/turtle', 'world')
            rate.sleep()
    """)
    out = graph.finish(graph.kame("""
        import rospy, tf
        from geometry_msgs.msg import PointStamped
        rospy.init_node('old_listener')
        listener = tf.TransformListener()
        listener.waitForTransform('/world', '/turtle', rospy.Time(), rospy.Duration(10))
        trans, rot = listener.lookupTransform('/world', '/turtle', rospy.Time(0))
        print([round(v, 6) for v in trans], [round(v, 6) for v in rot])
        p = PointStamped()
        p.header.frame_id = 'turtle'
        p.point.x = 1.0
        q = listener.transformPoint('world', p)
        print(q.header.frame_id, round(q.point.x, 6), round(q.point.y, 6))
        print(listener.frameExists('turtle'), listener.canTransform('world', 'turtle', rospy.Time(0)))
        try:
            listener.waitForTransform('world', 'ghost', rospy.Time(), rospy.Duration(0.2))
        except tf.Exception as e:
            print('timeout', e)
    """))
    lines = out.splitlines()
    assert lines[0] == "[2.0, 0.0, 0.0] [0.0, 0.0, 0.707107, 0.707107]"
    assert lines[1] == "world 2.0 1.0"
    assert lines[2] == "True True"
    assert lines[3] == "timeout canTransform: source_frame ghost does not exist."


@debian
def test_debian_publishers_feed_kame_buffer(graph: Graph) -> None:
    graph.start([DEBIAN_STATIC, "1", "2", "3", "0", "0", "0", "base", "sensor"])
    graph.start([DEBIAN_STATIC, "0", "0", "0.5", "0", "0", "0", "1", "world", "base", "__name:=second"])
    graph.real("""
        import rospy, tf2_ros
        from geometry_msgs.msg import TransformStamped
        rospy.init_node('debian_mover')
        b = tf2_ros.TransformBroadcaster()
        rate = rospy.Rate(50)
        while not rospy.is_shutdown():
            t = TransformStamped()
            t.header.stamp = rospy.Time.now()
            t.header.frame_id, t.child_frame_id = 'world', 'robot'
            t.transform.translation.y = 4.0
            t.transform.rotation.w = 1.0
            b.sendTransform(t)
            rate.sleep()
    """)
    out = graph.finish(graph.kame("""
        import rospy, tf2_ros
        rospy.init_node('kame_looker')
        buffer = tf2_ros.Buffer()
        tf2_ros.TransformListener(buffer)
        for target, source in (('world', 'sensor'), ('robot', 'sensor')):
            t = buffer.lookup_transform(target, source, rospy.Time(0), rospy.Duration(10)).transform.translation
            print(target, source, round(t.x, 6), round(t.y, 6), round(t.z, 6), flush=True)
        print(buffer.all_frames_as_yaml().count('broadcaster'), 'debian_mover' in buffer.all_frames_as_yaml())
    """))
    assert out.splitlines() == ["world sensor 1.0 2.0 3.5", "robot sensor 1.0 -2.0 3.5", "3 True"]


@debian
def test_kame_broadcasters_feed_debian_listener_and_tf_echo(graph: Graph) -> None:
    graph.kame(TF2_BROADCASTER)
    out = graph.finish(graph.real(TF2_LISTENER))
    lines = out.splitlines()
    assert lines[1:3] == ["camera 0.5", "point base 1.5"]
    assert lines[0].endswith("world laser")
    echo = graph.start([DEBIAN_TF_ECHO, "base", "camera"])
    echo.wait_line("- Translation: [0.500, 0.000, 0.000]", timeout=20)


BUFFER_CLIENT = """
    import rospy, tf2_ros
    rospy.init_node('asker')
    client = tf2_ros.BufferClient('tf2_buffer_server')
    print(client.wait_for_server(rospy.Duration(20)), flush=True)
    t = client.lookup_transform('world', 'base', rospy.Time(0), rospy.Duration(10)).transform.translation
    print('base', t.x, t.y, t.z, flush=True)
    for target, source in (('world', 'nowhere'), ('world', '')):
        try:
            client.lookup_transform(target, source, rospy.Time(0), rospy.Duration(0.3))
        except tf2_ros.TransformException as e:
            print(type(e).__name__, e, flush=True)
    print(client.can_transform('world', 'base', rospy.Time(0)), flush=True)
"""
BUFFER_SERVER = str(Path(__file__).resolve().parents[2] / "src/kame/share/tf2_ros/nodes/buffer_server")
DEBIAN_BUFFER_SERVER = "/usr/lib/tf2_ros/buffer_server"
EXPECTED_ANSWERS = [
    "True", "base 0.0 0.0 0.5",
    'LookupException "nowhere" passed to lookupTransform argument source_frame does not exist. ',
    "InvalidArgumentException Invalid argument passed to lookupTransform argument source_frame in tf2 frame_ids "
    "cannot be empty", "True",
]


def test_buffer_client_and_server(graph: Graph) -> None:
    graph.start([sys.executable, "-m", "kame.cli.rosrun", "tf2_ros", "static_transform_publisher",
                 "0", "0", "0.5", "0", "0", "0", "world", "base"])
    graph.start([sys.executable, BUFFER_SERVER])
    assert graph.finish(graph.kame(BUFFER_CLIENT)).splitlines() == EXPECTED_ANSWERS


@debian
def test_buffer_client_and_server_with_debian(graph: Graph) -> None:
    graph.start([DEBIAN_STATIC, "0", "0", "0.5", "0", "0", "0", "world", "base"])
    graph.start([DEBIAN_BUFFER_SERVER])
    assert graph.finish(graph.kame(BUFFER_CLIENT)).splitlines() == EXPECTED_ANSWERS
    graph.procs.pop().stop()
    graph.procs.pop().stop()
    graph.start([sys.executable, BUFFER_SERVER])
    assert graph.finish(graph.real(BUFFER_CLIENT)).splitlines() == EXPECTED_ANSWERS


SIM_CLOCK_THAT_JUMPS_BACK = """
    import threading, rospy
    from geometry_msgs.msg import TransformStamped
    from rosgraph_msgs.msg import Clock
    from tf2_msgs.msg import TFMessage
    rospy.init_node('looping_bag')
    clock = rospy.Publisher('/clock', Clock, queue_size=100)
    tf = rospy.Publisher('/tf', TFMessage, queue_size=100)
    pause = threading.Event()
    while not (clock.get_num_connections() and tf.get_num_connections()):
        pause.wait(0.05)
    # rosbag play --loop: sim time runs 100 -> 101 s, then starts again at 50 s
    for start in (100.0, 50.0):
        for step in range(21):
            now = rospy.Time.from_sec(start + 0.05 * step)
            clock.publish(Clock(clock=now))
            t = TransformStamped()
            t.header.stamp, t.header.frame_id, t.child_frame_id = now, 'odom', 'base'
            t.transform.translation.x, t.transform.rotation.w = start, 1.0
            tf.publish(TFMessage(transforms=[t]))
            pause.wait(0.05)
    pause.wait(60)
"""


def test_a_clock_jumping_back_clears_the_listeners_buffer(graph: Graph) -> None:
    """Sim time going back (a bag played in a loop) clears a live TransformListener's buffer, as
    tf2_ros's does, with its warning: the old stamps are gone and the new ones are looked up."""
    xmlrpc.client.ServerProxy(graph.uri).setParam("/test", "/use_sim_time", True)
    listener = graph.kame("""
        import rospy, tf2_ros
        rospy.init_node('looker')
        buffer = tf2_ros.Buffer()
        tf2_ros.TransformListener(buffer)
        first = buffer.lookup_transform('odom', 'base', rospy.Time.from_sec(100.5), rospy.Duration(30))
        print('before', first.transform.translation.x, flush=True)
        later = buffer.lookup_transform('odom', 'base', rospy.Time.from_sec(50.5), rospy.Duration(30))
        print('after', later.transform.translation.x, flush=True)
        print('old stamp', buffer.can_transform('odom', 'base', rospy.Time.from_sec(100.5)), flush=True)
    """)
    graph.kame(SIM_CLOCK_THAT_JUMPS_BACK)
    try:
        listener.popen.wait(60)
    except subprocess.TimeoutExpired:
        pass
    out, err = listener.stop()
    assert out.splitlines() == ["before 100.0", "after 50.0", "old stamp False"], err
    assert "Detected jump back in time" in err
