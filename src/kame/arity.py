"""Whether a callable takes a given number of positional arguments, read from its signature.

Where a callback may come in more than one shape (rospy's shutdown hooks take the reason or
nothing; an XML-RPC method takes what its signature says), the shape is decided here, before
the call, never by calling and catching TypeError: a TypeError raised inside the callback is
the callback's bug, and must reach the log with its traceback, not pick another way to call it.
"""

from __future__ import annotations

from collections.abc import Callable
from types import FunctionType, MethodType
from typing import Any

_CO_VARARGS = 0x04


def accepts(function: Callable[..., Any], count: int) -> bool:
    """True when `function` can be called with `count` positional arguments. Bound methods,
    functools.partial, defaults and *args are read as inspect.signature reads them; a callable
    whose signature Python cannot tell (some builtins) is taken to accept them."""
    if type(function) is MethodType:
        function, count = function.__func__, count + 1
    if type(function) is FunctionType and not hasattr(function, "__wrapped__") \
            and not hasattr(function, "__signature__"):
        return _function_accepts(function, count)
    import inspect  # here: inspect (with ast, dis, tokenize) is 1.6 MB a node never needs otherwise

    try:
        signature = inspect.signature(function)
    except (TypeError, ValueError):
        return True
    try:
        signature.bind(*range(count))
    except TypeError:  # raised by bind, not by the callable: nothing has been called
        return False
    return True


def _function_accepts(function: FunctionType, count: int) -> bool:
    """`accepts` for a plain function, read from its code object as inspect would read it
    (the XML-RPC servers ask this of their handlers on every call)."""
    code = function.__code__
    positional = code.co_argcount
    if count < positional - len(function.__defaults__ or ()):
        return False
    if count > positional and not code.co_flags & _CO_VARARGS:
        return False
    keyword_only = code.co_varnames[positional:positional + code.co_kwonlyargcount]
    defaults = function.__kwdefaults__ or {}
    return all(name in defaults for name in keyword_only)  # one without a default cannot be left out
