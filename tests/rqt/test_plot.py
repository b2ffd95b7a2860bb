"""rqt_plot: series names, the bounded history, numeric fields, the live turtle's pose, the window,
and a real rospy publisher on Debian's rosmaster."""

from __future__ import annotations

import struct
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from geometry_msgs.msg import PoseStamped, Twist
from kame.msg.fieldpath import field_type
from kame.rostime import Duration, Time
from kame.rqt.plot_model import (
    Series,
    SeriesNameError,
    as_number,
    expand_series_args,
    numeric_fields,
    padded,
    split_series,
    value_range,
    visible_peaks,
)
from kame.rqt.plot_source import READ_INTERVAL, PlotSource
from kame.rqt.ros_node import start_node
from sensor_msgs.msg import JointState
from tests.support import SYSTEM_PYTHON, Proc, free_port, have_debian_ros, ros_env, wait_for_master
from tests.turtlesim.sim import Sim, turtlesim, wait_until
from turtlesim.msg import Pose

TYPES = [("/turtle1/pose", "turtlesim/Pose"), ("/turtle1/cmd_vel", "geometry_msgs/Twist"),
         ("/joints", "sensor_msgs/JointState")]
CLASSES = {"turtlesim/Pose": Pose, "geometry_msgs/Twist": Twist, "sensor_msgs/JointState": JointState}


def check(type_name: str, field: str) -> str:
    return field_type(CLASSES[type_name], field)


def test_series_arguments_as_rqt_plot_reads_them() -> None:
    assert expand_series_args(["/turtle1/pose/x:y"]) == ["/turtle1/pose/x", "/turtle1/pose/y"]
    assert expand_series_args(["/a/b/c", "/turtle1/pose/x:theta,/x/y"]) == ["/a/b/c", "/turtle1/pose/x",
                                                                          "/turtle1/pose/theta", "/x/y"]
    assert expand_series_args(["/a/x:x"]) == ["/a/x"]


def test_series_names_split_against_the_published_topics() -> None:
    spec = split_series("/turtle1/pose/x", TYPES, check)
    assert (spec.topic, spec.type) == ("/turtle1/pose", "turtlesim/Pose")
    assert spec.path.evaluate(Pose(x=3.5)) == 3.5
    assert split_series("/turtle1/cmd_vel/linear/x", TYPES, check).path.evaluate(Twist()) == 0.0
    assert split_series("/joints/position[1]", TYPES, check).topic == "/joints"
    for bad, why in (("/turtle1/pose", "is a topic"), ("/nowhere/x", "no published topic"),
                     ("/turtle1/cmd_vel/linear", "not a number"), ("/joints/position", "not a number"),
                     ("/turtle1/pose/q", "no field named"), ("/joints/name[0]", "not a number")):
        with pytest.raises(SeriesNameError, match=why):
            split_series(bad, TYPES, check)


def test_numeric_fields_for_completion() -> None:
    assert numeric_fields(Pose) == ["x", "y", "theta", "linear_velocity", "angular_velocity"]
    assert numeric_fields(Twist) == ["linear/x", "linear/y", "linear/z", "angular/x", "angular/y", "angular/z"]
    fields = numeric_fields(PoseStamped)
    assert {"header/seq", "header/stamp", "pose/position/x", "pose/orientation/w"} <= set(fields)
    assert "header/frame_id" not in fields
    assert numeric_fields(JointState)[-3:] == ["position[0]", "velocity[0]", "effort[0]"]
    assert (as_number(True), as_number(3), as_number(Time(1, 500_000_000)), as_number(Duration(2, 0))) == (
        1.0, 3.0, 1.5, 2.0)
    with pytest.raises(TypeError):
        as_number("7")


def test_a_series_keeps_its_history_and_no_more() -> None:
    series = Series(history=10.0, max_points=50_000)
    for second in range(30):  # 30 s at 1 kHz, in batches as a subscriber hands them over
        t = second + np.arange(1000) / 1000.0
        series.extend(t, np.sin(t))
    t, v = series.data()
    assert t[0] >= 29.999 - 10.0 and t[-1] == pytest.approx(29.999)
    assert len(t) == len(v) == 10_001 and np.all(np.diff(t) > 0)
    assert series.last() == (pytest.approx(29.999), pytest.approx(np.sin(29.999)))
    capped = Series(history=1e9, max_points=100)
    capped.extend(np.arange(250.0), np.arange(250.0))
    assert len(capped) == 100 and capped.data()[0][0] == 150.0
    series.set_history(1.0)
    assert len(series) == 1001
    series.clear()
    assert len(series) == 0 and series.last() is None
    with pytest.raises(ValueError):
        Series(history=0)


def test_what_a_plot_draws_is_thinned_to_its_pixels_keeping_the_peaks() -> None:
    t = np.arange(60_000) / 1000.0
    v = np.sin(t)
    v[30_123] = 5.0  # a spike one sample wide
    shown_t, shown_v = visible_peaks(t, v, 10.0, 50.0, 400)
    assert len(shown_t) <= 2 * 400 + 2 and np.all(np.diff(shown_t) >= 0)
    assert shown_t[0] < 10.0 and shown_t[-1] > 50.0  # one point beyond each edge: lines reach them
    assert shown_v.max() == 5.0 and shown_v.min() == pytest.approx(-1.0, abs=1e-4)
    few_t, few_v = visible_peaks(t[:50], v[:50], 0.0, 1.0, 400)
    assert np.array_equal(few_t, t[:50]) and np.array_equal(few_v, v[:50])  # nothing to thin
    series = Series()
    series.extend(t, v)
    peak_t, _ = series.peaks(0.0, 60.0, 100)
    peak_t[:] = -1.0
    assert series.data()[0][0] == 0.0  # the peaks are copies


def test_the_value_axis_spans_the_finite_values_drawn() -> None:
    assert value_range([np.array([1.0, 3.0]), np.array([-1.0, 2.0])], padding=0.25) == (-2.0, 4.0)
    assert value_range([np.array([np.nan, 2.0, np.inf]), np.array([])], padding=0.0) == (1.5, 2.5)  # flat
    assert value_range([np.array([np.nan]), np.array([])]) is None  # nothing to fit
    assert value_range([]) is None
    assert padded(0.0, 10.0, 0.1) == (-1.0, 11.0) and padded(4.0, 4.0, 0.1) == (3.5, 4.5)


@pytest.fixture(scope="module")
def sim(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Sim]:
    with turtlesim(tmp_path_factory.mktemp("rqt_plot")) as (live, _node):
        yield live


@pytest.fixture
def source(sim: Sim) -> Iterator[PlotSource]:
    node = start_node("plot", {"master": sim.uri}, sim.env)
    plot = PlotSource(node)
    yield plot
    plot.close()
    node.shutdown("test over")


def test_pose_x_rises_after_a_cmd_vel(sim: Sim, source: PlotSource) -> None:
    sim.run("rosservice", "call", "/reset")
    for name in expand_series_args(["/turtle1/pose/x:y"]):
        source.add(name)
    assert sorted(source.series) == ["/turtle1/pose/x", "/turtle1/pose/y"]
    assert source.node.subscriptions["/turtle1/pose"].read_interval == READ_INTERVAL  # read in batches
    wait_until(lambda: len(source.data()["/turtle1/pose/x"][0]) > 5, what="pose samples")
    start_x = source.data()["/turtle1/pose/x"][1][-1]
    sim.run("rostopic", "pub", "-1", "/turtle1/cmd_vel", "geometry_msgs/Twist", "--", "[2,0,0]", "[0,0,0]")
    wait_until(lambda: source.data()["/turtle1/pose/x"][1][-1] > start_x + 1.0, what="x to rise")
    t, x = source.data()["/turtle1/pose/x"]
    y = source.data()["/turtle1/pose/y"][1]
    assert np.all(np.diff(t) >= 0) and x.max() > x.min() + 1.0
    assert np.ptp(y) < 1e-6  # straight along x
    with pytest.raises(SeriesNameError):
        source.add("/turtle1/pose/nothing")
    assert "/turtle1/pose/x" in source.completions() and "/turtle1/cmd_vel/linear/x" in source.completions()
    source.remove("/turtle1/pose/x")
    source.remove("/turtle1/pose/y")
    assert "/turtle1/pose" not in source.node.subscriptions


def test_the_window_plots_adds_and_removes(sim: Sim, source: PlotSource, qtbot, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    from kame.rqt.plot_window import PlotWindow

    window = PlotWindow(source)
    qtbot.addWidget(window)
    window.show()
    assert window.add_series("/turtle1/pose/x:theta") == ["/turtle1/pose/x", "/turtle1/pose/theta"]
    assert window.add_series("/turtle1/pose/bogus") == [] and "no field named" in window.status.text()
    def points() -> int:  # what the curve was given (getData is what is drawn: downsampled, clipped)
        x = window.curves["/turtle1/pose/x"].xData
        return 0 if x is None else len(x)

    qtbot.waitUntil(lambda: points() > 3, timeout=10_000)
    window.refresh_completions()
    assert "/turtle1/pose/y" in window.completer.model().stringList()
    labels = [label.text for _, label in window.legend.items]
    assert labels == ["/turtle1/pose/x", "/turtle1/pose/theta"]
    window.remove_series("/turtle1/pose/theta")
    assert list(window.curves) == ["/turtle1/pose/x"] and window.remove_box.count() == 1
    window.y_auto.setChecked(False)
    window.y_min.setValue(0.0)
    window.y_max.setValue(11.0)
    assert window.plot.getViewBox().viewRange()[1] == pytest.approx([0.0, 11.0])
    window.pause_button.setChecked(True)
    frozen = points()
    wait_until(lambda: len(source.data()["/turtle1/pose/x"][0]) > frozen + 3, what="more samples")
    window.redraw()
    assert points() == frozen
    window.grab().save(str(tmp_path / "plot.png"))
    assert (tmp_path / "plot.png").stat().st_size > 0


def test_the_window_draws_only_what_changed_and_fits_the_value_axis(sim: Sim, source: PlotSource, qtbot,  # type: ignore[no-untyped-def]
                                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    from PySide6.QtCore import QPoint, QPointF, Qt
    from PySide6.QtGui import QWheelEvent
    from PySide6.QtWidgets import QApplication

    from kame.rqt.plot_window import PlotWindow
    from std_msgs.msg import Float64

    publisher_node = start_node("levels", {"master": sim.uri}, sim.env)
    try:
        publisher_node.advertise("/level", "std_msgs/Float64", Float64._md5sum, Float64._full_text)
        window = PlotWindow(source)
        qtbot.addWidget(window)
        window.show()
        window.timer.stop()  # the test draws each frame itself
        assert window.add_series("/level/data") == ["/level/data"]
        curve = window.curves["/level/data"]
        drawn: list[int] = []
        real_set_data = curve.setData
        monkeypatch.setattr(curve, "setData", lambda *a, **k: (drawn.append(len(a[0])), real_set_data(*a, **k)))

        def arrive(*values: float) -> None:  # as the subscriber hands a batch of messages over
            source._deliver("/level", [memoryview(struct.pack("<d", v)) for v in values], {})

        arrive(1.0, 3.0, 2.0)
        window.redraw()
        assert drawn == [3] and list(curve.yData) == [1.0, 3.0, 2.0] and curve.opts["connect"] == "all"
        view = window.plot.getViewBox()
        low, high = view.viewRange()[1]
        assert low < 1.0 < 3.0 < high and high - low < 2.5  # fitted to the values, padded
        window.redraw()
        assert drawn == [3]  # nothing new: nothing drawn
        arrive(float("nan"), 7.0)
        window.hide()  # as a dock tabbed behind another
        window.redraw()
        assert drawn == [3]  # not seen: not drawn
        window.show()
        window.redraw()
        assert drawn == [3, 5] and np.array_equal(curve.yData, [1.0, 3.0, 2.0, np.nan, 7.0], equal_nan=True)
        assert curve.opts["connect"] == "finite"  # the NaN is a gap, found by pyqtgraph
        assert 7.0 < view.viewRange()[1][1] < 8.0  # and no part of the value axis' range

        centre = window.plot.viewport().rect().center()  # a turn of the mouse wheel zooms both axes
        wheel = QWheelEvent(QPointF(centre), QPointF(window.plot.viewport().mapToGlobal(centre)), QPoint(0, 0),
                            QPoint(0, 120), Qt.MouseButton.NoButton, Qt.KeyboardModifier.NoModifier,
                            Qt.ScrollPhase.NoScrollPhase, False)
        QApplication.sendEvent(window.plot.viewport(), wheel)
        assert not window.autoscroll.isChecked() and not window.y_auto.isChecked()
        zoomed = np.ravel(view.viewRange())
        assert (window.y_min.value(), window.y_max.value()) == pytest.approx(zoomed[2:], abs=1e-3)
        arrive(50.0)
        window.redraw()
        assert len(drawn) == 3 and np.ravel(view.viewRange()) == pytest.approx(zoomed, abs=1e-3)  # the user's view
        window.y_auto.setChecked(True)
        window.redraw()
        assert view.viewRange()[1][1] > 50.0
    finally:
        publisher_node.shutdown("test over")


def test_the_messages_of_one_read_are_spread_over_the_time_since_the_last(sim: Sim) -> None:
    from std_msgs.msg import Float64

    now = 100.0
    plot_node = start_node("plot", {"master": sim.uri}, sim.env)
    publisher_node = start_node("spread", {"master": sim.uri}, sim.env)
    source = PlotSource(plot_node, clock=lambda: now)
    try:
        publisher_node.advertise("/spread", "std_msgs/Float64", Float64._md5sum, Float64._full_text)
        source.add("/spread/data")

        def read(*values: float) -> np.ndarray:  # one read's worth of messages, as the subscriber hands it over
            source._deliver("/spread", [memoryview(struct.pack("<d", v)) for v in values], {})
            return source.data()["/spread/data"][0]

        now = 100.5
        assert read(1.0, 2.0) == pytest.approx([0.5 - READ_INTERVAL / 2, 0.5])  # the first: over one interval
        now = 100.504  # 4 ms later: four messages came in those 4 ms
        assert read(3.0, 4.0, 5.0, 6.0)[2:] == pytest.approx([0.501, 0.502, 0.503, 0.504])
        now = 160.0  # after a quiet minute, a burst: over one interval, not the minute
        assert read(7.0, 8.0)[-2:] == pytest.approx([60.0 - READ_INTERVAL / 2, 60.0])
        assert np.all(np.diff(source.data()["/spread/data"][0]) > 0)  # never two points at one time
    finally:
        source.close()
        publisher_node.shutdown("test over")
        plot_node.shutdown("test over")


def test_a_type_kame_does_not_have_is_read_from_its_publishers_definition(sim: Sim, source: PlotSource) -> None:
    from kame.msg.loader import generate_dynamic
    from kame.node.topics import serialize_frame

    odd = generate_dynamic("lab_msgs/Reading", "float64 value\nstring unit\n")["lab_msgs/Reading"]
    publisher_node = start_node("publisher", {"master": sim.uri}, sim.env)
    try:
        publication = publisher_node.advertise("/reading", "lab_msgs/Reading", odd._md5sum, odd._full_text)
        source.add("/reading/value")  # no lab_msgs here: subscribed as any type
        with pytest.raises(SeriesNameError, match="no published topic"):
            source.add("/readings/value")
        count = 0

        def publish_until_seen() -> bool:
            nonlocal count
            count += 1
            publication.publish_frame(serialize_frame(odd(value=float(count), unit="V")))
            return len(source.data()["/reading/value"][1]) > 0

        wait_until(publish_until_seen, what="a reading in the plot")
        assert source.data()["/reading/value"][1][-1] >= 1.0
        source.add("/reading/unit")  # a string: known only from the definition, refused when it comes
        publication.publish_frame(serialize_frame(odd(value=2.5, unit="V")))
        wait_until(lambda: bool(source.problems()), what="the string field's problem")
        assert "str is not a number" in source.problems()[0]
    finally:
        publisher_node.shutdown("test over")


def test_points_are_stamped_with_the_header_stamp_when_there_is_one(sim: Sim, source: PlotSource) -> None:
    from kame.node.topics import serialize_frame

    publisher_node = start_node("stamped", {"master": sim.uri}, sim.env)
    series = "/stamped_pose/pose/position/x"
    try:
        publication = publisher_node.advertise("/stamped_pose", "geometry_msgs/PoseStamped", PoseStamped._md5sum,
                                               PoseStamped._full_text)
        source.add(series)

        def pose(x: float, seconds_after_start: float | None) -> list[object]:
            message = PoseStamped()
            message.pose.position.x = x
            if seconds_after_start is not None:
                message.header.stamp = Time.from_sec(source.start + seconds_after_start)
            return serialize_frame(message)

        def publish_until_seen(frame: list[object], value: float) -> bool:
            publication.publish_frame(frame)
            return value in source.data()[series][1]

        # stamp zero: its arrival time
        wait_until(lambda: publish_until_seen(pose(1.0, None), 1.0), what="an unstamped pose")
        t, x = source.data()[series]
        assert np.all((t >= 0.0) & (t < 60.0))
        # stamped 100 s after the plot began, whenever it arrives
        wait_until(lambda: publish_until_seen(pose(1.5, 100.0), 1.5), what="a stamped pose")
        t, x = source.data()[series]
        assert np.allclose(t[x == 1.5], 100.0, atol=1e-3)
        publication.publish_frame(pose(2.5, 50.0))  # before the last: left out, and said
        wait_until(lambda: bool(source.problems()), what="the out-of-order message's problem")
        assert "stamped before the previous one" in source.problems()[0]
        t, x = source.data()[series]
        assert 2.5 not in x and np.all(np.diff(t) >= 0)
        # one batch with a message in order and one out of it: the good one is kept, the
        # problem still said (it was cleared by the good one's arrival)
        header = {"type": "geometry_msgs/PoseStamped", "message_definition": PoseStamped._full_text}
        batch = [memoryview(b"".join(bytes(part) for part in pose(x, after))[4:])  # without the length
                 for x, after in ((3.5, 200.0), (4.5, 150.0))]
        with source._lock:
            source.errors.clear()
        source._deliver("/stamped_pose", batch, header)
        assert "stamped before the previous one" in source.problems()[0]
        assert 3.5 in source.data()[series][1]
    finally:
        publisher_node.shutdown("test over")


@pytest.mark.skipif(not have_debian_ros(), reason="Debian's ROS 1 (rosmaster, rospy) is not installed")
def test_a_real_rospy_publisher_on_debians_rosmaster(tmp_path: Path) -> None:
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = ros_env(tmp_path, uri)
    code = ("import rospy\nfrom std_msgs.msg import Float64\nrospy.init_node('level')\n"
            "pub = rospy.Publisher('/level', Float64, queue_size=10)\nr = rospy.Rate(100)\ni = 0\n"
            "while not rospy.is_shutdown():\n    pub.publish(Float64(i))\n    i += 1\n    r.sleep()\n")
    procs = [Proc([SYSTEM_PYTHON, "/usr/bin/rosmaster", "--core", "-p", str(port)], env)]
    try:
        wait_for_master(uri, proc=procs[0])
        procs.append(Proc([SYSTEM_PYTHON, "-c", code], env))
        node = start_node("plot", {"master": uri}, env)
        source = PlotSource(node)
        try:
            wait_until(lambda: ("/level", "std_msgs/Float64") in source.topic_types(), what="rospy's publisher")
            source.add("/level/data")
            wait_until(lambda: len(source.data()["/level/data"][1]) >= 20, what="rospy's messages in the plot")
            t, v = source.data()["/level/data"]
            assert np.all(np.diff(v) > 0) and np.all(np.diff(t) >= 0)  # in the order published
        finally:
            source.close()
            node.shutdown("test over")
    finally:
        for proc in reversed(procs):
            proc.stop()
