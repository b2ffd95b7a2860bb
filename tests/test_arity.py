"""kame.arity: a callback's shape read from its signature, and rospy's shutdown hooks using it."""

from __future__ import annotations

import functools
import logging
import threading
from typing import Any

import pytest

from kame.arity import accepts


class _Hooks:
    def with_reason(self, reason: str) -> None: ...

    def without(self) -> None: ...


def _two(a: int, b: int) -> None: ...


def _defaulted(a: int, b: int = 0) -> None: ...


def _star(*args: Any) -> None: ...


def _keyword_only(a: int, *, b: int) -> None: ...


@pytest.mark.parametrize(("function", "count", "expected"), [
    (_Hooks().with_reason, 1, True),  # bound: self is not counted
    (_Hooks().with_reason, 0, False),
    (_Hooks().without, 0, True),
    (_Hooks().without, 1, False),
    (functools.partial(_two, 1), 1, True),  # partial: what is left
    (functools.partial(_two, 1), 2, False),
    (_defaulted, 1, True),
    (_defaulted, 2, True),
    (_defaulted, 3, False),
    (_star, 0, True),
    (_star, 5, True),
    (_keyword_only, 1, False),  # b is required and cannot be given positionally
    (lambda: None, 0, True),
    (threading.Event().set, 0, True),
    (threading.Event().set, 1, False),
])
def test_accepts_reads_the_signature(function: Any, count: int, expected: bool) -> None:
    assert accepts(function, count) is expected


def test_a_hook_raising_type_error_inside_is_called_once_and_logged(caplog: pytest.LogCaptureFixture) -> None:
    from kame.client.core import _call_hook

    calls: list[tuple[Any, ...]] = []

    def hook(*args: Any) -> None:  # takes the reason, then fails on its own
        calls.append(args)
        raise TypeError("a bug inside the hook")

    with caplog.at_level(logging.ERROR):
        _call_hook(hook, "bye")
    assert calls == [("bye",)]  # not called again as hook() after its TypeError
    (record,) = [r for r in caplog.records if "shutdown hook" in r.getMessage()]
    assert record.exc_info is not None and str(record.exc_info[1]) == "a bug inside the hook"


def test_a_hook_without_arguments_gets_none() -> None:
    from kame.client.core import _call_hook

    done = threading.Event()
    _call_hook(done.set, "bye")
    assert done.is_set()


def _keyword_defaulted(a: int, *, b: int = 0) -> None: ...


def _positional_only(a: int, /, b: int = 1, *rest: int, c: int = 2, **more: int) -> None: ...


@functools.wraps(_two)
def _wraps_two(*args: Any) -> None: ...


@pytest.mark.parametrize("function", [
    _two, _defaulted, _star, _keyword_only, _keyword_defaulted, _positional_only, _wraps_two, _Hooks().with_reason,
    _Hooks.with_reason, lambda a, b=1, *c: None, lambda *, a: None,
])
def test_plain_functions_are_read_as_inspect_reads_them(function: Any) -> None:
    import inspect  # accepts reads plain functions without it: the answers must be the same

    def by_inspect(count: int) -> bool:
        try:
            inspect.signature(function).bind(*range(count))
        except TypeError:
            return False
        return True

    assert [accepts(function, count) for count in range(5)] == [by_inspect(count) for count in range(5)]
