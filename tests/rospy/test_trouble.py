"""Behaviour under trouble: slow subscribers, failing callbacks, a master that goes away."""

from __future__ import annotations

import sys
import textwrap
import time
from pathlib import Path

from ..support import Proc, free_port, kame_command, ros_env, wait_for_master


def start_master(home: Path, port: int) -> Proc:
    env = ros_env(home, f"http://127.0.0.1:{port}/")
    master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), env)
    wait_for_master(f"http://127.0.0.1:{port}/", proc=master)
    return master


def node(home: Path, port: int, code: str) -> Proc:
    return Proc([sys.executable, "-c", textwrap.dedent(code)], ros_env(home, f"http://127.0.0.1:{port}/"))


def test_a_slow_subscriber_blocks_neither_the_publisher_nor_others(tmp_path: Path) -> None:
    port = free_port()
    master = start_master(tmp_path, port)
    slow = fast = None
    try:
        slow = node(tmp_path, port, """
            import rospy, time
            from std_msgs.msg import String
            rospy.init_node('slow')
            rospy.Subscriber('/burst', String, lambda m: time.sleep(0.5), queue_size=1)
            print('ready', flush=True)
            rospy.spin()
        """)
        fast = node(tmp_path, port, """
            import rospy
            from std_msgs.msg import String
            got = []
            rospy.init_node('fast')
            rospy.Subscriber('/burst', String, lambda m: got.append(m.data), queue_size=5000)
            print('ready', flush=True)
            while not rospy.is_shutdown() and len(got) < 3000:
                rospy.sleep(0.01)
            print('fast got', len(got), got[-1], flush=True)
        """)
        slow.wait_line("ready")
        fast.wait_line("ready")
        out, _ = run_publisher(tmp_path, port)
        assert out.splitlines()[-1].startswith("published 3000 in ")
        seconds = float(out.split()[-1])
        assert seconds < 2.0, out  # the slow subscriber's 0.5 s callbacks did not hold it up
        assert fast.wait_line("fast got 3000 2999")
    finally:
        for proc in (slow, fast):
            if proc is not None:
                proc.stop()
        master.stop()


def run_publisher(home: Path, port: int) -> tuple[str, str]:
    pub = node(home, port, """
        import rospy, time
        from std_msgs.msg import String
        rospy.init_node('bursty')
        p = rospy.Publisher('/burst', String, queue_size=100)
        while p.get_num_connections() < 2:
            rospy.sleep(0.01)
        start = time.monotonic()
        for i in range(3000):
            p.publish(str(i))
        print('published 3000 in %.3f' % (time.monotonic() - start), flush=True)
        rospy.sleep(1.0)
    """)
    pub.popen.wait(30)
    return pub.stop()


def test_a_failing_callback_is_logged_and_the_subscription_goes_on(tmp_path: Path) -> None:
    port = free_port()
    master = start_master(tmp_path, port)
    try:
        proc = node(tmp_path, port, """
            import rospy
            from std_msgs.msg import Int32
            rospy.init_node('fragile')
            seen = []
            def callback(msg):
                seen.append(msg.data)
                if msg.data == 1:
                    raise RuntimeError('boom on one')
            rospy.Subscriber('/numbers', Int32, callback)
            pub = rospy.Publisher('/numbers', Int32, queue_size=10)
            while pub.get_num_connections() < 1:
                rospy.sleep(0.01)
            for i in range(3):
                pub.publish(i)
            while len(seen) < 3 and not rospy.is_shutdown():
                rospy.sleep(0.01)
            print('seen', seen, flush=True)
        """)
        proc.popen.wait(30)
        out, err = proc.stop()
        assert "seen [0, 1, 2]" in out
        assert "bad callback: <function callback" in err
        assert "RuntimeError: boom on one" in err
        assert "Traceback (most recent call last)" in err
    finally:
        master.stop()


def test_the_master_going_away_and_back_does_not_crash_a_node(tmp_path: Path) -> None:
    port = free_port()
    master = start_master(tmp_path, port)
    proc = node(tmp_path, port, """
        import rospy
        from std_msgs.msg import String
        rospy.init_node('survivor')
        got = []
        rospy.Subscriber('/loop', String, lambda m: got.append(m.data))
        pub = rospy.Publisher('/loop', String, queue_size=10)
        while pub.get_num_connections() < 1:
            rospy.sleep(0.01)
        print('connected', flush=True)
        i = 0
        while not rospy.is_shutdown():
            pub.publish(str(i)); i += 1
            print('got', len(got), flush=True)
            try:
                rospy.get_param('/anything', 0)
                print('param ok', flush=True)
            except Exception as e:
                print('param failed', type(e).__name__, flush=True)
            rospy.sleep(0.05)
    """)
    try:
        proc.wait_line("connected")
        master.stop()
        deadline = time.monotonic() + 10
        while "param failed" not in "".join(proc.out) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert "param failed" in "".join(proc.out)
        count = len(proc.out)
        master = start_master(tmp_path, port)
        deadline = time.monotonic() + 10
        while "param ok" not in "".join(proc.out[count:]) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert "param ok" in "".join(proc.out[count:])
        time.sleep(0.3)
        assert proc.popen.poll() is None
        got = [int(line.split()[1]) for line in proc.out if line.startswith("got ")]
        assert got and got[-1] > got[0], "".join(proc.out[-20:]) + "".join(proc.err)  # kept flowing
        assert "Traceback" not in "".join(proc.err)
    finally:
        proc.stop()
        master.stop()


def test_an_undeserializable_message_is_skipped_and_the_connection_kept(tmp_path: Path) -> None:
    # One bad frame from a publisher used to end the connection for good ("no retry"), losing the
    # good messages that came with it in the same read and every one after it. rospy logs and
    # reads on; so do we now, logging the first failure per publisher, not a line per message.
    import socket
    import struct
    import threading

    from kame.node.node import Node, NodeConfig
    from kame.protocol import tcpros
    from std_msgs.msg import String

    port = free_port()
    master = start_master(tmp_path, port)
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(1)
    liar = Node(NodeConfig("/liar", f"http://127.0.0.1:{port}/", "127.0.0.1"))
    proc = None
    try:
        proc = node(tmp_path, port, """
            import rospy
            from std_msgs.msg import String
            rospy.init_node('reader')
            rospy.Subscriber('/mixed', String, lambda msg: print('got', msg.data, flush=True))
            print('ready', flush=True)
            rospy.spin()
        """)
        proc.wait_line("ready")

        def good(text: str) -> bytes:
            return tcpros.encode_frame(struct.pack("<I", len(text)) + text.encode())

        bad = tcpros.encode_frame(struct.pack("<I", 1000) + b"abc")  # claims 1000 bytes, has 3

        def serve() -> None:
            conn, _ = server.accept()
            conn.recv(65536)
            conn.sendall(tcpros.encode_header(tcpros.publisher_reply_fields(
                callerid="/liar", topic="/mixed", spec=tcpros.TopicSpec("std_msgs/String", String._md5sum))))
            conn.sendall(good("a") + bad + good("b") + bad + bad)  # one read: good ones around bad ones
            time.sleep(0.3)
            conn.sendall(bad + good("c"))
            time.sleep(5)
            conn.close()

        threading.Thread(target=serve, daemon=True).start()
        # requestTopic points at the fake server: set before advertising, since the reader asks
        # as soon as the master tells it about the publisher, which can be before advertise returns
        liar.tcpros_port = server.getsockname()[1]
        liar.advertise("/mixed", "std_msgs/String", String._md5sum, String._full_text)
        proc.wait_line("got c", timeout=10)
        out, err = proc.stop()
        assert [line.split()[1] for line in out.splitlines() if line.startswith("got")] == ["a", "b", "c"]
        assert sum("cannot deserialize" in line for line in err.splitlines()) == 1, err
        assert "/liar" in err and "std_msgs/String" in err
        assert "Traceback" not in err
    finally:
        if proc is not None:
            proc.stop()
        liar.shutdown("test over")
        server.close()
        master.stop()


def test_a_private_parameter_argument_that_is_an_alias_bomb_is_refused(tmp_path: Path) -> None:
    # `_p:=...` was loaded with plain yaml.safe_load and sent: 9 levels of 9 aliases never finished.
    port = free_port()
    master = start_master(tmp_path, port)
    try:
        levels = ["l0: &l0 [" + ", ".join(["x"] * 9) + "]"]
        levels += [f"l{n}: &l{n} [{', '.join([f'*l{n - 1}'] * 9)}]" for n in range(1, 9)]
        bomb = "{" + ", ".join(levels) + "}"
        proc = Proc([sys.executable, "-c", "import rospy; rospy.init_node('bombed')", f"_p:={bomb}"],
                    ros_env(tmp_path, f"http://127.0.0.1:{port}/"))
        assert proc.popen.wait(30) == 1
        _, err = proc.stop()
        # one line, as a bad command-line option gets: the traceback said nothing more
        assert err.splitlines() == [err.strip()], err
        assert err.startswith("[ERROR] invalid command-line parameters: ~p: YAML aliases expand this value to"), err
        # rospy's ROSInitException all the same, for a program that catches it
        caught = Proc([sys.executable, "-c", "import rospy\ntry:\n    rospy.init_node('bombed')\n"
                       "except rospy.ROSInitException as e:\n    print('caught', e)", f"_p:={bomb}"],
                      ros_env(tmp_path, f"http://127.0.0.1:{port}/"))
        assert caught.popen.wait(30) == 0
        out, err = caught.stop()
        assert out.startswith("caught invalid command-line parameters: ~p: YAML aliases"), out + err
    finally:
        master.stop()


def test_an_anymsg_subscriber_joins_a_typed_subscription_of_its_topic(tmp_path: Path) -> None:
    # rostopic hz /clock under /use_sim_time: the node's clock subscribes /clock typed, hz with
    # AnyMsg; rospy shares one subscription, kame refused the second with ROSException
    port = free_port()
    master = start_master(tmp_path, port)
    code = ("import threading, rospy\nfrom rosgraph_msgs.msg import Clock\nrospy.init_node('joiner')\n"
            "typed, anything = threading.Event(), threading.Event()\n"
            "rospy.Subscriber('/c', Clock, lambda m: typed.set())\n"
            "rospy.Subscriber('/c', rospy.AnyMsg, lambda m: anything.set())\n"
            "rospy.Publisher('/c', Clock, queue_size=1, latch=True).publish(Clock())\n"
            "print(typed.wait(20), anything.wait(20), flush=True)\n")
    try:
        proc = Proc([sys.executable, "-c", code], ros_env(tmp_path, f"http://127.0.0.1:{port}/"))
        assert proc.popen.wait(30) == 0
        out, err = proc.stop()
        assert out.strip() == "True True", out + err
    finally:
        master.stop()
