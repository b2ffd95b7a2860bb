"""rospy.impl.validators: the parameter validators of rospy's APIs and their exception."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

__all__ = ["ParameterInvalid", "non_empty"]


class ParameterInvalid(Exception):
    """A parameter of an API call that fails its validation."""

    def __init__(self, message: str) -> None:
        super().__init__(message)
        self._message = message

    def __str__(self) -> str:
        return str(self._message)


def non_empty(param_name: str) -> Callable[[Any, Any], Any]:
    """A validator of a parameter that must be given and not empty."""
    def validator(param: Any, context: Any) -> Any:
        if not param:
            raise ParameterInvalid(f"ERROR: parameter [{param_name}] must be specified and non-empty")
        return param

    return validator
