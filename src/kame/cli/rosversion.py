"""rosversion: a ROS package's version, or the distribution's name, as rospkg's rosversion prints.

    rosversion [-s] (-d | -a | PACKAGE)

-d prints ROS_DISTRO, or `noetic` (the distribution kame re-creates) when it is unset.
An unknown package prints `Cannot locate [PACKAGE]` on stdout and exits 1; a package.xml
without a version prints `<unversioned>`.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence

from kame.manifest import ManifestError, read_manifest
from kame.msg.catalog import find_packages, package_path_roots

DISTRO = "noetic"


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="rosversion",
        description="rosversion -d: Output the version of the given package\n"
        "rosversion package: Output the ROS distribution name",
        formatter_class=argparse.RawTextHelpFormatter)
    parser.add_argument("-s", "--skip-newline", action="store_true", help="Skip trailing newline")
    group = parser.add_mutually_exclusive_group(required=True)
    group.add_argument("package", nargs="?", help="The ROS package name (e.g. 'roscpp')")
    group.add_argument("-d", "--distro", action="store_true", help="Output the ROS distribution name")
    group.add_argument("-a", "--all", action="store_true", help="Show all ROS package names and their versions")
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    args = _parser().parse_args(sys.argv[1:] if argv is None else argv)
    end = "" if args.skip_newline else "\n"
    if args.distro:
        print(os.environ.get("ROS_DISTRO") or DISTRO, end=end)
        return 0
    packages = find_packages(package_path_roots())

    def version_of(name: str) -> str | None:
        try:
            return read_manifest(name, packages[name].path).version
        except ManifestError:
            return None

    if args.all:
        for name in sorted(packages):
            print(f"{name}: {version_of(name)}", end=end)
        return 0
    if args.package not in packages:
        print(f"Cannot locate [{args.package}]")
        return 1
    print(version_of(args.package) or "<unversioned>", end=end)
    return 0


if __name__ == "__main__":
    sys.exit(main())
