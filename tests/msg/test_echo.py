"""kame.msg.echo: what rostopic echo prints (YAML text, --noarr/--nostr, -w, --offset, -p CSV).

Expected texts are what Debian's rostopic 1.15.15 prints for the same messages.
"""

from __future__ import annotations

from geometry_msgs.msg import Point, Pose, PoseArray, Quaternion
from kame.msg.echo import as_field_value, csv_header, csv_row, field_filter, to_yaml, transform
from kame.rostime import Time
from sensor_msgs.msg import JointState
from std_msgs.msg import Bool, Header, UInt8MultiArray
from turtlesim.msg import Pose as TurtlePose

STAMP = Time(1795311367, 122221231)


def joint_state() -> JointState:
    return JointState(header=Header(seq=1, stamp=STAMP, frame_id="base"), name=["a", "b"], position=[1.0, 2.5])


def test_yaml_text_of_a_message() -> None:
    assert to_yaml(joint_state()) == (
        "header: \n  seq: 1\n  stamp: \n    secs: 1795311367\n    nsecs: 122221231\n  frame_id: \"base\"\n"
        "name: \n  - a\n  - b\nposition: [1.0, 2.5]\nvelocity: []\neffort: []")


def test_arrays_of_messages_bytes_and_empty_strings() -> None:
    msg = PoseArray(poses=[Pose(Point(1.0, 0.0, 0.0), Quaternion(0.0, 0.0, 0.0, 1.0))])
    assert "poses: \n  - \n    position: \n      x: 1.0\n" in to_yaml(msg)
    assert "frame_id: ''" in to_yaml(msg)
    assert to_yaml(UInt8MultiArray(data=bytes([1, 2, 255]))).endswith("data: [1, 2, 255]")
    assert to_yaml(Bool(data=True)) == "data: True"


def test_fixed_width_numbers() -> None:
    pose = TurtlePose(x=5.544444561004639, y=10.0, theta=0.0)
    assert to_yaml(pose, width=4) == "x: 5.54\ny: 10.0\ntheta: 0.00\nlinear_velocity: 0.00\nangular_velocity: 0.00"
    header = Header(seq=7, stamp=Time(3, 4))
    assert to_yaml(header, width=3) == "seq:   7\nstamp: \n  secs:   3\n  nsecs:   4\nframe_id: ''"
    assert to_yaml([1.5, 2.25], width=3) == "[1.5, 2.2]"  # genpy cuts, it does not round


def test_time_offsets() -> None:
    assert to_yaml(Header(stamp=Time(10, 0)), time_offset=Time(12, 500)).startswith(
        "seq: 0\nstamp: \n  secs: -3\n  nsecs: 999999500")


def test_noarr_and_nostr_placeholders() -> None:
    js = joint_state()
    noarr = to_yaml(transform(js, None, nostr=False, noarr=True))
    assert 'name: "<array type: string, length: 2>"\nposition: "<array type: float64, length: 2>"' in noarr
    assert '  frame_id: "base"' in noarr
    nostr = to_yaml(transform(js, None, nostr=True, noarr=False))
    assert '  frame_id: "<string length: 4>"\nname: "<array type: string, length: 2>"\nposition: [1.0, 2.5]' in nostr
    # like rostopic, strings inside arrays of messages are left alone
    arr = PoseArray(header=Header(frame_id="map"), poses=[Pose()])
    assert 'frame_id: "<string length: 3>"' in to_yaml(transform(arr, None, nostr=True, noarr=False))
    assert transform(js.position, "float64[]", nostr=False, noarr=True) == "<array type: float64, length: 2>"
    assert transform(2.5, "float64", nostr=True, noarr=True) == 2.5


def test_field_values() -> None:
    assert as_field_value(b"\x01\x02", "uint8[]") == [1, 2]
    assert to_yaml(["a", "b"]) == "\n- a\n- b"
    assert to_yaml(Time(3, 4)) == "\nsecs: 3\nnsecs:         4"


def test_csv() -> None:
    js = joint_state()
    assert csv_header(js) == ("%time,field.header.seq,field.header.stamp,field.header.frame_id,field.name0,"
                              "field.name1,field.position0,field.position1")
    assert csv_row(js, now=Time(1, 0)) == "1795311367122221231,1,1795311367122221231,base,a,b,1.0,2.5"
    pose = TurtlePose(x=1.5)
    assert csv_row(pose, now=Time(2, 5)) == "2000000005,1.5,0.0,0.0,0.0,0.0"
    assert csv_row(pose, now=Time(2, 5), time_offset=Time(1, 0)) == "1000000005,1.5,0.0,0.0,0.0,0.0"
    assert csv_header([1.0, 2.5]) == "%time,field0,field1"
    assert csv_row(Bool(data=True), now=Time(0, 1)) == "1,1"
    only = field_filter(nostr=True, noarr=True)
    assert csv_header(js, only) == "%time,field.header.seq,field.header.stamp"
    assert csv_header(UInt8MultiArray(data=b"\x01")) == "%time,field.layout.data_offset"  # as rostopic on Python 3
