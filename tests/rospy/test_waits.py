"""rospy's blocking waits end on what they wait for or on shutdown, whichever comes first (one
event each, no polling): wait_for_message, spin and on_shutdown hooks with either shape; and
after shutdown no thread is left running, an action server's included."""

from __future__ import annotations

import sys
import textwrap
from collections.abc import Iterator
from pathlib import Path

import pytest

from ..support import Proc, free_port, kame_command, ros_env, wait_for_master


@pytest.fixture(scope="module")
def env(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, str]]:
    home = Path(tmp_path_factory.mktemp("rospy_waits"))
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    environment = ros_env(home, uri)
    master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), environment)
    try:
        wait_for_master(uri, proc=master)
        yield environment
    finally:
        master.stop()


def run(env: dict[str, str], code: str, timeout: float = 30) -> str:
    out, err = Proc([sys.executable, "-c", textwrap.dedent(code)], env).finish(timeout)
    assert "Traceback" not in err, err
    return out


def test_shutdown_ends_wait_for_message_spin_and_runs_both_hook_shapes(env: dict[str, str]) -> None:
    out = run(env, """
        import threading
        import rospy
        from std_msgs.msg import String
        said = []  # lines from several threads, printed at the end (print is not atomic)
        rospy.init_node('waiter')
        rospy.on_shutdown(lambda: said.append('hook without arguments'))
        rospy.on_shutdown(lambda reason: said.append('hook told ' + reason))
        waiting = threading.Event()
        def stop_later():
            waiting.wait()
            rospy.signal_shutdown('enough')
        stopper = threading.Thread(target=stop_later)
        stopper.start()
        def wait():
            try:
                rospy.wait_for_message('/never', String)  # no timeout: only shutdown ends it
            except rospy.ROSInterruptException as e:
                said.append('interrupted: ' + str(e))
        waiter = threading.Thread(target=wait)
        waiter.start()
        waiting.set()
        rospy.spin()  # ends with the shutdown too
        waiter.join()
        said.append('spin returned')
        stopper.join()  # signal_shutdown returns once the node is down
        left = sorted(t.name for t in threading.enumerate() if t is not threading.main_thread())
        said.append('threads left: ' + str(left))
        try:
            rospy.wait_for_message('/never', String, timeout=5)  # already shut down: at once
        except rospy.ROSInterruptException as e:
            said.append('after shutdown: ' + str(e))
        print('\\n'.join(said))
    """)
    assert sorted(out.splitlines()) == sorted([
        "hook without arguments", "hook told enough", "interrupted: rospy shutdown", "spin returned",
        "after shutdown: rospy shutdown", "threads left: []"])


def test_an_action_servers_execute_thread_is_joined_at_shutdown(env: dict[str, str]) -> None:
    out = run(env, """
        import threading
        import actionlib
        import rospy
        from actionlib_tutorials.msg import FibonacciAction, FibonacciResult
        rospy.init_node('action_waiter')
        def execute(goal):
            server.set_succeeded(FibonacciResult(sequence=[goal.order]))
        server = actionlib.SimpleActionServer('fib', FibonacciAction, execute, auto_start=False)
        server.start()
        client = actionlib.SimpleActionClient('fib', FibonacciAction)
        client.wait_for_server()
        from actionlib_tutorials.msg import FibonacciGoal
        client.send_goal(FibonacciGoal(order=7))
        client.wait_for_result()
        print('result', list(client.get_result().sequence))
        rospy.signal_shutdown('done')
        print('threads left:', sorted(t.name for t in threading.enumerate() if t is not threading.main_thread()))
    """)
    assert out.splitlines() == ["result [7]", "threads left: []"]


def test_wait_for_server_and_sleep_end_on_simulated_time_and_at_shutdown(env: dict[str, str]) -> None:
    # No server ever comes. A wait of 5 s on simulated time (no /clock yet: time 0) ends when
    # /clock passes its deadline, published in one step to 110 s, however little wall time went
    # by; rospy.sleep on simulated time ends with the /clock message that passes its end; a wait
    # with no timeout ends with the shutdown, and a sleep after it raises at once.
    out = run(env, """
        import os
        import threading
        import xmlrpc.client
        import actionlib
        import rospy
        from actionlib_tutorials.msg import FibonacciAction
        from rosgraph_msgs.msg import Clock
        master = xmlrpc.client.ServerProxy(os.environ['ROS_MASTER_URI'])
        master.setParam('/test', '/use_sim_time', True)  # read by init_node; taken away again below
        rospy.init_node('server_waiter')
        master.deleteParam('/test', '/use_sim_time')
        clock = rospy.Publisher('/clock', Clock, queue_size=1, latch=True)
        client = actionlib.SimpleActionClient('nobody', FibonacciAction)
        waiting = threading.Event()
        def tick_later():
            waiting.wait()
            clock.publish(Clock(clock=rospy.Time(110)))
        ticker = threading.Thread(target=tick_later)
        ticker.start()
        waiting.set()
        print('timed wait:', client.wait_for_server(rospy.Duration(5)), rospy.get_rostime().secs)
        ticker.join()
        ticker = threading.Timer(0.5, clock.publish, (Clock(clock=rospy.Time(130)),))  # sleeping by then
        ticker.start()
        rospy.sleep(rospy.Duration(15))  # on simulated time: until /clock passes 125
        print('slept until', rospy.get_rostime().secs)
        ticker.join()
        stopper = threading.Timer(0.2, rospy.signal_shutdown, ('enough',))
        stopper.start()
        print('endless wait:', client.wait_for_server())
        stopper.join()
        try:
            rospy.sleep(rospy.Duration(15))  # already shut down: at once
        except rospy.ROSInterruptException:
            print('sleep interrupted')
    """)
    assert out.splitlines() == ["timed wait: False 110", "slept until 130", "endless wait: False", "sleep interrupted"]


def test_sigint_caught_by_another_thread_ends_spin(env: dict[str, str]) -> None:
    # Linux gives a signal sent to the process to any thread that does not block it, often a
    # busy one rather than the sleeping main thread (roslaunch's SIGINT to a node receiving
    # messages). The program sends its SIGINT to one of its other threads, once the main thread
    # sleeps in spin(): spin must still end, through the handler rospy installed.
    out = run(env, """
        import signal, threading, time
        import rospy
        from kame.client import core
        rospy.init_node('spinner')
        main_task = '/proc/self/task/%d/stat' % threading.main_thread().native_id
        def main_sleeps():
            with open(main_task) as stat:
                return stat.read().rsplit(')', 1)[1].split()[0] == 'S'
        def interrupt_from_here():
            while not (core.main_thread_is_waiting() and main_sleeps()):
                time.sleep(0.01)  # the main thread's state has no event to wait on
            signal.pthread_kill(threading.get_ident(), signal.SIGINT)
        threading.Thread(target=interrupt_from_here, name='interrupter').start()
        rospy.spin()
        print('spin returned:', rospy.core.is_shutdown_requested())
    """, timeout=10)
    assert out.splitlines() == ["spin returned: True"]
