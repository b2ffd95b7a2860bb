"""kame's ports of the roscpp tutorial programs, for machines without a C++ toolchain or roscpp.

Each program keeps the C++ one's node name, topics, service, parameters and console lines
(roscpp's format, kame.console), so a course's transcript reads the same whichever runs.
`main(name, argv)` runs one; the table PROGRAMS names them all.
"""

from __future__ import annotations

import queue
import sys
import threading
import time
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from typing import Any

from kame.client import clock, core, errors, log, process, services, timer, topics
from roscpp_tutorials.srv import TwoInts, TwoIntsRequest, TwoIntsResponse
from std_msgs.msg import String


def _info(text: str, *args: Any) -> None:
    log.emit(log.INFO, text, args)


def _start(name: str, argv: Sequence[str], anonymous: bool = False) -> list[str]:
    """ros::init: the node registered; the program's own (non-ROS) arguments returned."""
    log.use_roscpp_console()
    process.init_node(name, argv=list(argv), anonymous=anonymous)
    return process.myargv(list(argv))[1:]


def _say(publisher: topics.Publisher, hz: float) -> None:
    """talker's and babbler's loop: "hello world N", logged and published, at `hz`."""
    rate = timer.Rate(hz)
    count = 0
    while not core.is_shutdown():
        text = f"hello world {count}"
        _info("%s", text)
        publisher.publish(String(data=text))
        count += 1
        try:
            rate.sleep()
        except errors.ROSInterruptException:
            break


def talker(argv: Sequence[str]) -> int:
    _start("talker", argv)
    _say(topics.Publisher("chatter", String, queue_size=1000), 10)
    return 0


def babbler(argv: Sequence[str]) -> int:
    _start("babbler", argv)
    _say(topics.Publisher("babble", String, queue_size=1000), 10)
    return 0


def _heard(msg: String) -> None:
    _info("I heard: [%s]", msg.data)


def listener(argv: Sequence[str]) -> int:
    _start("listener", argv)
    topics.Subscriber("chatter", String, _heard, queue_size=1000)
    core.spin()
    return 0


def anonymous_listener(argv: Sequence[str]) -> int:
    _start("listener", argv, anonymous=True)
    topics.Subscriber("chatter", String, _heard, queue_size=1000)
    core.spin()
    return 0


def listener_with_userdata(argv: Sequence[str]) -> int:
    _start("listener_with_userdata", argv)

    def heard(msg: String, user: str) -> None:
        _info("I heard: [%s] with user string [%s]", msg.data, user)

    for user in ("User 1", "User 2", "User 3"):
        topics.Subscriber("chatter", String, heard, callback_args=user, queue_size=1000)
    core.spin()
    return 0


def listener_class(argv: Sequence[str]) -> int:
    _start("listener_class", argv)
    topics.Subscriber("chatter", String, _heard, queue_size=1000)
    core.spin()
    return 0


def listener_unreliable(argv: Sequence[str]) -> int:
    """Asks for UDP as roscpp's does; kame's publishers offer TCP, which roscpp then uses too."""
    _start("listener_unreliable", argv)
    topics.Subscriber("chatter", String, _heard, queue_size=1000)
    core.spin()
    return 0


def listener_with_tracked_object(argv: Sequence[str]) -> int:
    """The tracked object is gone before any message comes: only the plain callback prints."""
    _start("listener", argv)
    topics.Subscriber("chatter", String, lambda msg: _info("Only this version should print: [%s]", msg.data),
                      queue_size=1)
    core.spin()
    return 0


def _four_callbacks(pool: ThreadPoolExecutor | None) -> None:
    """listener_multiple's four subscriptions to chatter; with a pool (the spinner tutorials' four
    threads), each callback runs on it, printing its thread and working a hundredth of a second."""
    def callback(which: int) -> Callable[[String], None]:
        def work(msg: String) -> None:
            _info("chatter%d: [%s] [thread=%d]", which, msg.data, threading.get_ident())
            timer.sleep(0.01)

        def heard(msg: String) -> None:
            if pool is None:
                _info("chatter%d: [%s]", which, msg.data)
            else:
                pool.submit(work, msg)
        return heard

    for which in (1, 2, 3, 4):
        topics.Subscriber("chatter", String, callback(which), queue_size=10)


def listener_multiple(argv: Sequence[str]) -> int:
    _start("listener", argv)
    _four_callbacks(None)
    core.spin()
    return 0


def listener_threaded_spin(argv: Sequence[str]) -> int:
    _start("listener", argv)
    with ThreadPoolExecutor(4, thread_name_prefix="spinner") as pool:  # ros::MultiThreadedSpinner(4)
        _four_callbacks(pool)
        core.spin()
    return 0


def listener_async_spin(argv: Sequence[str]) -> int:
    _start("listener", argv)
    with ThreadPoolExecutor(4, thread_name_prefix="async-spinner") as pool:  # ros::AsyncSpinner(4)
        _four_callbacks(pool)
        rate = timer.Rate(5)
        while not core.is_shutdown():
            _info("Main thread [%d].", threading.get_ident())
            try:
                rate.sleep()
            except errors.ROSInterruptException:
                break
    return 0


def node_handle_namespaces(argv: Sequence[str]) -> int:
    _start("node_handle_namespaces", argv)
    for name in ("level1/a", "level1/level2/a", "~a"):  # NodeHandles "level1", its "level2", and "~"
        _info("%s", core.resolve_name(name))
    return 0


class _Announcer(topics.SubscribeListener):
    """notify_connect's callbacks: each new subscriber is greeted (it alone gets the message)."""

    def __init__(self) -> None:
        self.count = 0

    def peer_subscribe(self, topic_name: str, topic_publish: Callable[[Any], None],
                       peer_publish: Callable[[Any], None]) -> None:
        text = f"chatter connect #{self.count}"
        self.count += 1
        _info("%s", text)
        peer_publish(String(data=text))

    def peer_unsubscribe(self, topic_name: str, num_peers: int) -> None:
        _info("chatter disconnect")


def notify_connect(argv: Sequence[str]) -> int:
    _start("notify_connect", argv)
    topics.Publisher("chatter", String, subscriber_listener=_Announcer(), queue_size=1000)
    core.spin()
    return 0


def add_two_ints_server(argv: Sequence[str]) -> int:
    """add_two_ints_server, and add_two_ints_server_class (the same with an object's method)."""
    _start("add_two_ints_server", argv)

    def add(request: TwoIntsRequest) -> TwoIntsResponse:
        total = request.a + request.b
        _info("request: x=%d, y=%d", request.a, request.b)
        _info("  sending back response: [%d]", total)
        return TwoIntsResponse(sum=total)

    services.Service("add_two_ints", TwoInts, add)
    core.spin()
    return 0


def _atoi(text: str) -> int:
    """C's atoi: the leading integer of the text, 0 when there is none."""
    digits = ""
    for i, ch in enumerate(text.strip()):
        if ch.isdigit() or (i == 0 and ch in "+-"):
            digits += ch
        else:
            break
    try:
        return int(digits)
    except ValueError:
        return 0


def add_two_ints_client(argv: Sequence[str]) -> int:
    args = _start("add_two_ints_client", argv)
    if len(args) != 2:
        _info("usage: add_two_ints_client X Y")
        return 1
    try:
        answer = services.ServiceProxy("add_two_ints", TwoInts)(_atoi(args[0]), _atoi(args[1]))
    except (services.ServiceException, errors.ROSException):
        log.emit(log.ERROR, "Failed to call service add_two_ints", ())
        return 1
    _info("Sum: %d", answer.sum)
    return 0


def time_api_sleep(argv: Sequence[str]) -> int:
    """No node: prints and sleeps on the wall clock, as ros::Time::init() leaves it."""
    steps = [("sleeping for one second", 1.0), ("sleeping for a half second", 0.5)]
    steps += [("sleeping for a tenth of a second", 0.1)] * 5
    for text, seconds in steps:
        sys.stdout.write(text + "\n")
        sys.stdout.flush()
        time.sleep(seconds)  # the program's own work is this sleep, as Duration::sleep()
    return 0


def timers(argv: Sequence[str]) -> int:
    _start("talker", argv)  # the tutorial's own node name
    timer.Timer(clock.Duration.from_sec(0.1), lambda _event: _info("Callback 1 triggered"))
    timer.Timer(clock.Duration.from_sec(1.0), lambda _event: _info("Callback 2 triggered"))
    core.spin()
    return 0


def parameters(argv: Sequence[str]) -> int:
    _start("parameters", argv)
    prefix = core.get_namespace()
    name = prefix + "my_param"
    if process.has_param(name) and isinstance(process.get_param(name), str):
        _info("Got param: %s", process.get_param(name))
    else:
        log.emit(log.ERROR, "Failed to get param 'my_param'", ())
    process.set_param(name, "hello there")
    process.delete_param(name)
    if not process.has_param(name):
        _info("No param named 'my_param'")
    found = process.search_param("b")
    if found is None:
        _info("No param 'b' found in an upward search")
    return 0


def custom_callback_processing(argv: Sequence[str]) -> int:
    """One subscription's callbacks on a queue served by a thread of its own, the other's on the
    main thread, which serves its queue once a second (ros::spinOnce at 1 Hz)."""
    _start("listener_with_custom_callback_processing", argv)
    custom: queue.Queue[String | None] = queue.Queue()
    main: queue.Queue[String] = queue.Queue()

    def serve_custom() -> None:
        _info("Callback thread id=%d", threading.get_ident())
        while (msg := custom.get()) is not None:
            _info("I heard: [ %s] in thread [%d]", msg.data, threading.get_ident())

    topics.Subscriber("chatter", String, custom.put, queue_size=1000)
    topics.Subscriber("chatter", String, main.put, queue_size=1000)
    worker = threading.Thread(target=serve_custom, name="custom-callback-queue")
    worker.start()
    _info("Main thread id=%d", threading.get_ident())
    rate = timer.Rate(1)
    try:
        while not core.is_shutdown():
            while not main.empty():
                _info("I heard: [ %s] in thread [%d] (Main thread)", main.get().data, threading.get_ident())
            try:
                rate.sleep()
            except errors.ROSInterruptException:
                break
    finally:
        custom.put(None)
        worker.join()
    return 0


PROGRAMS: dict[str, Callable[[Sequence[str]], int]] = {
    "talker": talker, "listener": listener, "babbler": babbler, "anonymous_listener": anonymous_listener,
    "listener_with_userdata": listener_with_userdata, "notify_connect": notify_connect,
    "add_two_ints_server": add_two_ints_server, "add_two_ints_client": add_two_ints_client,
    "time_api_sleep": time_api_sleep, "timers": timers, "parameters": parameters,
    "custom_callback_processing": custom_callback_processing, "listener_class": listener_class,
    "listener_multiple": listener_multiple, "listener_threaded_spin": listener_threaded_spin,
    "listener_async_spin": listener_async_spin, "listener_unreliable": listener_unreliable,
    "node_handle_namespaces": node_handle_namespaces, "add_two_ints_server_class": add_two_ints_server,
    "listener_with_tracked_object": listener_with_tracked_object,
}


def main(name: str, argv: Sequence[str]) -> int:
    try:
        return PROGRAMS[name](argv)
    except KeyboardInterrupt:
        return 0
