"""dynamic_reconfigure as ROS code imports it: the exceptions and helpers of upstream's package
__init__, beside the generated dynamic_reconfigure.msg and .srv and the server, client,
encoding and parameter_generator_catkin modules.

Written by hand, not by kame-genmsg: as catkin leaves a package's own `__init__.py` to the
package, kame-genmsg keeps a top-level `__init__.py` that lacks its GENERATED line.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from kame.reconfigure.errors import (
    DynamicReconfigureCallbackException,
    DynamicReconfigureException,
    DynamicReconfigureParameterException,
)

__all__ = ["DynamicReconfigureCallbackException", "DynamicReconfigureException",
           "DynamicReconfigureParameterException", "find_reconfigure_services", "get_parameter_names"]


def find_reconfigure_services() -> list[str]:
    """The dynamic_reconfigure servers the master knows: each service `<ns>/set_parameters`, as `<ns>`."""
    import rosservice

    suffix = "/set_parameters"
    return sorted(name[:-len(suffix)] for name in rosservice.get_service_list() if name.endswith(suffix))


def get_parameter_names(descr: Any) -> Iterable[str]:
    """The parameter names of a generated `<Name>Config` module (its `defaults`' keys)."""
    return descr.defaults.keys()  # type: ignore[no-any-return]
