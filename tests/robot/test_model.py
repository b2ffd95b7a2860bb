"""The URDF joint model behind robot_state_publisher and joint_state_publisher: fixed and moving
joints' transforms, mimic joints, joint_state_publisher's starting positions and sliders, and
its window (offscreen)."""

from __future__ import annotations

import math
import threading

import pytest

pytest.importorskip("urdf_parser_py", reason="the robot programs parse URDF with urdf_parser_py (kame[robot])")

from kame.robot.model import JointPositions, RobotTree

ARM = """<robot name="arm">
  <link name="base"/><link name="upper"/><link name="lower"/><link name="slide"/><link name="finger"/>
  <link name="float"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 1" rpy="0 0 1.5707963267948966"/><axis xyz="0 0 2"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="elbow" type="continuous"><parent link="upper"/><child link="lower"/><origin xyz="1 0 0"/>
    <axis xyz="0 1 0"/></joint>
  <joint name="rail" type="prismatic"><parent link="base"/><child link="slide"/><axis xyz="1 0 0"/>
    <limit lower="0.2" upper="0.6" effort="1" velocity="1"/></joint>
  <joint name="thumb" type="revolute"><parent link="upper"/><child link="finger"/>
    <mimic joint="shoulder" multiplier="2" offset="0.1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="weld" type="floating"><parent link="base"/><child link="float"/><origin xyz="0 5 0"/></joint>
</robot>"""


def _close(found: tuple[float, ...], wanted: tuple[float, ...]) -> bool:
    return all(math.isclose(a, b, abs_tol=1e-9) for a, b in zip(found, wanted, strict=True))


def test_fixed_joints_make_the_static_transforms_and_moving_ones_follow_their_positions() -> None:
    tree = RobotTree(ARM)
    assert [j.name for j in tree.fixed] == ["weld"]  # floating: fixed, as kdl_parser makes it
    assert tree.static_transforms() == [("base", "float", (0.0, 5.0, 0.0), (0.0, 0.0, 0.0, 1.0))]
    moved = {child: (t, q) for _, child, t, q in tree.moving_transforms({"shoulder": 0.5, "rail": 0.3})}
    # the origin's quarter turn about z, then 0.5 rad more about the (normalised) axis z
    t, q = moved["upper"]
    half = (math.pi / 2 + 0.5) / 2
    assert _close(t, (0.0, 0.0, 1.0)) and _close(q, (0.0, 0.0, math.sin(half), math.cos(half)))
    assert _close(moved["slide"][0], (0.3, 0.0, 0.0))
    assert "lower" not in moved  # elbow: nothing was said of it, so nothing is published
    t, q = moved["finger"]  # thumb mimics the shoulder: 2 * 0.5 + 0.1, about the default axis x
    assert _close(q, (math.sin(0.55), 0.0, 0.0, math.cos(0.55)))
    (_, _, t, q), = tree.moving_transforms({"elbow": math.pi})
    assert _close(t, (1.0, 0.0, 0.0)) and _close(q, (0.0, 1.0, 0.0, math.cos(math.pi / 2)))


def test_a_text_that_is_not_a_urdf_is_refused() -> None:
    with pytest.raises(ValueError, match="cannot parse the robot description"):
        RobotTree("<robot><link name='a'>")


def _robot(links: str, joints: dict[str, tuple[str, str]]) -> str:
    text = "".join(f"<link name='{link}'/>" for link in links.split())
    for name, (parent, child) in joints.items():
        text += f"<joint name='{name}' type='fixed'><parent link='{parent}'/><child link='{child}'/></joint>"
    return f"<robot name='r'>{text}</robot>"


@pytest.mark.parametrize(("links", "joints", "problem"), [
    ("a b c", {"ab": ("a", "b"), "bc": ("b", "c"), "ca": ("c", "a")},
     "No roots detected, invalid URDF: every link has a parent joint, and joints [ab] -> [bc] -> [ca] form a loop"),
    ("a", {"aa": ("a", "a")},
     "No roots detected, invalid URDF: every link has a parent joint, and joints [aa] form a loop"),
    ("r a b", {"ra": ("r", "a"), "ab": ("a", "b"), "ba": ("b", "a")},
     "link [a] is the child of two joints, [ra] and [ba]: invalid URDF, a robot is a tree"),
    ("r a b", {"ra": ("r", "a"), "ab": ("a", "b"), "bb": ("b", "b")},
     "link [b] is the child of two joints, [ab] and [bb]: invalid URDF, a robot is a tree"),
    ("r b c", {"bc": ("b", "c"), "cb": ("c", "b")},
     "joints [bc] -> [cb] form a loop, invalid URDF: a robot is a tree from its root [r]"),
    ("r a", {}, "Multiple roots detected, invalid URDF: links [r], [a] have no parent joint"),
    ("r a", {"ra": ("r", "a"), "ax": ("a", "x")}, "child link [x] of joint [ax] not found"),
])
def test_a_urdf_that_is_not_one_tree_is_refused_naming_its_loop_or_roots(
        links: str, joints: dict[str, tuple[str, str]], problem: str) -> None:
    # robot_state_publisher published such a robot's joints as they came: a tf loop
    with pytest.raises(ValueError) as refused:
        RobotTree(_robot(links, joints))
    assert str(refused.value) == problem


def test_joint_state_publisher_starts_at_zero_or_mid_range_and_mimic_joints_follow() -> None:
    positions = JointPositions(RobotTree(ARM), zeros={"elbow": 0.25})
    assert list(positions.free) == ["shoulder", "elbow", "rail"]  # thumb mimics, weld is fixed
    assert positions.names_and_positions() == (["shoulder", "elbow", "rail", "thumb"],
                                               [0.0, 0.25, pytest.approx(0.4), 0.1])
    assert positions.free["elbow"].lower == -math.pi and positions.free["elbow"].upper == math.pi
    positions.set("shoulder", 5.0)  # clamped to the limit
    assert positions.free["shoulder"].position == 1.0
    assert positions.names_and_positions()[1][3] == pytest.approx(2.1)
    positions.update(["rail", "unknown"], [0.5, 1.0])
    assert positions.free["rail"].position == 0.5
    assert positions.slider_value("rail") == 7500
    assert positions.from_slider("rail", 2500) == pytest.approx(0.3)
    positions.randomize(lambda lower, upper: upper)
    assert [j.position for j in positions.free.values()] == [1.0, math.pi, 0.6]
    positions.center()
    assert [j.position for j in positions.free.values()] == [0.0, 0.25, pytest.approx(0.4)]


class _Publishing:
    """What the window reads of joint_state_publisher: its positions and their lock."""

    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.positions = JointPositions(RobotTree(ARM))


def test_the_slider_window_moves_the_joints(qtbot) -> None:  # type: ignore[no-untyped-def]
    pytest.importorskip("PySide6")
    from kame.robot.sliders import SliderWindow

    publishing = _Publishing()
    window = SliderWindow(publishing)  # type: ignore[arg-type]
    qtbot.addWidget(window)
    assert sorted(window.sliders) == ["elbow", "rail", "shoulder"]
    assert window.sliders["rail"].value() == 5000 and window.values["rail"].text() == "0.40"
    window.sliders["shoulder"].setValue(10000)
    assert publishing.positions.free["shoulder"].position == pytest.approx(1.0)
    assert window.values["shoulder"].text() == "1.00"
    window.center()
    assert publishing.positions.free["shoulder"].position == 0.0 and window.sliders["shoulder"].value() == 5000
    window.randomize()
    shoulder = publishing.positions.free["shoulder"].position
    assert -1.0 <= shoulder <= 1.0 and window.sliders["shoulder"].value() == publishing.positions.slider_value(
        "shoulder")
