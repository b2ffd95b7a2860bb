"""rosbag on the command line, end to end against kame's roscore: record (limit, Ctrl-C, a
killed recorder repaired by reindex), play into a subscriber, filter, compress, decompress.
Every process is started through tests.support.Proc and stopped by its PID."""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

import rosbag
from tests.support import SYSTEM_PYTHON, Proc, free_port, have_debian_ros, ros_env, wait_for_master

BIN = Path(sys.executable).parent


@pytest.fixture(scope="module")
def core(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, str]]:
    home = tmp_path_factory.mktemp("bagcli")
    port = free_port()
    env = ros_env(home, f"http://127.0.0.1:{port}/")
    proc = Proc([str(BIN / "roscore"), "-p", str(port)], env)
    try:
        wait_for_master(env["ROS_MASTER_URI"], proc=proc)
        yield env
    finally:
        proc.stop()


def _run(env: dict[str, str], *args: str, cwd: Path, timeout: float = 30) -> subprocess.CompletedProcess[str]:
    return subprocess.run([str(BIN / "rosbag"), *args], env=env, cwd=cwd, capture_output=True, text=True,
                          timeout=timeout)


def _talker(env: dict[str, str], topic: str = "/chatter", rate: str = "100") -> Proc:
    return Proc([str(BIN / "rostopic"), "pub", "-r", rate, topic, "std_msgs/String", "data: hi"], env)


def test_record_with_limit_then_play_into_a_subscriber(core: dict[str, str], tmp_path: Path) -> None:
    talker = _talker(core)
    try:
        res = _run(core, "record", "-O", "rec", "/chatter", "-l", "20", cwd=tmp_path)
    finally:
        talker.stop()
    assert res.returncode == 0, res.stderr
    assert "Subscribing to /chatter" in res.stdout and "Recording to 'rec.bag'." in res.stdout
    with rosbag.Bag(tmp_path / "rec.bag") as bag:
        msgs = list(bag.read_messages(return_connection_header=True))
    assert len(msgs) == 20 and all(m.message.data == "hi" for m in msgs)
    assert msgs[0].connection_header["callerid"].startswith("/rostopic_")
    echo = Proc([str(BIN / "rostopic"), "echo", "/chatter", "-n", "5"], core)
    try:
        # -d alone is a guess at how long the echo takes to find the topic and connect: the 20
        # messages go out in 50 ms, so a slow echo missed them. Wait for the subscriber too.
        play = _run(core, "play", "-q", "-r", "4", "-d", "0.5", "--wait-for-subscribers", "rec.bag", cwd=tmp_path)
        assert play.returncode == 0, play.stderr
        assert "Hit space to toggle paused, or 's' to step." in play.stdout and play.stdout.endswith("Done.\n")
        echo.popen.wait(10)
    finally:
        out, _ = echo.stop()
    assert out.count('data: "hi"') == 5


def wait_for_bytes(path: Path, size: int = 20_000, timeout: float = 30.0) -> None:
    """Until the recorder has written `size` bytes of chunks (a String 'hi' takes under 70 bytes
    with its index, so 20 kB is well over the 100 messages the test wants), not for a fixed time:
    under load the talker and the recorder's connection can take most of a second or two to get going."""
    deadline = time.monotonic() + timeout
    while not (path.exists() and path.stat().st_size > size):
        assert time.monotonic() < deadline, f"{path} did not reach {size} bytes in {timeout}s"
        time.sleep(0.05)


def test_ctrl_c_closes_and_kill_is_repaired_by_reindex(core: dict[str, str], tmp_path: Path) -> None:
    talker = _talker(core, "/fast", "500")
    try:
        rec = Proc([str(BIN / "rosbag"), "record", "-O", "clean", "-a", "--chunksize", "4"], core, cwd=tmp_path)
        rec.wait_line("Recording to")
        wait_for_bytes(tmp_path / "clean.bag.active")
        rec.stop()
        assert (tmp_path / "clean.bag").exists() and not (tmp_path / "clean.bag.active").exists()
        with rosbag.Bag(tmp_path / "clean.bag") as bag:
            assert bag.get_message_count("/fast") > 100
        killed = Proc([str(BIN / "rosbag"), "record", "-O", "killed", "/fast", "--chunksize", "4"], core, cwd=tmp_path)
        killed.wait_line("Recording to")
        wait_for_bytes(tmp_path / "killed.bag.active")
        os.kill(killed.pid, signal.SIGKILL)
        killed.stop()
    finally:
        talker.stop()
    active = tmp_path / "killed.bag.active"
    assert active.exists()
    with pytest.raises(rosbag.ROSBagUnindexedException):
        rosbag.Bag(active)
    res = _run(core, "reindex", str(active), cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    with rosbag.Bag(active) as bag:
        assert bag.get_message_count() > 100


STEADY_TALKER = """
import sys, time, rospy
from std_msgs.msg import String
rospy.init_node("steady", anonymous=True)
pub = rospy.Publisher("/steady", String, queue_size=1000)
rate = rospy.Rate(200)
seq = 0
while not rospy.is_shutdown():
    now = time.time()
    pub.publish(String(data=f"{seq:08d} {now:.6f}".ljust(96)))  # 100 bytes serialized
    sys.stdout.write(f"{seq} {now}\\n")  # one write: SIGINT between print's pieces left a line without its stamp
    sys.stdout.flush()
    seq += 1
    rate.sleep()
"""


def test_a_recorder_killed_by_sigkill_keeps_all_but_its_last_second(core: dict[str, str], tmp_path: Path) -> None:
    """200 Hz of 100-byte messages, SIGKILL after 4 s: reindex finds >= 99% of what was published
    more than a second before the kill (rosbag's recorder keeps its open chunk, 768 kB, in memory)."""
    talker = Proc([sys.executable, "-c", STEADY_TALKER], core)
    try:
        talker.wait_line(" ")
        rec = Proc([str(BIN / "rosbag"), "record", "-O", "steady", "/steady"], core, cwd=tmp_path)
        rec.wait_line("Recording to")
        start = len(talker.out)
        deadline = time.monotonic() + 30
        while len(talker.out) < start + 800:  # 4 s of messages published while recording
            assert time.monotonic() < deadline, "the talker stopped publishing"
            time.sleep(0.05)
        os.kill(rec.pid, signal.SIGKILL)
        killed_at = time.time()
        rec.stop()
    finally:
        published_lines, _ = talker.stop()
    res = _run(core, "reindex", "steady.bag.active", cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    with rosbag.Bag(tmp_path / "steady.bag.active") as bag:
        recorded = {int(m.message.data.split()[0]) for m in bag.read_messages()}
    assert recorded, "nothing recovered"
    published = [line.split() for line in published_lines.splitlines()]
    due = {int(seq) for seq, stamp in published if int(seq) >= min(recorded) and float(stamp) < killed_at - 1.0}
    kept = len(due & recorded)
    print(f"kept {kept} of {len(due)} messages published more than 1 s before the kill")
    assert len(due) > 400 and kept >= 0.99 * len(due), (kept, len(due))


@pytest.mark.skipif(not have_debian_ros(), reason="Debian's ROS 1 is not installed")
def test_reindex_recovers_the_torn_chunk_of_a_killed_cpp_recorder(core: dict[str, str], tmp_path: Path) -> None:
    # ROS's C++ recorder streams its open chunk under a zero-size header too; Debian's reindex
    # drops that chunk (0 messages here), kame's keeps its whole records, and Debian reads the result.
    talker = _talker(core, "/fast", "200")
    debian_env = {"PATH": "/usr/bin:/bin", "ROS_MASTER_URI": core["ROS_MASTER_URI"], "ROS_HOME": str(tmp_path)}
    try:
        rec = Proc(["/usr/lib/rosbag/record", "-O", "cpp", "/fast"], debian_env, cwd=tmp_path)
        wait_for_bytes(tmp_path / "cpp.bag.active", 20_000)
        os.kill(rec.pid, signal.SIGKILL)
        rec.stop()
    finally:
        talker.stop()
    res = _run(core, "reindex", "cpp.bag.active", cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    with rosbag.Bag(tmp_path / "cpp.bag.active") as bag:
        kept = bag.get_message_count("/fast")
    assert kept > 100
    info = subprocess.run([SYSTEM_PYTHON, "/usr/bin/rosbag", "info", "cpp.bag.active"], env=debian_env, cwd=tmp_path,
                          capture_output=True, text=True, timeout=60)
    assert f"messages:    {kept}" in info.stdout, info.stderr


@contextlib.contextmanager
def _tmpfs(path: Path, options: str) -> Iterator[Path]:
    """A small tmpfs at `path` (the test is skipped where we may not mount one: not root)."""
    path.mkdir()
    if os.geteuid() != 0 or subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", str(path)],
                                           capture_output=True).returncode != 0:
        pytest.skip("cannot mount a tmpfs here")
    try:
        yield path
    finally:
        subprocess.run(["umount", str(path)], check=True)


def test_a_full_disk_or_a_read_only_one_ends_the_recording_with_a_readable_bag(core: dict[str, str],
                                                                               tmp_path: Path) -> None:
    talker = Proc([str(BIN / "rostopic"), "pub", "-r", "50", "/big", "std_msgs/String", "data: " + "x" * 20000], core)
    try:
        with _tmpfs(tmp_path / "full", "size=400k") as full:
            res = _run(core, "record", "-O", str(full / "f.bag"), "/big", cwd=tmp_path)
            assert res.returncode == 1
            assert f"Error writing: cannot write {full}/f.bag.active: No space left on device" in res.stderr
            with rosbag.Bag(full / "f.bag") as bag:  # closed with what reached the disk
                assert bag.get_message_count("/big") >= 5
        with _tmpfs(tmp_path / "split", "size=400k") as full:
            split = _run(core, "record", "-O", str(full / "s.bag"), "--split", "--size", "0.1", "/big", cwd=tmp_path)
            assert split.returncode == 1 and "No space left on device" in split.stderr
            parts = sorted(full.glob("s_*.bag"))
            assert len(parts) >= 2 and not list(full.glob("*.active"))
            counts = []
            for part in parts:  # each closed, the last with what fitted (maybe nothing)
                with rosbag.Bag(part) as bag:
                    counts.append(bag.get_message_count("/big"))
            assert all(n >= 1 for n in counts[:-1])
        with _tmpfs(tmp_path / "ro", "ro,size=100k") as read_only:
            res = _run(core, "record", "-O", str(read_only / "r.bag"), "/big", cwd=tmp_path)
            assert res.returncode == 1
            assert f"Error writing: Error opening file: {read_only}/r.bag.active" in res.stderr
    finally:
        talker.stop()


def test_filter_compress_decompress(core: dict[str, str], tmp_path: Path) -> None:
    from rospy import Time
    from std_msgs.msg import String

    with rosbag.Bag(tmp_path / "in.bag", "w") as bag:
        for i in range(200):
            bag.write("/a" if i % 2 else "/b", String(data=str(i)), Time(10 + i, 0))
    res = _run(core, "filter", "in.bag", "out.bag", "topic == '/a' and int(m.data) > 100", cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    with rosbag.Bag(tmp_path / "out.bag") as bag:
        assert [m.message.data for m in bag.read_messages()] == [str(i) for i in range(101, 200, 2)]
    for args, kind in ((["compress", "--lz4"], "lz4"), (["compress"], "bz2"), (["decompress"], "none")):
        res = _run(core, *args, "-f", "in.bag", cwd=tmp_path)
        assert res.returncode == 0, res.stderr
        with rosbag.Bag(tmp_path / "in.bag") as bag:
            assert bag.get_compression_info().compression == kind
            assert [m.message.data for m in bag.read_messages()] == [str(i) for i in range(200)]
    assert (tmp_path / "in.orig.bag").exists()
    res = _run(core, "compress", "in.bag", cwd=tmp_path)
    assert "Skipping in.bag. Backup path in.orig.bag already exists." in res.stderr


def test_play_of_a_bag_damaged_past_its_index_plays_what_it_can_then_says_why(core: dict[str, str],
                                                                               tmp_path: Path) -> None:
    from kame.bag.reader import BagReader
    from rospy import Time
    from std_msgs.msg import String

    path = tmp_path / "d.bag"
    with rosbag.Bag(path, "w", chunk_threshold=300) as bag:
        for i in range(30):
            bag.write("/d", String(data="x" * i), Time(100, i * 10_000_000))
    data = bytearray(path.read_bytes())
    with BagReader(path) as reader:
        pos = reader.chunk_infos[-1].pos
    data[pos:pos + 4] = (0xFFFFFFF0).to_bytes(4, "little")  # the last chunk's header length
    path.write_bytes(data)
    play = _run(core, "play", "-q", "-d", "0", "d.bag", cwd=tmp_path)
    assert play.returncode == 1
    assert "Traceback" not in play.stderr
    assert "[FATAL]" in play.stderr and "claims a 4294967280-byte header" in play.stderr


def test_record_into_a_missing_folder_or_onto_a_full_disk_says_so_and_ends(core: dict[str, str],
                                                                           tmp_path: Path) -> None:
    import resource

    talker = Proc([str(BIN / "rostopic"), "pub", "-r", "50", "/big", "std_msgs/String", "data: " + "x" * 20000], core)
    try:
        res = _run(core, "record", "-O", str(tmp_path / "missing" / "r.bag"), "/big", cwd=tmp_path)
        assert res.returncode == 1
        assert f"Error writing: Error opening file: {tmp_path}/missing/r.bag.active" in res.stderr
        assert not (tmp_path / "missing").exists()  # rosbag makes no folder for it

        def small_files() -> None:  # a full disk, as the writer sees it: EFBIG past 100 KB
            resource.setrlimit(resource.RLIMIT_FSIZE, (100_000, 100_000))

        full = subprocess.run([str(BIN / "rosbag"), "record", "-O", "f.bag", "/big"], env=core, cwd=tmp_path,
                              capture_output=True, text=True, timeout=30, preexec_fn=small_files)
    finally:
        talker.stop()
    assert full.returncode == 1
    assert "Error writing: cannot write f.bag.active: File too large" in full.stderr
    assert "Traceback" not in full.stderr
    with rosbag.Bag(tmp_path / "f.bag") as bag:  # ended with what reached the disk
        assert bag.get_message_count("/big") >= 1


def test_record_with_a_duration_ends_on_time_with_no_messages(core: dict[str, str], tmp_path: Path) -> None:
    # The writer waits on its queue until the duration is up, not for a message that never comes
    # (rosbag's recorder checks the duration while idle too).
    res = _run(core, "record", "-O", "idle", "--duration=1", "/nobody_publishes", cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    with rosbag.Bag(tmp_path / "idle.bag") as bag:
        assert bag.get_message_count() == 0
    assert not (tmp_path / "idle.bag.active").exists()
