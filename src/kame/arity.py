"""Whether a callable takes a given number of positional arguments, read from its signature.

Where a callback may come in more than one shape (rospy's shutdown hooks take the reason or
nothing; an XML-RPC method takes what its signature says), the shape is decided here, before
the call, never by calling and catching TypeError: a TypeError raised inside the callback is
the callback's bug, and must reach the log with its traceback, not pick another way to call it.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any


def accepts(function: Callable[..., Any], count: int) -> bool:
    """True when `function` can be called with `count` positional arguments. Bound methods,
    functools.partial, defaults and *args are read as inspect.signature reads them; a callable
    whose signature Python cannot tell (some builtins) is taken to accept them."""
    import inspect  # here: inspect (with ast, dis, tokenize) is a megabyte a talker never needs

    try:
        signature = inspect.signature(function)
    except (TypeError, ValueError):
        return True
    try:
        signature.bind(*range(count))
    except TypeError:  # raised by bind, not by the callable: nothing has been called
        return False
    return True
