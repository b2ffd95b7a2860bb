"""One of rospy's waits, ended by shutdown: run by kame's interpreter and by Debian's.

    shutdown_driver.py WAIT CLOCK HOW

WAIT is sleep, rate, wait_for_message, wait_for_service, timer, spin, callback, busy (a loop
in the program's own code) or after (a sleep begun after the shutdown); CLOCK is wall or sim
(simulated time that no /clock ever moves: the test runs the driver against a master whose
/use_sim_time is set); HOW is signal_shutdown or sigint. The driver prints what the wait did
(returned, or raised what) and what ran after it. Plain rospy, as a user's program: the two
interpreters must print the same lines.
"""

import os
import signal
import sys
import threading
import time

import rospy
from std_msgs.msg import String


def stop(how):
    if how == "sigint":
        os.kill(os.getpid(), signal.SIGINT)
    else:
        rospy.signal_shutdown("test")


def main_sleeps():
    with open(f"/proc/self/task/{threading.main_thread().native_id}/stat") as stat:
        return stat.read().rsplit(")", 1)[1].split()[0] == "S"


def stop_later(how, asleep=True):
    """Shutdown 0.3 s from now, once the main thread sleeps in its wait (a loaded machine may
    take longer to get it there: a Ctrl-C before would not find it waiting), or at once when
    the main thread is busy (`asleep` false)."""
    def later():
        time.sleep(0.3)
        while asleep and not main_sleeps():
            time.sleep(0.01)  # a thread's state has no event to wait on
        stop(how)

    threading.Thread(target=later).start()


def outcome(wait):
    try:
        wait()
    except rospy.ROSInterruptException as e:
        return f"raised ROSInterruptException: {e}"
    except rospy.ROSException as e:
        return f"raised ROSException: {e}"
    return "returned"


def main():
    wait, clock, how = sys.argv[1:4]
    rospy.init_node("shutdown_driver", anonymous=True)
    assert rospy.get_param("/use_sim_time", False) == (clock == "sim")  # the test's master for the clock
    if wait == "sleep":
        stop_later(how)
        print("sleep:", outcome(lambda: rospy.sleep(0.8)))
    elif wait == "rate":
        def loop():
            rate = rospy.Rate(2)
            while not rospy.is_shutdown():
                rate.sleep()
        stop_later(how)
        print("rate loop:", outcome(loop))
    elif wait == "wait_for_message":
        stop_later(how)
        print("wait_for_message:", outcome(lambda: rospy.wait_for_message("/nobody", String, rospy.Duration(30))))
    elif wait == "wait_for_service":
        stop_later(how)
        print("wait_for_service:", outcome(lambda: rospy.wait_for_service("/nobody", rospy.Duration(30))))
    elif wait == "timer":
        timer = rospy.Timer(rospy.Duration(0.05), lambda event: None)
        stop_later(how)
        print("spin:", outcome(rospy.spin))
        timer.join(10)
        print("timer thread ended:", not timer.is_alive())
    elif wait == "busy":
        def work():
            while not rospy.is_shutdown():
                sum(range(10000))  # the main thread in the program's own code, not in a wait
        stop_later(how, asleep=False)
        print("busy loop:", outcome(work))
    elif wait == "after":
        stop(how)
        while not rospy.is_shutdown():
            time.sleep(0.01)  # kame shuts down on a thread of its own
        started = time.monotonic()
        said = outcome(lambda: rospy.sleep(0.5))
        print("sleep after shutdown:", said + ", slept whole:", time.monotonic() - started >= 0.45)
    elif wait == "spin":
        stop_later(how)
        print("spin:", outcome(rospy.spin))
    elif wait == "callback":
        entered, released, finished = threading.Event(), threading.Event(), threading.Event()
        seen = []

        def callback(msg):
            if entered.is_set():
                return
            entered.set()
            released.wait()
            seen.append(rospy.is_shutdown())
            finished.set()

        rospy.Subscriber(rospy.get_name() + "/chatter", String, callback)
        pub = rospy.Publisher(rospy.get_name() + "/chatter", String, queue_size=1, latch=True)
        pub.publish(String(data="hello"))

        def stop_in_callback():
            entered.wait()
            stop(how)

        threading.Thread(target=stop_in_callback).start()
        print("spin:", outcome(rospy.spin))
        released.set()
        print("callback in flight finished:", finished.wait(10), "and saw shutdown:", seen)
    print("is_shutdown:", rospy.is_shutdown())


main()
