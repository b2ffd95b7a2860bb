"""Field paths into messages: `/pose/position/x`, `/position[1]`, `/poses[1:3]/position`.

What `rostopic echo /topic/field...`, `rostopic type /topic/field` and plotting tools use.
A path is split at `/` into steps, each a field name with an optional index or slice; a
slice in the middle of a path maps the rest of the path over the selected elements.
Error texts are rostopic's (`no field named q in /x/q`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from kame.msg.errors import MessageError
from kame.msg.message import Message
from kame.msg.spec import split_array

__all__ = ["FieldPath", "FieldPathError", "field_type", "has_field", "parse_field_path"]


class FieldPathError(MessageError):
    """A malformed field path, or one the message does not have."""


@dataclass(frozen=True)
class Step:
    name: str
    index: int | slice | None


@dataclass(frozen=True)
class FieldPath:
    """A parsed path; `evaluate(msg)` picks the field's value out of a message."""

    pattern: str
    steps: tuple[Step, ...]

    def evaluate(self, msg: Any) -> Any:
        return self._evaluate(msg, self.steps)

    def _evaluate(self, value: Any, steps: tuple[Step, ...]) -> Any:
        for position, step in enumerate(steps):
            try:
                value = getattr(value, step.name)
            except AttributeError:
                raise FieldPathError(f"no field named {step.name} in {self.pattern}") from None
            if step.index is None:
                continue
            try:
                value = value[step.index]
            except IndexError as exc:
                raise FieldPathError(f"{exc}: {self.pattern}") from None
            except TypeError:
                raise FieldPathError(f"field {step.name} is not an array: {self.pattern}") from None
            if isinstance(value, list):  # a slice: the rest of the path applies to each element
                rest = steps[position + 1:]
                return [self._evaluate(item, rest) for item in value]
        return value


def parse_field_path(pattern: str) -> FieldPath | None:
    """The steps of `pattern` (`/a/b[2]/c`), or None when it names no field at all."""
    steps: list[Step] = []
    for part in (p for p in pattern.split("/") if p):
        if "[" not in part:
            steps.append(Step(part, None))
            continue
        name, rest = part.split("[", 1)
        if not rest.endswith("]"):
            raise FieldPathError(f"missing closing ']' in slice spec '{part}'")
        inside = rest[:-1]
        try:
            index = _index_or_slice(inside)
        except ValueError as exc:
            raise FieldPathError(f"field '{name}' has invalid slice argument '{inside}': {exc}") from None
        steps.append(Step(name, index))
    return FieldPath(pattern, tuple(steps)) if steps else None


def _index_or_slice(text: str) -> int | slice:
    if text == "":
        raise ValueError("empty array index")
    parts = text.split(":")
    if len(parts) == 1:
        try:
            return int(parts[0])
        except ValueError:
            raise ValueError(f"non-integer array index step '{parts[0]}'") from None
    if len(parts) > 3:
        raise ValueError("too many slice arguments")
    bounds: list[int | None] = [None, None, None]
    for position, (part, what) in enumerate(zip(parts, ("start", "stop", "step"), strict=False)):
        if part:
            try:
                bounds[position] = int(part)
            except ValueError:
                raise ValueError(f"non-integer slice {what} '{part}'") from None
    return slice(*bounds)


def field_type(cls: type[Message], path: str) -> str:
    """The declared type of the field at `path` (`header/stamp` -> `time`, `position[1]` -> `float64`)."""
    parsed = parse_field_path(path)
    if parsed is None:
        return cls._type
    current: type[Message] | None = cls
    slot_type = cls._type
    for position, step in enumerate(parsed.steps):
        if current is None or step.name not in current.__slots__:
            owner = current._type if current is not None else slot_type
            raise FieldPathError(f"{owner} has no field named [{step.name}] (in {path})")
        slot_type = current._slot_types[current.__slots__.index(step.name)]
        base, is_array, _length = split_array(slot_type)
        if step.index is not None:
            if not is_array:
                raise FieldPathError(f"field {step.name} of type {slot_type} is not an array (in {path})")
            if isinstance(step.index, int):
                slot_type = base
        elif is_array and position + 1 < len(parsed.steps):
            raise FieldPathError(f"field {step.name} is an array: index it to reach its fields (in {path})")
        current = current._slot_classes.get(step.name)
    return slot_type


def has_field(cls: type[Message], path: str) -> bool:
    try:
        field_type(cls, path)
    except FieldPathError:
        return False
    return True
