# ruff: noqa: E501  (option help texts are rosbag's, one option per line)
"""rosbag: info, record, play, filter, compress, decompress, reindex, check, fix, and convert.

Behaviour and texts follow rosbag 1.15 (ros1-user-behaviour spec §9): its optparse usage errors
(exit 2), `ERROR reading X: ...` for bad bags, `info` in rosbag's layout or YAML, compress/
decompress/reindex rewriting in place and keeping `name.orig.bag`. record and play live in
kame.cli.bag_record and kame.cli.bag_play. `info` imports no message code: it reads the index
and prints, so it answers at once even for very large bags. info, play and the Bag API also read
MCAP files (kame.bag.mcap_file); `convert` (beyond rosbag 1.15) writes a bag as MCAP or back.
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable, Sequence

from kame.bag.errors import BagError, BagUnindexedError

TYPE_CHECKING = False  # typing.TYPE_CHECKING without importing typing (`rosbag info` starts in ms)
if TYPE_CHECKING:
    from kame.bag.info import BagSummary
    from kame.cli._options import OptionParser

NAME = "rosbag"
COMMANDS = ("check", "compress", "convert", "decompress", "filter", "fix", "help", "info", "play", "record", "reindex")


def _parser(usage: str, description: str = "") -> OptionParser:
    from kame.cli._options import OptionParser

    return OptionParser(usage=usage, description=description or None)


# ------------------------------------------------------------------------------ info


class _InfoOptions:
    __slots__ = ("freq", "key", "yaml")

    def __init__(self) -> None:
        self.yaml = False
        self.key: str | None = None
        self.freq = False


def _quick_info_args(argv: list[str]) -> tuple[_InfoOptions, list[str]] | None:
    """`rosbag info`'s options parsed without argparse, whose import costs more than reading a
    big bag's index; None for anything unusual (help, errors, `--`), which the parser then handles
    with its own messages."""
    options = _InfoOptions()
    args: list[str] = []
    it = iter(argv)
    for arg in it:
        if arg in ("-y", "--yaml"):
            options.yaml = True
        elif arg == "--freq":
            options.freq = True
        elif arg in ("-k", "--key"):
            value = next(it, None)
            if value is None:
                return None
            options.key = value
        elif arg.startswith("--key="):
            options.key = arg[len("--key="):]
        elif arg.startswith("-") and arg != "-":
            return None
        else:
            args.append(arg)
    if not args or (options.key and not options.yaml):
        return None
    return options, args


def _info_summary(path: str, frequencies: bool) -> BagSummary:
    if frequencies:
        from kame.client.bag import Bag

        with Bag(path, "r") as bag:
            return bag.summary(frequencies=True)
    from kame.bag.info import BagSummary
    from kame.bag.reader import BagReader, open_reader

    with open_reader(path) as reader:
        return BagSummary(path, reader.size, reader.connections, reader.chunk_infos, reader.chunk_headers(),
                          version="2.0" if isinstance(reader, BagReader) else "mcap")


def cmd_info(argv: list[str]) -> int:
    quick = _quick_info_args(argv)
    if quick is not None:
        options, args = quick
    else:
        parser = _parser("rosbag info [options] BAGFILE1 [BAGFILE2 BAGFILE3 ...]",
                         "Summarize the contents of one or more bag files.")
        parser.add_argument("-y", "--yaml", dest="yaml", default=False, action="store_true",
                          help="print information in YAML format")
        parser.add_argument("-k", "--key", dest="key", default=None, action="store", help="print information on the given key")
        parser.add_argument("--freq", dest="freq", default=False, action="store_true",
                          help="display topic message frequency statistics")
        values = parser.parse_args(argv)
        args = values.args
        if not args:
            parser.error("You must specify at least 1 bag file.")
        if values.key and not values.yaml:
            parser.error("You can only specify key when printing in YAML format.")
        options = _InfoOptions()
        options.yaml, options.key, options.freq = values.yaml, values.key, values.freq
    from kame.bag.info import info_text, info_yaml, yaml_key

    for i, arg in enumerate(args):
        try:
            summary = _info_summary(arg, options.freq)
            if options.yaml:
                text: str | None = info_yaml(summary)
                if options.key:
                    text = yaml_key(text or "", options.key)
                    if text is None:
                        print(f'Error getting key "{options.key}"', file=sys.stderr)
                if text is not None:
                    print(text)
            else:
                print(info_text(summary))
            if i < len(args) - 1:
                print("---")
        except BagUnindexedError:
            print(f"ERROR bag unindexed: {arg}.  Run rosbag reindex.", file=sys.stderr)
            return 1
        except (BagError, OSError) as exc:
            print(f"ERROR reading {arg}: {exc}", file=sys.stderr)
            return 1
    return 0


# ------------------------------------------------------------------------------ rewriting


def _progress(out_path: str, quiet: bool) -> Callable[[int, int], None]:
    start = time.monotonic()
    last = [0.0]

    def update(done: int, total: int) -> None:
        if quiet:
            return
        now = time.monotonic()
        if now - last[0] < 0.2 and done < total:
            return
        last[0] = now
        from kame.bag.info import human_readable_size

        pct = 100 * done // max(total, 1)
        el = int(now - start)
        sys.stdout.write(f"\r {os.path.basename(out_path)}   {pct:3d}%  {human_readable_size(done):>9} "
                         f"{el // 60:02d}:{el % 60:02d}    ")
        if done >= total:
            sys.stdout.write("\n")
        sys.stdout.flush()

    return update


def rewrite(in_path: str, out_path: str, compression: str | None,
            keep: Callable[[str, object, tuple[int, int]], bool] | None = None,
            progress: Callable[[int, int], None] | None = None, decode: bool = False) -> int:
    """Copy the messages of one bag into a new one (same connections), optionally filtered;
    messages are copied as bytes unless `keep` needs them decoded. Returns messages written."""
    from kame.bag.reader import BagReader
    from kame.bag.writer import BagWriter
    from kame.client.bag import message_class

    with BagReader(in_path) as reader:
        if compression is None:
            headers = reader.chunk_headers()
            compression = headers[0].compression if headers else "none"
        total = sum(h.uncompressed_size for h in reader.chunk_headers()) or 1
        done = 0
        written = 0
        ids: dict[int, int] = {}
        last_chunk = -1
        with BagWriter(out_path, "w", compression) as writer:
            for m in reader.messages():
                if keep is not None:
                    value: object = m
                    if decode:
                        value = message_class(m.conn)().deserialize(m.data)
                    if not keep(m.conn.topic, value, m.time):
                        continue
                conn_id = ids.get(m.conn.id)
                if conn_id is None:
                    conn_id = ids[m.conn.id] = writer.add_connection(m.conn.topic, m.conn.header)
                writer.write(conn_id, m.time[0], m.time[1], m.data)
                written += 1
                if progress is not None and m.position[0] != last_chunk:
                    last_chunk = m.position[0]
                    done = min(done + reader.chunk_header(
                        next(i for i in reader.chunk_infos if i.pos == last_chunk)).uncompressed_size, total)
                    progress(done, total)
        if progress is not None:
            progress(total, total)
    return written


def _in_place(argv: list[str], name: str, default_compression: str | None, allow_choice: bool) -> int:
    import shutil

    parser = _parser(f"rosbag {name} [options] BAGFILE1 [BAGFILE2 ...]",
                     {"compress": "Compress one or more bag files.",
                      "decompress": "Decompress one or more bag files.",
                      "reindex": "Reindexes one or more bag files."}[name])
    parser.add_argument("--output-dir", action="store", dest="output_dir", help="write to directory DIR", metavar="DIR")
    parser.add_argument("-f", "--force", action="store_true", dest="force", help="force overwriting of backup file if it exists")
    parser.add_argument("-q", "--quiet", action="store_true", dest="quiet", help="suppress noncritical messages")
    if allow_choice:
        parser.add_argument("-j", "--bz2", action="store_const", dest="compression", help="use BZ2 compression",
                          const="bz2", default="bz2")
        parser.add_argument("--lz4", action="store_const", dest="compression", help="use lz4 compression", const="lz4")
    options = parser.parse_args(argv)
    args = options.args
    if not args:
        parser.error("You must specify at least one bag file.")
    compression = getattr(options, "compression", default_compression)
    status = 0
    for inbag in args:
        if not os.path.exists(inbag):
            print(f"ERROR reading {inbag}: [Errno 2] No such file or directory: '{inbag}'", file=sys.stderr)
            status = 1
            continue
        root, ext = os.path.splitext(inbag)
        backup = root + ".orig" + ext
        outbag = inbag
        if options.output_dir:
            os.makedirs(options.output_dir, exist_ok=True)
            outbag = os.path.join(options.output_dir, os.path.basename(inbag))
        elif os.path.exists(backup) and not options.force:
            print(f"Skipping {inbag}. Backup path {backup} already exists.", file=sys.stderr)
            continue
        source = inbag
        if not options.output_dir:
            shutil.move(inbag, backup)
            source = backup
        try:
            if name == "reindex":
                reindex_file(source, outbag, _progress(outbag, bool(options.quiet)))
            else:
                rewrite(source, outbag, compression, progress=_progress(outbag, bool(options.quiet)))
        except (BagError, OSError) as exc:
            print(f"ERROR {name}ing {inbag}: {exc}", file=sys.stderr)
            if not options.output_dir:
                if os.path.exists(outbag):
                    os.remove(outbag)
                shutil.move(backup, inbag)
            status = 1
    return status


def reindex_file(source: str, outbag: str, progress: Callable[[int, int], None] | None = None) -> None:
    """Write `outbag` as `source` with its index rebuilt from its chunks (a copy of the good
    part, then the index written after the last intact chunk)."""
    from kame.bag.writer import BagWriter

    if os.path.abspath(source) != os.path.abspath(outbag):
        import shutil

        shutil.copyfile(source, outbag)
    total = os.path.getsize(outbag)
    writer = BagWriter(outbag, "a", allow_unindexed=True)
    writer.close()
    if progress is not None:
        progress(total, total)


def cmd_compress(argv: list[str]) -> int:
    return _in_place(argv, "compress", "bz2", True)


def cmd_decompress(argv: list[str]) -> int:
    return _in_place(argv, "decompress", "none", False)


def cmd_reindex(argv: list[str]) -> int:
    return _in_place(argv, "reindex", None, False)


def cmd_filter(argv: list[str]) -> int:
    parser = _parser("rosbag filter [options] INBAG OUTBAG EXPRESSION",
                     'Filter the contents of the bag. EXPRESSION can be any Python-evaluable expression using '
                     'the variables: topic, m (message) and t (time of message, a genpy.Time).')
    parser.add_argument("-p", "--print", action="store", dest="verbose_pattern", default=None, metavar="PRINT-EXPRESSION",
                      help="Python expression to print for verbose debugging. Uses same variables as filter-expression")
    options = parser.parse_args(argv)
    args = options.args
    if len(args) == 0:
        parser.error("You must specify an in bag, an out bag, and an expression.")
    if len(args) == 1:
        parser.error("You must specify an out bag and an expression.")
    if len(args) == 2:
        parser.error("You must specify an expression.")
    if len(args) > 3:
        parser.error("Too many arguments.")
    inbag, outbag, expr = args
    if not os.path.isfile(inbag):
        print(f"Cannot locate input bag file [{inbag}]", file=sys.stderr)
        return 2
    if os.path.realpath(inbag) == os.path.realpath(outbag):
        print(f"Cannot use same file as input and output [{inbag}]", file=sys.stderr)
        return 3
    try:
        code = compile(expr, "<filter>", "eval")
        pcode = compile(options.verbose_pattern, "<print>", "eval") if options.verbose_pattern else None
    except SyntaxError as exc:
        print(f"ERROR: invalid expression: {exc}", file=sys.stderr)
        return 1
    from kame.client.clock import Time

    def keep(topic: str, m: object, t: tuple[int, int]) -> bool:
        env = {"topic": topic, "m": m, "t": Time(t[0], t[1])}
        if pcode is not None:
            print(eval(pcode, {}, env))
        return bool(eval(code, {}, env))

    try:
        rewrite(inbag, outbag, None, keep, _progress(outbag, False), decode=True)
    except BagUnindexedError:
        print(f"ERROR bag unindexed: {inbag}.  Run rosbag reindex.", file=sys.stderr)
        return 1
    except BagError as exc:
        print(f"ERROR reading {inbag}: {exc}", file=sys.stderr)
        return 1
    return 0


def cmd_check(argv: list[str]) -> int:
    parser = _parser("rosbag check BAG [-g RULEFILE] [EXTRARULES1 EXTRARULES2 ...]",
                     "Determine whether a bag is playable in the current system, or if it can be migrated.")
    parser.add_argument("-g", "--genrules", action="store", dest="rulefile", default=None,
                      help="generate a rulefile named RULEFILE")
    parser.add_argument("-a", "--append", action="store_true", dest="append", help="append to the end of an existing rulefile")
    parser.add_argument("-n", "--noplugins", action="store_true", dest="noplugins", help="do not load rulefiles via plugins")
    parsed = parser.parse_args(argv)
    args = parsed.args
    if not args:
        parser.error("You must specify a bag file to check.")
    from kame.client.bag import Bag

    try:  # kame reads every message with the definition stored in the bag: nothing to migrate
        with Bag(args[0]):
            pass
    except (BagError, OSError) as exc:
        print(f"ERROR reading {args[0]}: {exc}", file=sys.stderr)
        return 1
    print("Bag file does not need any migrations.")
    return 0


def cmd_fix(argv: list[str]) -> int:
    parser = _parser("rosbag fix INBAG OUTBAG [EXTRARULES1 EXTRARULES2 ...]",
                     "Repair the messages in a bag file so that it can be played in the current system.")
    parser.add_argument("-n", "--noplugins", action="store_true", dest="noplugins", help="do not load rulefiles via plugins")
    parser.add_argument("--force", action="store_true", dest="force", help="proceed with migrations, even if not all rules defined")
    parsed = parser.parse_args(argv)
    args = parsed.args
    if len(args) < 2:
        parser.error("You must pass input and output bag files.")
    inbag, outbag = args[0], args[1]
    try:
        rewrite(inbag, outbag, None)
    except BagUnindexedError:
        print(f"ERROR bag unindexed: {inbag}.  Run rosbag reindex.", file=sys.stderr)
        return 1
    except (BagError, OSError) as exc:
        print(f"ERROR reading {inbag}: {exc}", file=sys.stderr)
        return 1
    print(f"{outbag} needed no migration: kame reads each message with the definition stored in the bag.")
    return 0


# ------------------------------------------------------------------------------ main


def cmd_record(argv: list[str]) -> int:
    from kame.cli.bag_record import main as record_main

    return record_main(argv)


def cmd_convert(argv: list[str]) -> int:
    parser = _parser("rosbag convert [options] INFILE OUTFILE",
                     "Convert a bag to MCAP (OUTFILE ending in .mcap) or an MCAP file to a bag; message bytes, "
                     "receive times and connection headers are kept.")
    parser.add_argument("--compression", dest="compression", default=None, choices=["none", "lz4", "zstd", "bz2"],
                        help="compression of the output (MCAP: zstd, lz4 or none; default zstd; bag: none, bz2 or lz4; default none)")
    parser.add_argument("-q", "--quiet", dest="quiet", default=False, action="store_true", help="suppress noncritical messages")
    options = parser.parse_args(argv)
    if len(options.args) != 2:
        parser.error("You must specify an input file and an output file.")
    in_path, out_path = options.args
    if os.path.abspath(in_path) == os.path.abspath(out_path):
        parser.error("The output file must differ from the input file.")
    try:
        from kame.bag.mcap_file import bag_to_mcap, is_mcap, mcap_to_bag
    except ModuleNotFoundError as exc:
        print(f"rosbag convert needs the mcap library, kame's 'web' extra (pip install 'kame[web]'): {exc}",
              file=sys.stderr)
        return 1
    progress = _progress(out_path, options.quiet)
    try:
        if is_mcap(in_path):
            if options.compression in ("zstd",):
                parser.error("A bag's compression is none, bz2 or lz4.")
            mcap_to_bag(in_path, out_path, options.compression or "none", progress)
        else:
            if options.compression == "bz2":
                parser.error("MCAP's compression is zstd, lz4 or none.")
            bag_to_mcap(in_path, out_path, options.compression or "zstd", progress)
    except (BagError, OSError) as exc:
        print(f"ERROR converting {in_path}: {exc}", file=sys.stderr)
        return 1
    return 0


def cmd_play(argv: list[str]) -> int:
    from kame.cli.bag_play import main as play_main

    return play_main(argv)


_USAGE = """Usage: rosbag <subcommand> [options] [args]

A bag is a file format in ROS for storing ROS message data. The rosbag command can record, replay and manipulate bags.

Available subcommands:
   check  \tDetermine whether a bag is playable in the current system, or if it can be migrated.
   compress  \tCompress one or more bag files.
   convert  \tConvert a bag to MCAP, or an MCAP file to a bag.
   decompress  \tDecompress one or more bag files.
   filter  \tFilter the contents of the bag.
   fix  \tRepair the messages in a bag file so that it can be played in the current system.
   help
   info  \tSummarize the contents of one or more bag files.
   play  \tPlay back the contents of one or more bag files in a time-synchronized fashion.
   record  \tRecord a bag file with the contents of specified topics.
   reindex  \tReindexes one or more bag files.

For additional information, see http://wiki.ros.org/rosbag
"""

_COMMANDS: dict[str, Callable[[list[str]], int]] = {
    "check": cmd_check, "compress": cmd_compress, "convert": cmd_convert, "decompress": cmd_decompress,
    "filter": cmd_filter,
    "fix": cmd_fix, "info": cmd_info, "play": cmd_play, "record": cmd_record, "reindex": cmd_reindex,
}


def main(argv: Sequence[str] | None = None) -> int:
    args = list(sys.argv[1:] if argv is None else argv)
    if not args or args[0] in ("-h", "--help"):
        print(_USAGE)
        return 0
    cmd = args[0]
    if cmd == "help":
        if len(args) > 1 and args[1] in _COMMANDS:
            return _COMMANDS[args[1]]([*args[2:], "-h"])
        print(_USAGE)
        return 0
    func = _COMMANDS.get(cmd)
    if func is None:
        print(f"Unknown command: '{cmd}'", file=sys.stderr)
        print(_USAGE)
        return 0
    try:
        return func(args[1:])
    except KeyboardInterrupt:
        return 0
    except BrokenPipeError:
        return 0


if __name__ == "__main__":
    sys.exit(main())
