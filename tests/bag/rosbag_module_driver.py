"""rosbag.Bag and rosbag.bag's record helpers on the cases of test_rosbag_module.py; prints JSON.
Run by kame's interpreter and Debian's /usr/bin/python3 (its real rosbag) in a folder given on stdin."""

from __future__ import annotations

import io
import json
import os
import sys
from collections.abc import Callable
from typing import Any

import genpy
import rosbag
import rosbag.bag as bag_module
import rospy
from rospy.msg import AnyMsg
from std_msgs.msg import String

ERRORS = [("ROSBagFormatException", rosbag.ROSBagFormatException), ("ROSBagException", rosbag.ROSBagException),
          ("ROSException", rospy.ROSException), ("ValueError", ValueError)]


def outcome(call: Callable[[], Any]) -> Any:
    """What `call` returned, or the rosbag name of what it raised, with its message."""
    try:
        return call()
    except Exception as exc:
        name = next((n for n, cls in ERRORS if isinstance(exc, cls)), type(exc).__name__)
        return ["raised", name, str(exc)]


def messages(bag: rosbag.Bag) -> list[Any]:
    return [[m.topic, m.message.data, m.timestamp.to_nsec()] for m in bag.read_messages()]


def file_objects(folder: str) -> dict[str, Any]:
    path = os.path.join(folder, "stream.bag")
    with open(path, "w+b") as f:
        bag = rosbag.Bag(f, "w")
        bag.write("/a", String("one"), genpy.Time(1, 2))
        bag.close()
        closed_by_bag = f.closed
    with open(path, "r+b") as f:
        bag = rosbag.Bag(f, "a")
        bag.write("/b", String("two"), genpy.Time(3, 0))
        bag.close()
    with open(path, "rb") as f:
        bag = rosbag.Bag(f)
        read = {"filename": bag.filename, "mode": bag.mode, "messages": messages(bag),
                "start": bag.get_start_time(), "end": bag.get_end_time(), "count": bag.get_message_count()}
        bag.close()
    return {"closed_by_bag": closed_by_bag, "read": read}


def argument_checks(folder: str) -> dict[str, Any]:
    missing = os.path.join(folder, "no", "such", "folder.bag")
    return {
        "chunk_threshold": outcome(lambda: rosbag.Bag(missing, "w", chunk_threshold=-1000)),
        "compression": outcome(lambda: rosbag.Bag(missing, "w", compression="zip")),
        "options": outcome(lambda: rosbag.Bag(missing, "w", options="x")),  # type: ignore[arg-type]
        "options_threshold": outcome(lambda: rosbag.Bag(missing, "w", options={"chunk_threshold": -1})),
        "mode": outcome(lambda: rosbag.Bag(missing, "x")),
        "no_file": outcome(lambda: rosbag.Bag("", "w")),
    }


def times(folder: str) -> dict[str, Any]:
    path = os.path.join(folder, "times.bag")
    out: dict[str, Any] = {}
    bag = rosbag.Bag(path, "w")
    out["writing_empty"] = [outcome(bag.get_start_time), outcome(bag.get_end_time), bag.get_message_count()]
    bag.close()
    bag = rosbag.Bag(path)
    out["read_empty"] = [outcome(bag.get_start_time), outcome(bag.get_end_time), bag.get_message_count()]
    bag.close()
    bag = rosbag.Bag(path, "w", chunk_threshold=100)
    for secs in (5, 3, 9):
        bag.write("/t", String("x" * 80), genpy.Time(secs, 500))
    out["writing"] = [bag.get_start_time(), bag.get_end_time(), bag.get_message_count(), bag.get_message_count("/t"),
                      bag.get_message_count("/other")]
    bag.close()
    out["closed"] = [bag.get_start_time(), bag.get_end_time(), bag.get_message_count()]
    with rosbag.Bag(path) as bag:
        out["read"] = [bag.get_start_time(), bag.get_end_time(), bag.get_message_count()]
    return out


def record_helpers(folder: str) -> dict[str, Any]:
    path = os.path.join(folder, "records.bag")
    with rosbag.Bag(path, "w") as bag:
        bag.write("/r", String("rec"), genpy.Time(7, 8))
    bag = rosbag.Bag(path)
    out: dict[str, Any] = {"version": bag._version, "header_pos": bag._file_header_pos}
    f = bag._file
    f.seek(bag._file_header_pos)
    header = bag_module._read_header(f, bag_module._OP_FILE_HEADER)
    out["file_header"] = {k: bag_module._read_uint32_field(header, k) if k != "index_pos"
                          else bag_module._read_uint64_field(header, k) for k in sorted(header) if k != "op"}
    out["padding"] = len(bag_module._read_record_data(f))
    out["next_op"] = bag_module._peek_next_header_op(f)
    chunk = bag_module._read_header(f, bag_module._OP_CHUNK)
    out["chunk"] = [bag_module._read_str_field(chunk, "compression"), bag_module._read_uint32_field(chunk, "size")]
    bag_module._skip_sized(f)
    out["after_chunk_op"] = bag_module._peek_next_header_op(f)
    out["wrong_op"] = outcome(lambda: bag_module._read_header(f, bag_module._OP_CHUNK))
    bag.close()
    buff = io.BytesIO()
    bag_module._write_record(buff, {"op": bag_module._pack_uint8(bag_module._OP_FILE_HEADER),
                                    "index_pos": bag_module._pack_uint64(0)}, padded_size=64)
    bag_module._write_record(buff, {"op": bag_module._pack_uint8(bag_module._OP_MSG_DATA), "k": "v"}, "data")
    out["written"] = buff.getvalue().hex()
    buff.seek(0)
    out["read_back"] = [sorted(bag_module._read_header(buff)), len(bag_module._read_sized(buff))]
    out["short"] = outcome(lambda: bag_module._read_sized(io.BytesIO(b"\x09\x00\x00\x00abc")))
    out["truncated_size"] = outcome(lambda: bag_module._read_sized(io.BytesIO(b"\x09")))
    out["missing_field"] = outcome(lambda: bag_module._read_uint32_field({}, "conn"))
    out["constants"] = [bag_module._FILE_HEADER_LENGTH, bag_module._VERSION, bag_module._OP_MSG_DEF,
                        bag_module._OP_MSG_DATA, bag_module._OP_FILE_HEADER, bag_module._OP_INDEX_DATA,
                        bag_module._OP_CHUNK, bag_module._OP_CHUNK_INFO, bag_module._OP_CONNECTION,
                        sorted(bag_module._OP_CODES.values())]
    out["packed"] = [bag_module._pack_uint8(200).hex(), bag_module._pack_uint32(70000).hex(),
                     bag_module._pack_uint64(2**40 + 3).hex(), bag_module._pack_time(genpy.Time(1, 2)).hex(),
                     bag_module._unpack_time(bytes.fromhex("0100000002000000")).to_nsec()]
    return out


def captured(call: Callable[[], Any]) -> list[Any]:
    """[what `call` returned or raised, its stdout, its stderr]."""
    import contextlib

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        result = outcome(call)
    return [result, out.getvalue(), err.getvalue()]


def main_parts(folder: str) -> dict[str, Any]:
    """rosbag.rosbag_main's reusable parts: bag_op with its ops, ProgressMeter, RosbagCmds, callbacks."""
    import contextlib
    import optparse

    import rosbag.rosbag_main as main_module

    path = os.path.join(folder, "op.bag")
    with rosbag.Bag(path, "w") as bag:
        for i in range(3):
            bag.write("/op", String(f"m{i}"), genpy.Time(i + 1))

    def compress(inbag: Any, outbag: Any, quiet: bool) -> None:
        main_module.change_compression_op(inbag, outbag, "bz2", quiet)

    compressed = captured(lambda: main_module.bag_op([path], False, True, lambda b: False, compress, quiet=True))
    with rosbag.Bag(path) as bag:
        after = [bag.get_compression_info().compression, messages(bag)]
    again = captured(lambda: main_module.bag_op([path], False, True, lambda b: False, compress, quiet=True))
    out_dir = os.path.join(folder, "out")
    os.mkdir(out_dir)
    reindexed = captured(lambda: main_module.bag_op([path], True, True, lambda b: True, main_module.reindex_op,
                                                    output_dir=out_dir, quiet=True))
    with rosbag.Bag(os.path.join(out_dir, "op.bag")) as bag:
        reindexed_messages = messages(bag)
    missing = captured(lambda: main_module.bag_op([os.path.join(folder, "none.bag")], False, True, lambda b: False,
                                                  compress, quiet=True))
    os.environ["COLUMNS"] = "60"
    meter = captured(lambda: main_module.ProgressMeter("/some/where/long/enough/x.bag", 4096).finish())
    cmds = main_module.RosbagCmds()
    cmds.add_cmd("info", lambda argv: print("info", argv), "Summarize bags.")
    parser = optparse.OptionParser()
    parser.add_option("--topics", dest="topics", default=[], callback=main_module.handle_topics, action="callback")
    parser.add_option("--pause-topics", dest="pause_topics", default=[], callback=main_module.handle_pause_topics,
                      action="callback")
    parser.add_option("--split", dest="split", default=False, callback=main_module.handle_split, action="callback")
    parser.add_option("--size", dest="size", type="int", default=0)
    parser.add_option("-x", dest="x", default=False, action="store_true")
    warned = io.StringIO()
    with contextlib.redirect_stderr(warned):
        options, args = parser.parse_args(["--topics", "/a", "/b", "--pause-topics", "/c", "-x", "--split", "12", "f"])
    answer = {"compressed": [compressed, after, os.path.exists(path.replace(".bag", ".orig.bag"))], "again": again,
            "reindexed": [reindexed, reindexed_messages], "missing": missing, "meter": meter,
            "cmds": [cmds.get_valid_cmds(), captured(lambda: cmds.help_cmd([])), captured(lambda: cmds.help_cmd(["x"])),
                     captured(lambda: cmds.help_cmd(["info"])), sorted(cmds)],
            "options": [options.topics, options.pause_topics, options.split, options.size, args, warned.getvalue()],
            "trans": captured(lambda: main_module.print_trans(String, None, 1))}
    return json.loads(json.dumps(answer).replace(folder, "FOLDER"))


def any_msg() -> Any:
    return outcome(lambda: AnyMsg().serialize(io.BytesIO()))


def main() -> None:
    folder = json.load(sys.stdin)["folder"]
    json.dump({"file_objects": file_objects(folder), "argument_checks": argument_checks(folder),
               "times": times(folder), "record_helpers": record_helpers(folder), "any_msg": any_msg(),
               "main_parts": main_parts(folder)}, sys.stdout)


if __name__ == "__main__":
    main()
