"""rostopic find TYPE: the topics of a message type."""

from __future__ import annotations

from ._common import option_parser, topic_types


def cmd_find(args: list[str]) -> None:
    parser = option_parser("usage: %prog find msg-type")
    options = parser.parse_args(args)
    rest = options.args
    if not rest:
        parser.error("please specify a message type")
    if len(rest) > 1:
        parser.error("you may only specify one message type")
    print("\n".join(t for t, ty in topic_types() if ty == rest[0]))
