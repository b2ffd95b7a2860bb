"""The rospy API on kame, exercised as programs use it (each case is a small node process)."""

from __future__ import annotations

import sys
import textwrap
from collections.abc import Iterator
from pathlib import Path

import pytest

from ..support import Proc, free_port, kame_command, ros_env, wait_for_master


@pytest.fixture(scope="module")
def env(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, str]]:
    home = Path(tmp_path_factory.mktemp("rospy_api"))
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    environment = ros_env(home, uri)
    master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), environment)
    try:
        wait_for_master(uri, proc=master)
        yield environment
    finally:
        master.stop()


def run(env: dict[str, str], code: str, *args: str, timeout: float = 30) -> tuple[str, str]:
    return Proc([sys.executable, "-c", textwrap.dedent(code), *args], env).finish(timeout)


def test_names_args_and_private_params(env: dict[str, str]) -> None:
    out, _ = run(env, """
        import rospy
        rospy.init_node('namer', anonymous=True)
        print(rospy.get_name().startswith('/robot/namer_'), rospy.get_namespace())
        print(rospy.resolve_name('chatter'), rospy.resolve_name('~x'), rospy.resolve_name('/abs'))
        print(rospy.myargv())
        print(rospy.get_param('~gain'), rospy.get_param('~list'), rospy.get_param('~flag'))
    """, "__ns:=/robot", "chatter:=talk", "_gain:=1.5", "_list:=[1, 2]", "_flag:=yes", "plain")
    lines = out.splitlines()
    assert lines[0] == "True /robot/"
    assert lines[1].split()[0] == "/robot/talk" and lines[1].split()[2] == "/abs"
    assert lines[2] == "['-c', 'plain']"
    assert lines[3] == "1.5 [1, 2] True"


def test_bad_node_names_get_rospys_errors(env: dict[str, str]) -> None:
    out, _ = run(env, """
        import rospy
        for bad in ('a/b', ''):
            try:
                rospy.init_node(bad)
            except ValueError as e:
                print(e)
    """)
    assert out.splitlines() == ["namespaces are not allowed in node names", "name must not be empty"]


def test_params_and_cached_params(env: dict[str, str]) -> None:
    out, _ = run(env, """
        import rospy, time
        rospy.init_node('params')
        rospy.set_param('/gains', {'p': 1.0, 'i': {'x': 2}})
        print(rospy.get_param('/gains/i/x'), rospy.has_param('/gains/p'), rospy.has_param('/nope'))
        print(rospy.get_param('/nope', 'dflt'), rospy.search_param('gains'))
        try:
            rospy.get_param('/nope')
        except KeyError as e:
            print('KeyError', e)
        print(rospy.get_param_cached('/gains/p'))
        rospy.set_param('/gains/p', 3.0)   # our own change: the master does not tell us ...
        other = rospy.ServiceProxy  # (keep the name)
        import xmlrpc.client, os
        xmlrpc.client.ServerProxy(os.environ['ROS_MASTER_URI']).setParam('/other', '/gains/p', 4.0)
        deadline = time.time() + 5
        while rospy.get_param_cached('/gains/p') != 4.0 and time.time() < deadline:
            time.sleep(0.05)
        print(rospy.get_param_cached('/gains/p'))
        rospy.delete_param('/gains')
        print(sorted(rospy.get_param_names()) == sorted(n for n in rospy.get_param_names()), rospy.has_param('/gains'))
    """)
    lines = out.splitlines()
    assert lines[0] == "2 True False"
    assert lines[1] == "dflt /gains"
    assert lines[2] == "KeyError '/nope'"
    assert lines[3] == "1.0"
    assert lines[4] == "4.0"
    assert lines[5] == "True False"


def test_a_param_update_during_the_first_cached_get_is_kept(env: dict[str, str]) -> None:
    # get_param_cached subscribed, then stored the value subscribeParam returned: a paramUpdate
    # that arrived in between (another node set the parameter) was refused, as nothing was
    # cached yet, and the stale value then stayed in the cache for good.
    out, _ = run(env, """
        import os, threading, xmlrpc.client
        import rospy
        from rospy import core
        rospy.init_node('cached_race')
        rospy.set_param('/race', 'old')
        node = core.get_node()
        updated = threading.Event()
        node.on_param_update.append(lambda key, value: updated.set())
        call = node.master.call

        def slow_reply(method, *args, **kwargs):
            result = call(method, *args, **kwargs)
            if method == 'subscribeParam':  # someone sets it before our reply is stored
                xmlrpc.client.ServerProxy(os.environ['ROS_MASTER_URI']).setParam('/other', '/race', 'new')
                assert updated.wait(10)
            return result

        node.master.call = slow_reply
        print(rospy.get_param_cached('/race'), rospy.get_param_cached('/race'))
    """)
    assert out.splitlines() == ["new new"]


def test_publisher_subscriber_details(env: dict[str, str]) -> None:
    out, _ = run(env, """
        import rospy, threading
        from std_msgs.msg import String, Header
        from rospy_tutorials.msg import HeaderString, Floats
        from rospy.numpy_msg import numpy_msg
        import numpy
        rospy.init_node('details')
        got = {}
        done = threading.Event()
        def cb(msg, tag):
            got.setdefault(tag, []).append(msg)
            if len(got.get('h', [])) >= 2 and got.get('f') and got.get('s'):
                done.set()
        rospy.Subscriber('/h', HeaderString, cb, callback_args='h')
        rospy.Subscriber('/f', numpy_msg(Floats), cb, callback_args='f')
        rospy.Subscriber('/s', rospy.AnyMsg, cb, callback_args='s')
        ph = rospy.Publisher('/h', HeaderString, queue_size=10, headers={'extra': 'yes'})
        pf = rospy.Publisher('/f', numpy_msg(Floats), queue_size=10)
        ps = rospy.Publisher('/s', String, queue_size=10)
        while ph.get_num_connections() < 1 or pf.get_num_connections() < 1 or ps.get_num_connections() < 1:
            rospy.sleep(0.01)
        ph.publish(data='one')
        ph.publish(HeaderString(data='two'))
        pf.publish(Floats(data=numpy.array([1.5, 2.5], dtype=numpy.float32)))
        ps.publish('raw')
        done.wait(5)
        print([m.header.seq for m in got['h']], [m.data for m in got['h']], got['h'][0]._connection_header['extra'])
        print(type(got['f'][0].data).__name__, got['f'][0].data.tolist())
        print(got['s'][0]._buff, got['s'][0]._connection_header['type'])
        try:
            ph.publish(String('wrong'))
        except Exception as e:
            print(type(e).__name__)
        ph.unregister()
        try:
            ph.publish(data='x')
        except rospy.ROSException as e:
            print(e)
    """)
    lines = out.splitlines()
    assert lines[0] == "[1, 2] ['one', 'two'] yes"
    assert lines[1] == "ndarray [1.5, 2.5]"
    assert lines[2] == "b'\\x03\\x00\\x00\\x00raw' std_msgs/String"
    assert lines[3] == "ROSSerializationException"
    assert lines[4] == "publish() to an unregistered() handle"


def test_wait_for_message_timer_and_logging_variants(env: dict[str, str]) -> None:
    out, err = run(env, """
        import rospy, threading
        from std_msgs.msg import String
        rospy.init_node('misc', log_level=rospy.DEBUG)
        p = rospy.Publisher('/once', String, queue_size=1, latch=True)
        p.publish('latched')
        print(rospy.wait_for_message('/once', String, timeout=5).data)
        try:
            rospy.wait_for_message('/never', String, timeout=0.2)
        except rospy.ROSException as e:
            print(e)
        ticks = []
        t = rospy.Timer(rospy.Duration(0.02), lambda ev: ticks.append(ev.current_real))
        rospy.sleep(0.3)
        t.shutdown()
        print(len(ticks) >= 5)
        for i in range(5):
            rospy.logwarn_once('only once')
            rospy.loginfo_throttle(60, 'throttled %d', i)
            rospy.logdebug('debug %d', i)
        rate = rospy.Rate(100)
        start = rospy.get_time()
        for _ in range(10):
            rate.sleep()
        print(0.08 < rospy.get_time() - start < 0.5, rospy.Time.now() > rospy.Time(1000))
    """)
    lines = out.splitlines()
    assert lines[0] == "latched"
    assert lines[1] == "timeout exceeded while waiting for message on topic /never"
    assert lines[2] == "True"
    assert lines[-1] == "True True"
    assert err.count("only once") == 1
    assert out.count("throttled") == 1 and "throttled 0" in out
    assert out.count("[DEBUG]") >= 5
    assert "[WARN] [" in err


def test_a_latched_message_that_comes_with_the_handshake_reaches_the_callback(env: dict[str, str]) -> None:
    # Under load the latched message arrives in the same read as the publisher's header, so it
    # is delivered the moment the connection starts: forced here by holding subscribe() until
    # then. The callback must already be in place (it once was added after, and missed it).
    # Publisher and subscriber share the process: intra-process delivery is off to keep TCPROS.
    out, _ = run({**env, "KAME_INTRAPROCESS": "0"}, """
        import threading
        import rospy
        from kame.node import topics
        from std_msgs.msg import String
        rospy.init_node('handshake_latch')
        delivered = threading.Event()
        deliver, set_publishers = topics.Subscription.deliver, topics.Subscription.set_publishers
        topics.Subscription.deliver = lambda self, *a: (deliver(self, *a), delivered.set())
        topics.Subscription.set_publishers = lambda self, uris: (set_publishers(self, uris), delivered.wait(5))
        rospy.Publisher('/early', String, latch=True, queue_size=1).publish('first')
        got = threading.Event()
        rospy.Subscriber('/early', String, lambda msg: (print(msg.data), got.set()))
        print(delivered.is_set(), got.wait(5))
    """)
    assert out.splitlines() == ["first", "True True"]


def test_a_second_subscriber_gets_the_latched_message_too(env: dict[str, str]) -> None:
    # rospy's #1852: a callback added to a topic this process already subscribes to is given
    # each connected latching publisher's last message.
    out, _ = run(env, """
        import threading
        import rospy
        from std_msgs.msg import String
        rospy.init_node('second_latch')
        rospy.Publisher('/kept', String, latch=True, queue_size=1).publish('kept')
        first = threading.Event()
        rospy.Subscriber('/kept', String, lambda msg: first.set())
        print(first.wait(5))
        second = threading.Event()
        rospy.Subscriber('/kept', String, lambda msg, arg: (print(msg.data, arg), second.set()), 'B')
        print(second.wait(5))
    """)
    assert out.splitlines() == ["True", "kept B", "True"]


def test_a_subscribe_listener_hears_of_a_subscriber_that_connects_at_once(env: dict[str, str]) -> None:
    # A subscriber already waiting connects as soon as the master hears of the publisher: forced
    # here by holding advertise() until it has. The listener must already be in place.
    out, _ = run(env, """
        import threading, time
        import rospy
        from kame.node.node import Node
        from std_msgs.msg import String
        rospy.init_node('early_listener')
        heard = []
        rospy.Subscriber('/listened', String, lambda msg: heard.append(msg.data))
        advertise = Node.advertise
        def held(self, *args):
            pub = advertise(self, *args)
            deadline = time.monotonic() + 5
            while not pub.links and time.monotonic() < deadline:
                time.sleep(0.01)
            return pub
        Node.advertise = held

        class Listener(rospy.SubscribeListener):
            def peer_subscribe(self, topic, publish, peer_publish):
                print('peer_subscribe', topic, flush=True)
                peer_publish(String('hello you'))

        rospy.Publisher('/listened', String, subscriber_listener=Listener(), queue_size=1)
        deadline = time.monotonic() + 5
        while not heard and time.monotonic() < deadline:
            time.sleep(0.01)
        print(heard)
    """)
    assert out.splitlines() == ["peer_subscribe /listened", "['hello you']"]


def test_simulated_time_follows_clock(env: dict[str, str]) -> None:
    out, _ = run(env, """
        import rospy, threading, time, os, subprocess, sys
        from rosgraph_msgs.msg import Clock
        import xmlrpc.client
        xmlrpc.client.ServerProxy(os.environ['ROS_MASTER_URI']).setParam('/t', '/use_sim_time', True)
        rospy.init_node('simtime')
        print(rospy.get_time())
        pub = rospy.Publisher('/clock', Clock, queue_size=10)
        while pub.get_num_connections() < 1:
            time.sleep(0.01)
        pub.publish(Clock(rospy.Time(100, 5)))
        deadline = time.time() + 5
        while rospy.get_time() == 0 and time.time() < deadline:
            time.sleep(0.01)
        print(rospy.Time.now().secs, rospy.Time.now().nsecs)
        woke = []
        threading.Thread(target=lambda: (rospy.sleep(2.0), woke.append(rospy.get_time())), daemon=True).start()
        time.sleep(0.2)
        pub.publish(Clock(rospy.Time(103)))
        deadline = time.time() + 5
        while not woke and time.time() < deadline:
            time.sleep(0.01)
        print(woke)
        xmlrpc.client.ServerProxy(os.environ['ROS_MASTER_URI']).setParam('/t', '/use_sim_time', False)
    """)
    assert out.splitlines() == ["0.0", "100 5", "[103.0]"]
