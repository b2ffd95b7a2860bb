"""roslib.resources: the files in a package's folder (msg, srv, ...) as resource names."""

from __future__ import annotations

import os
from collections.abc import Callable

import rospkg
from roslib import names as _names
from roslib import packages as _packages

__all__ = ["list_package_resources", "list_package_resources_by_dir"]


def list_package_resources_by_dir(package_dir: str, include_depends: bool, subdir: str,
                                  rfilter: Callable[[str], bool] = os.path.isfile) -> list[str]:
    """The names of the files in `package_dir`/`subdir` that `rfilter` accepts (with
    `include_depends`, also those of the packages it depends on, as `dep/file`)."""
    package = os.path.basename(package_dir)
    folder = os.path.join(package_dir, subdir)
    found = [_names.resource_name(package, f, my_pkg=package) for f in os.listdir(folder)
             if rfilter(os.path.join(folder, f))] if os.path.isdir(folder) else []
    if include_depends:
        for depend in rospkg.RosPack().get_depends(package, implicit=False):
            dep_folder = _packages.get_pkg_subdir(depend, subdir, False)
            if dep_folder and os.path.isdir(dep_folder):
                found += [_names.resource_name(depend, f, my_pkg=package) for f in os.listdir(dep_folder)
                          if rfilter(os.path.join(dep_folder, f))]
    return found


def list_package_resources(package: str, include_depends: bool, subdir: str,
                           rfilter: Callable[[str], bool] = os.path.isfile) -> list[str]:
    """list_package_resources_by_dir on the folder of `package`."""
    package_dir = _packages.get_pkg_dir(package)
    assert package_dir is not None  # required: InvalidROSPkgException when there is none
    return list_package_resources_by_dir(package_dir, include_depends, subdir, rfilter)
