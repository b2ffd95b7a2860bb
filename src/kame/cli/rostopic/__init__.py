"""rostopic: list, info, type, find, echo, hz, bw, delay and pub, as ROS users know them.

One module per verb (list_, info, type_, find, echo, hz, bw, delay, pub; what they share in
_common); command-line parsing, master queries and printing; the pieces with rules live in pure
modules: kame.msg.fill (YAML arguments into messages), kame.msg.fieldpath (`/topic/a/b[1]`),
kame.msg.echo (what echo prints) and kame.cli.topic_stats (hz, bw and delay figures).

Behaviour follows ros_comm 1.15's rostopic: its usage errors (exit 2, optparse's texts where it used optparse), one
`ERROR: ...` line on stderr and exit 1 for bad input and an unreachable master, the same
node start-up (an anonymous `/rostopic_<pid>_<ms>` node), hz and bw subscribing with
`md5sum=*`, and `pub -1` latching for 3 s. Where kame does better on purpose:
- echo, hz --filter and delay work for types kame does not have installed: they subscribe
  as AnyMsg and build the class from the publisher's message_definition;
- pub checks the whole message before publishing and names the field that does not fit,
  also when nobody subscribes yet (rostopic only fails once a subscriber serializes);
- field paths also work through array indices (`rostopic type /js/position[0]`);
- `list -b` and `echo -b` read bags through kame's rosbag (any message type, from the
  definitions stored in the bag).
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable

from kame import names

from ._common import RostopicError, close_master
from .bw import cmd_bw
from .delay import cmd_delay
from .echo import cmd_echo
from .find import cmd_find
from .hz import cmd_hz
from .info import cmd_info
from .list_ import cmd_list
from .pub import cmd_pub
from .type_ import cmd_type

EX_USAGE = 64

USAGE = """rostopic is a command-line tool for printing information about ROS Topics.

Commands:
\trostopic bw\tdisplay bandwidth used by topic
\trostopic delay\tdisplay delay of topic from timestamp in header
\trostopic echo\tprint messages to screen
\trostopic find\tfind topics by type
\trostopic hz\tdisplay publishing rate of topic{TRAILING}
\trostopic info\tprint information about active topic
\trostopic list\tlist active topics
\trostopic pub\tpublish data to topic
\trostopic type\tprint topic or field type

Type rostopic <command> -h for more detailed usage, e.g. 'rostopic echo -h'
""".replace("{TRAILING}", "    ")  # the real usage text has trailing spaces there


COMMANDS: dict[str, Callable[[list[str]], None]] = {
    "bw": cmd_bw, "delay": cmd_delay, "echo": cmd_echo, "find": cmd_find, "hz": cmd_hz, "info": cmd_info,
    "list": cmd_list, "pub": cmd_pub, "type": cmd_type,
}


def _shutdown() -> None:
    from kame.client import core

    if core.get_node() is not None:
        core.signal_shutdown("rostopic done")
    close_master()


def main(argv: list[str] | None = None) -> int:
    args = names.parse_args(sys.argv if argv is None else argv).argv
    if len(args) < 2 or args[1] not in COMMANDS:
        print(USAGE)
        return EX_USAGE
    try:
        COMMANDS[args[1]](args[2:])
    except RostopicError as exc:
        sys.stderr.write(f"ERROR: {exc}\n")
        return 1
    except BrokenPipeError:
        _quiet_stdout()
    except OSError:
        sys.stderr.write("Network communication failed. Most likely failed to communicate with master.\n")
        return 1
    except KeyboardInterrupt:
        pass
    finally:
        try:
            _shutdown()
        except KeyboardInterrupt:
            pass
    try:
        sys.stdout.flush()
    except BrokenPipeError:
        _quiet_stdout()
    return 0


def _quiet_stdout() -> None:
    """After a closed pipe (`rostopic echo /x | head`), let Python exit without complaining."""
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())
