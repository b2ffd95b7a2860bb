"""MCAP: a bag recorded by kame, converted with `rosbag convert`, read by the `mcap` library (with
mcap-ros1-support's decoder), by @mcap/core in Node (Foxglove's reader), and by kame's own
rosbag info, play and Bag API; round trips keep every message's bytes.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import xmlrpc.client
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from ..support import Proc, free_port, kame_command, ros_env, wait_for_master, wait_until

pytest.importorskip("mcap")
pytest.importorskip("mcap_ros1")

WEB = Path(__file__).resolve().parent

PUBLISHER = """
import rospy
from sensor_msgs.msg import Image
from std_msgs.msg import String
rospy.init_node("source")
image = rospy.Publisher("/camera/image_raw", Image, queue_size=10)
chatter = rospy.Publisher("/chatter", String, queue_size=10)
w, h = 64, 48
rate = rospy.Rate(30)
n = 0
print("ready", flush=True)
while not rospy.is_shutdown():
    msg = Image(height=h, width=w, encoding="rgb8", step=w * 3, data=bytes((n + i) % 256 for i in range(w * h * 3)))
    msg.header.stamp = rospy.Time.now()
    msg.header.frame_id = "camera"
    image.publish(msg)
    chatter.publish(String(data=f"hello {n}"))
    n += 1
    try:
        rate.sleep()
    except rospy.ROSInterruptException:
        break
"""


LISTENER = """
import rospy
from std_msgs.msg import String
rospy.init_node("listener")
heard = []
def hear(msg):
    heard.append(msg.data)
    print("data: " + msg.data, flush=True)
    if len(heard) == 3:
        rospy.signal_shutdown("heard 3")
rospy.Subscriber("/chatter", String, hear)
rospy.spin()
"""


def checksum(data: bytes) -> int:
    total = 0
    for i, b in enumerate(data):
        total = (total + b * ((i % 251) + 1)) % 1000000007
    return total


def rosbag(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    done = subprocess.run(kame_command("kame.cli.rosbag", *args), cwd=cwd, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return done


@pytest.fixture(scope="module")
def recorded(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Path]:
    """A bag kame's rosbag record made of 10 images and 10 strings."""
    home = tmp_path_factory.mktemp("mcap")
    uri = f"http://127.0.0.1:{free_port()}/"
    env = ros_env(home, uri)
    master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", uri.rsplit(":", 1)[1][:-1]), env)
    procs: list[Proc] = []
    try:
        wait_for_master(uri, proc=master)
        procs.append(Proc([sys.executable, "-c", PUBLISHER], env))
        procs[-1].wait_line("ready", timeout=30)
        record = subprocess.run(kame_command("kame.cli.rosbag", "record", "-q", "-O", "rec.bag", "-l", "10",
                                             "/chatter", "/camera/image_raw"),
                                cwd=home, env=env, capture_output=True, text=True, timeout=60)
        assert record.returncode == 0, record.stderr
    finally:
        for proc in procs:
            proc.stop()
        master.stop()
    yield home / "rec.bag"


def raw_messages(path: Path) -> list[tuple[str, tuple[int, int], bytes, dict[str, str]]]:
    from kame.bag.reader import open_reader

    with open_reader(path) as reader:
        return [(m.conn.topic, m.time, m.data, dict(m.conn.header)) for m in reader.messages()]


def test_mcap_library_reads_what_kame_converted(recorded: Path, tmp_path: Path) -> None:
    from mcap.reader import make_reader
    from mcap_ros1.decoder import DecoderFactory

    out = tmp_path / "rec.mcap"
    rosbag("convert", str(recorded), str(out), cwd=tmp_path)
    original = raw_messages(recorded)
    assert len(original) == 20
    with open(out, "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        assert reader.get_header().profile == "ros1"
        decoded = list(reader.iter_decoded_messages(log_time_order=True))
    assert [(c.topic, m.log_time, m.data) for _, c, m, _ in decoded] == [
        (topic, t[0] * 1_000_000_000 + t[1], data) for topic, t, data, _ in original]
    for (schema, channel, _, msg), (_, _, _, header) in zip(decoded, original, strict=True):
        assert schema is not None and schema.encoding == "ros1msg" and schema.name == header["type"]
        assert schema.data.decode() == header["message_definition"]
        assert channel.message_encoding == "ros1" and channel.metadata["md5sum"] == header["md5sum"]
        if channel.topic == "/chatter":
            assert msg.data.startswith("hello ")
        else:
            assert (msg.width, msg.height, msg.encoding, len(msg.data)) == (64, 48, "rgb8", 64 * 48 * 3)


@pytest.mark.skipif(shutil.which("node") is None or not (WEB / "node_modules" / "@mcap").is_dir(),
                    reason="node or tests/web/node_modules is missing (bash scripts/install-web-peers.sh)")
def test_foxglove_mcap_reader_reads_what_kame_converted(recorded: Path, tmp_path: Path) -> None:
    out = tmp_path / "rec.mcap"
    rosbag("convert", "--compression", "none", str(recorded), str(out), cwd=tmp_path)  # @mcap/core has no zstd
    done = subprocess.run(["node", str(WEB / "mcap_read.js"), str(out)], cwd=WEB, capture_output=True, text=True,
                          timeout=60)
    assert done.returncode == 0, done.stderr
    lines: list[dict[str, Any]] = [json.loads(line) for line in done.stdout.splitlines()]
    assert lines[-1] == {"done": True, "profile": "ros1"}
    original = raw_messages(recorded)
    assert [(m["topic"], int(m["logTime"]), m["checksum"]) for m in lines[:-1]] == [
        (topic, t[0] * 1_000_000_000 + t[1], checksum(data)) for topic, t, data, _ in original]
    from kame.client.bag import Bag

    with Bag(str(recorded)) as bag:
        kame_read = [msg for _, msg, _ in bag.read_messages()]
    for line, msg in zip(lines[:-1], kame_read, strict=True):
        if line["topic"] == "/chatter":
            assert line["message"] == {"data": msg.data}
        else:
            assert line["message"]["header"]["frame_id"] == "camera"
            assert line["message"]["data"] == {"length": len(msg.data), "checksum": checksum(bytes(msg.data))}


@pytest.mark.parametrize("compression", ["zstd", "lz4", "none"])
def test_round_trips_keep_every_byte(recorded: Path, tmp_path: Path, compression: str) -> None:
    there, back, again = tmp_path / "a.mcap", tmp_path / "b.bag", tmp_path / "c.mcap"
    rosbag("convert", "--compression", compression, str(recorded), str(there), cwd=tmp_path)
    rosbag("convert", str(there), str(back), cwd=tmp_path)
    rosbag("convert", "--compression", compression, str(back), str(again), cwd=tmp_path)
    original = raw_messages(recorded)
    assert raw_messages(back) == original  # bytes, receive times and connection headers
    assert raw_messages(there) == raw_messages(again) == original


def test_rosbag_info_and_the_bag_api_read_mcap(recorded: Path, tmp_path: Path) -> None:
    out = tmp_path / "rec.mcap"
    rosbag("convert", str(recorded), str(out), cwd=tmp_path)
    text = [" ".join(line.split()) for line in rosbag("info", str(out), cwd=tmp_path).stdout.splitlines()]
    bag_info = [" ".join(line.split()) for line in rosbag("info", str(recorded), cwd=tmp_path).stdout.splitlines()]
    assert text[1] == "version: mcap" and bag_info[1] == "version: 2.0"
    assert text[2:5] == bag_info[2:5]  # duration, start, end
    assert "messages: 20" in text and any(line.startswith("compression: zstd [1/1 chunks; ") for line in text)
    assert text[-4:] == bag_info[-4:] == [
        "types: sensor_msgs/Image [060021388200f6f0f447d0fcd9c64743]",
        "std_msgs/String [992ce8a1687cec8c8bd883ec73ca41d1]",
        "topics: /camera/image_raw 10 msgs : sensor_msgs/Image", "/chatter 10 msgs : std_msgs/String"]
    from kame.client.bag import Bag

    with Bag(str(out)) as mcap_bag, Bag(str(recorded)) as bag:
        assert mcap_bag.get_message_count() == 20
        assert mcap_bag.get_type_and_topic_info().topics == bag.get_type_and_topic_info().topics
        from_mcap = [(t, m, s) for t, m, s in mcap_bag.read_messages(topics=["/chatter"])]
        assert from_mcap == list(bag.read_messages(topics=["/chatter"]))


def test_rosbag_play_plays_mcap(recorded: Path, tmp_path: Path) -> None:
    out = tmp_path / "rec.mcap"
    rosbag("convert", str(recorded), str(out), cwd=tmp_path)
    uri = f"http://127.0.0.1:{free_port()}/"
    env = ros_env(tmp_path / "home", uri)
    master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", uri.rsplit(":", 1)[1][:-1]), env)
    try:
        wait_for_master(uri, proc=master)
        echo = Proc([sys.executable, "-c", LISTENER], env)
        master_api = xmlrpc.client.ServerProxy(uri)
        assert wait_until(lambda: any(topic == "/chatter"
                                      for topic, _ in master_api.getSystemState("/test")[2][1]))
        play = subprocess.run(kame_command("kame.cli.rosbag", "play", "-q", str(out)), env=env, capture_output=True,
                              text=True, timeout=60)
        assert play.returncode == 0, play.stderr
        echo.popen.wait(20)
        printed, _ = echo.stop()
    finally:
        master.stop()
    texts = [line[len("data: "):] for line in printed.splitlines() if line.startswith("data:")]
    first = int(texts[0].split()[1])
    assert texts == [f"hello {first + i}" for i in range(3)]


def test_rosbag_record_mcap(tmp_path: Path) -> None:
    """`rosbag record --mcap` writes what the mcap library reads, with the ros1 profile."""
    from mcap.reader import make_reader
    from mcap_ros1.decoder import DecoderFactory

    uri = f"http://127.0.0.1:{free_port()}/"
    env = ros_env(tmp_path / "home", uri)
    master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", uri.rsplit(":", 1)[1][:-1]), env)
    source = None
    try:
        wait_for_master(uri, proc=master)
        source = Proc([sys.executable, "-c", PUBLISHER], env)
        source.wait_line("ready", timeout=30)
        record = subprocess.run(kame_command("kame.cli.rosbag", "record", "--mcap", "-q", "-O", "live.mcap", "-l", "5",
                                             "/chatter", "/camera/image_raw"),
                                cwd=tmp_path, env=env, capture_output=True, text=True, timeout=60)
        assert record.returncode == 0, record.stderr
    finally:
        if source is not None:
            source.stop()
        master.stop()
    with open(tmp_path / "live.mcap", "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        assert reader.get_header().profile == "ros1"
        decoded = list(reader.iter_decoded_messages(log_time_order=True))
    topics = [c.topic for _, c, _, _ in decoded]
    assert topics.count("/chatter") == 5 and topics.count("/camera/image_raw") == 5
    texts = [m.data for _, c, _, m in decoded if c.topic == "/chatter"]
    first = int(texts[0].split()[1])
    assert texts == [f"hello {first + i}" for i in range(5)]
    assert all(c.metadata["callerid"] == "/source" for _, c, _, _ in decoded)
    info = rosbag("info", str(tmp_path / "live.mcap"), cwd=tmp_path).stdout
    assert "messages:     10" in info


def test_kame_reads_an_mcap_written_by_mcap_ros1(tmp_path: Path) -> None:
    """An MCAP file from another writer (mcap-ros1-support's, whose channels carry no md5sum):
    the Bag API and rosbag info read it, the md5sum made from the schema."""
    from mcap_ros1.writer import Writer

    from kame.client.bag import Bag
    from std_msgs.msg import String

    path = tmp_path / "theirs.mcap"
    with open(path, "wb") as f:
        writer = Writer(f)
        for i in range(3):
            writer.write_message("/chatter", String(data=f"x{i}"), log_time=10**9 + i, publish_time=10**9 + i)
        writer.finish()
    with Bag(str(path)) as bag:
        assert [(t, m.data, s.to_nsec()) for t, m, s in bag.read_messages()] == [
            ("/chatter", f"x{i}", 10**9 + i) for i in range(3)]
        assert bag.get_type_and_topic_info().msg_types == {"std_msgs/String": String._md5sum}
    info = [" ".join(line.split()) for line in rosbag("info", str(path), cwd=tmp_path).stdout.splitlines()]
    assert "topics: /chatter 3 msgs : std_msgs/String" in info
