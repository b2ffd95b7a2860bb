"""rostopic type /topic[/field]: the type of a topic, or of a field in it."""

from __future__ import annotations

import argparse
import sys

from kame.msg.fieldpath import FieldPathError, field_type

from ._common import NAME, RostopicError, find_topic, load_message_class, script_resolve_name


def cmd_type(args: list[str]) -> None:
    parser = argparse.ArgumentParser(prog=f"{NAME} type")
    parser.add_argument("topic_or_field", help="Topic or field name")
    topic = script_resolve_name(parser.parse_args(args).topic_or_field)
    found = find_topic(topic)
    if found is None:
        sys.stderr.write(f"unknown topic type [{topic}]\n")
        raise SystemExit(1)
    topic_type, real_topic, _ = found
    if topic == real_topic:
        print(topic_type)
        return
    field = topic[len(real_topic) + 1:]
    cls = load_message_class(topic_type)
    if cls is None:
        raise RostopicError(f"Cannot load message class for [{topic_type}]. Are your messages built?")
    try:
        print(f"{topic_type} {field} {field_type(cls, field)}")
    except FieldPathError as exc:
        raise RostopicError(str(exc)) from None
