"""rostopic's and rosmsg's library functions on fixed cases; prints JSON. Run by kame's
interpreter and Debian's /usr/bin/python3 (its real rostopic and rosmsg), ROS_PACKAGE_PATH on a
workspace of two test packages and Debian's message packages."""

from __future__ import annotations

import contextlib
import io
import json
import sys
from collections.abc import Callable
from typing import Any

import genpy
import rosmsg
import rospkg
import rostopic
from geometry_msgs.msg import PoseStamped
from sensor_msgs.msg import JointState
from std_msgs.msg import Float32MultiArray, MultiArrayDimension, String

TEST_PACKAGES = ("kame_probe_a", "kame_probe_b")


def captured(call: Callable[[], Any]) -> list[Any]:
    """[what `call` returned (or its exit status / exception), its stdout, its stderr]."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            result: Any = call()
        except SystemExit as exc:
            result = ["exit", exc.code]
        except Exception as exc:
            result = ["raised", type(exc).__name__, str(exc)]
    return [result, out.getvalue(), err.getvalue()]


def messages() -> list[Any]:
    pose = PoseStamped()
    pose.header.stamp = genpy.Time(3, 4)
    pose.header.frame_id = "map"
    pose.pose.position.x = 1.5
    joints = JointState(name=["a", "b"], position=[0.5, 1.0], velocity=[], effort=[2.0])
    joints.header.stamp = genpy.Time(7, 0)
    array = Float32MultiArray(data=[1.0, 2.5])
    array.layout.dim = [MultiArrayDimension(label="x", size=2, stride=2)]
    return [pose, joints, array, String(data="hi")]


def rostopic_answers() -> dict[str, Any]:
    out: dict[str, Any] = {"plot": [], "fields": []}
    for flags in ((False, False), (True, False), (False, True), (True, True)):
        field_filter = rostopic.create_field_filter(*flags)
        for msg in messages():
            out["fields"].append([list(field_filter(msg)), rostopic._str_plot_fields(msg, "field", field_filter)])
            out["plot"].append([rostopic._str_plot(msg, current_time=genpy.Time(5, 6), field_filter=field_filter),
                                rostopic._str_plot(msg, time_offset=genpy.Time(1, 0), current_time=genpy.Time(9),
                                                   field_filter=field_filter)])
    pose, joints, *_ = messages()
    out["header_stamp"] = [rostopic._str_plot(pose), rostopic._str_plot(joints, time_offset=genpy.Time(1))]
    out["no_header_no_time"] = captured(lambda: rostopic._str_plot(String(data="x")))[0]
    good = rostopic.msgevalgen("/pose/position")
    out["evalgen"] = {
        "good": [good is not None, good(pose).x if good else None],
        "slice": captured(lambda: rostopic.msgevalgen("/name[0:1]")(joints)),  # type: ignore[misc]
        "empty": captured(lambda: rostopic.msgevalgen("")),
        "missing_field": captured(lambda: rostopic.msgevalgen("/nope/x")(pose)),  # type: ignore[misc]
        "past_the_end": captured(lambda: rostopic.msgevalgen("/name[5]")(joints)),  # type: ignore[misc]
    }
    for pattern in ("/pose[", "/name[x]", "/name[1:y]", "/name[]"):
        out["evalgen"][pattern] = captured(lambda pattern=pattern: rostopic.msgevalgen(pattern))
    return out


def echo_answers() -> dict[str, Any]:
    """rostopic.CallbackEcho's callback, called by hand as rostopic's tests do."""
    pose, joints, array, text = messages()
    at = genpy.Time(10, 0)
    cases = {
        "yaml": (dict(topic="/pose", msg_eval=None), [(pose, "/pose"), (text, "/other")]),
        "field": (dict(topic="/pose/pose/position", msg_eval=None), [(pose, "/pose")]),
        "plot": (dict(topic="/joints", msg_eval=None, plot=True), [(joints, "/joints"), (joints, "/joints")]),
        "count": (dict(topic="/a", msg_eval=None, count=1), [(array, "/a"), (array, "/a")]),
        "all_topics": (dict(topic="/a", msg_eval=None, echo_all_topics=True), [(text, "/b")]),
        "filter": (dict(topic="/a", msg_eval=None, filter_fn=lambda m: m.data == "hi"),
                   [(text, "/a"), (String(data="no"), "/a")]),
        "nostr": (dict(topic="/j", msg_eval=None, value_transform_fn=rostopic.create_value_transform(True, True)),
                  [(joints, "/j")]),
        "width": (dict(topic="/p", msg_eval=rostopic.msgevalgen("/pose/position"), fixed_numeric_width=6),
                  [(pose, "/p")]),
        "plot_filtered": (dict(topic="/j", msg_eval=None, plot=True, field_filter_fn=rostopic.create_field_filter(
            True, True)), [(joints, "/j")]),
    }
    out = {}
    for name, (options, calls) in cases.items():
        echo = rostopic.CallbackEcho(**options)  # type: ignore[arg-type]

        def run(echo: Any = echo, calls: Any = calls) -> None:
            for msg, topic in calls:
                echo.callback(msg, {"topic": topic}, current_time=at)

        result = captured(run)
        out[name] = [result[1], echo.count, echo.done]
    return out


def rosmsg_answers() -> dict[str, Any]:
    rospack = rospkg.RosPack()
    prototypes = {" ".join(args): captured(lambda args=args: rosmsg.rosmsg_cmd_prototype(args)) for args in (
        ["msg", "geometry_msgs/Twist"], ["msg", "geometry_msgs/PoseStamped", "-H"], ["msg", "Twist", "-p", "  "],
        ["msg", "std_msgs/Float32MultiArray"], ["msg", "std_msgs/Float32MultiArray", "-e", "-f", "1"],
        ["msg", "geometry_msgs/PoseStamped", "-x", "header,orientation", "-f", "0"], ["srv", "std_srvs/SetBool"],
        ["msg", "Probe"], ["msg", "Nope"], ["msg", "Nope", "-s"], ["msg"], ["msg", "a::b"], ["msg", "no_pkg/Nope"])}
    ours = [pair for pair in rosmsg.iterate_packages(rospack, rosmsg.MODE_MSG) if pair[0] in TEST_PACKAGES]
    listed = captured(lambda: rosmsg.rosmsg_cmd_list(rosmsg.MODE_MSG, "message type", ["list"]))
    listed_srv = captured(lambda: rosmsg.rosmsg_cmd_list(rosmsg.MODE_SRV, "service type", ["list"]))
    packages = captured(lambda: rosmsg.rosmsg_cmd_packages(rosmsg.MODE_MSG, "message type", ["packages"]))
    packages_one_line = captured(lambda: rosmsg.rosmsg_cmd_packages(rosmsg.MODE_SRV, "service type",
                                                                     ["packages", "-s"]))
    pose = messages()[0]
    names_filter = rosmsg.create_names_filter("header")
    return {
        "prototype": prototypes,
        "iterate": sorted([name, path.rsplit("/", 2)[-2:]] for name, path in ours),
        "iterate_bad_mode": captured(lambda: list(rosmsg.iterate_packages(rospack, ".x"))),
        "search": sorted(rosmsg.rosmsg_search(rospack, rosmsg.MODE_MSG, "Probe")),
        "list": [line for line in listed[1].splitlines() if line.split("/")[0] in TEST_PACKAGES],
        "list_srv": [line for line in listed_srv[1].splitlines() if line.split("/")[0] in TEST_PACKAGES],
        "packages": [p for p in packages[1].split() if p in TEST_PACKAGES],
        "packages_one_line": [packages_one_line[1].count("\n"),
                              [p for p in packages_one_line[1].split() if p in TEST_PACKAGES]],
        "md5": [rosmsg.rosmsg_md5(rosmsg.MODE_MSG, "geometry_msgs/Twist"),
                rosmsg.rosmsg_md5(rosmsg.MODE_SRV, "std_srvs/SetBool"),
                captured(lambda: rosmsg.rosmsg_md5(rosmsg.MODE_MSG, "no_pkg/Nope"))[0]],
        "debug": captured(lambda: rosmsg.rosmsg_debug(rospack, rosmsg.MODE_MSG, "geometry_msgs/Point")),
        "fullusage": [rosmsg.fullusage(rosmsg.MODE_MSG), rosmsg.fullusage(rosmsg.MODE_SRV)],
        "names_filter": [names_filter(pose), rosmsg.create_names_filter("bar")(JointState()),
                         rosmsg.create_names_filter(["name", "effort"])(JointState()),
                         rosmsg.create_names_filter("position,velocity")(JointState())],
        "exceptions": [issubclass(rosmsg.RosMsgProtoException, Exception),
                       issubclass(rosmsg.RosMsgProtoArgsException, Exception)],
    }


def main() -> None:
    sys.stdout.write(json.dumps({"rostopic": rostopic_answers(), "rosmsg": rosmsg_answers(), "echo": echo_answers()}))


if __name__ == "__main__":
    main()
