"""xacro: the xacro package's own macro processor, with `$(find pkg)` answered by kame's
package finder (ROS_PACKAGE_PATH and kame's shipped packages), as ROS 1's xacro answers it
with rospack; the PyPI release asks ament's index, which a ROS 1 workspace does not have.

`xacro robot.urdf.xacro name:=value ... [-o out.urdf]` (also `$(find xacro)/xacro` in a launch
file's `<param command=...>`) prints the expanded document."""

from __future__ import annotations

import os
import sys
from collections.abc import Sequence


def find_package(name: str) -> str:
    from kame.catkin import executables

    package = executables.packages(os.environ).get(name)
    if package is None:
        from xacro.substitution_args import SubstitutionException

        raise SubstitutionException(f"[{name}] not found in ROS_PACKAGE_PATH")
    return str(package.path)


def use_kame_packages() -> None:
    """Points xacro's `$(find)` (in attributes and in `${...}` expressions) at kame's finder. Run
    wherever xacro is imported (kame.importhook), so also under the xacro distribution's command."""
    # xacro 2.1's error path names xml.parsers.expat without importing it: a missing input file
    # ended in an AttributeError traceback instead of its "No such file or directory" message
    import xml.parsers.expat  # noqa: F401

    from xacro import substitution_args

    substitution_args._eval_find = find_package
    substitution_args._eval_dict["find"] = find_package


def main(argv: Sequence[str] | None = None) -> int:
    import xacro

    use_kame_packages()
    if argv is not None:
        sys.argv[1:] = list(argv)
    xacro.main()
    return 0


if __name__ == "__main__":
    sys.exit(main())
