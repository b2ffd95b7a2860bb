"""Fills messages with genpy.message.fill_message_args from JSON cases and prints the results
(str() of the message, or the error text). Run by kame's and Debian's interpreters."""

from __future__ import annotations

import json
import sys
from typing import Any

import genpy.message
from genpy import Time


def run(cases: list[list[Any]]) -> list[str]:
    answers = []
    for type_name, args in cases:
        msg = genpy.message.get_message_class(type_name)()
        try:
            genpy.message.fill_message_args(msg, args, keys={"now": Time(5, 6)})
        except genpy.MessageException as exc:
            answers.append("error: " + str(exc))
            continue
        answers.append(str(msg) + " | " + genpy.message.get_printable_message_args(msg))
    return answers


if __name__ == "__main__":
    print(json.dumps(run(json.load(sys.stdin))))
