"""roslib's rosbuild manifests (manifest, manifestlib, stack_manifest, stacks,
packages.list_pkgs_by_path) on a tree of one stack holding one package, given on stdin; prints
JSON. Run by kame's interpreter and Debian's /usr/bin/python3 (its real roslib)."""

from __future__ import annotations

import json
import os
import sys
import warnings
from collections.abc import Callable
from typing import Any

warnings.simplefilter("ignore")

import roslib.manifest  # noqa: E402
import roslib.manifestlib  # noqa: E402
import roslib.packages  # noqa: E402
import roslib.stack_manifest  # noqa: E402
import roslib.stacks  # noqa: E402


def outcome(call: Callable[[], Any]) -> Any:
    """What `call` returned (a manifest as its XML), or what it raised."""
    try:
        value = call()
        return value.xml() if isinstance(value, roslib.manifestlib._Manifest) else value
    except Exception as exc:
        return ["raised", type(exc).__name__, str(exc)]


def fields(m: Any) -> dict[str, Any]:
    return {"description": m.description, "brief": m.brief, "author": m.author, "license": m.license,
            "license_url": m.license_url, "url": m.url, "logo": m.logo, "status": m.status, "notes": m.notes,
            "version": m.version, "depends": [str(d) for d in m.depends], "rosdeps": [r.name for r in m.rosdeps],
            "platforms": [[p.os, p.version, p.notes] for p in m.platforms],
            "exports": [[e.tag, e.attrs, e.str, e.xml()] for e in m.exports],
            "versioncontrol": m.versioncontrol.xml() if m.versioncontrol else None,
            "unknown": [t.tagName for t in m.unknown_tags], "xml": m.xml(),
            "cpp_flags": m.get_export("cpp", "cflags")}


def main() -> None:
    root = json.load(sys.stdin)["root"]
    stack_dir = os.path.join(root, "mystack")
    package_dir = os.path.join(stack_dir, "mypkg")
    manifest = roslib.manifest.parse_file(os.path.join(package_dir, "manifest.xml"))
    stack = roslib.stack_manifest.parse_file(os.path.join(stack_dir, "stack.xml"))
    cache: dict[str, Any] = {}
    out = {
        "manifest": fields(manifest), "stack": fields(stack),
        "version_in_manifest": outcome(lambda: roslib.manifest.parse(
            "<package><author>a</author><license>BSD</license><version>1</version></package>")),
        "bad_xml": outcome(lambda: roslib.manifest.parse("<package>"))[:2],
        "two_roots": outcome(lambda: roslib.manifest.parse("<x/>")),
        "stack_exports": outcome(lambda: roslib.stack_manifest.parse(
            "<stack><export><cpp cflags='x'/></export></stack>")),
        "two_authors": outcome(lambda: roslib.manifest.parse(
            "<package><author>a</author><author>b</author></package>")),
        "missing_file": outcome(lambda: roslib.manifest.parse_file(os.path.join(root, "none.xml"))),
        "depend_without_package": outcome(lambda: roslib.manifest.parse("<package><depend/></package>")),
        "platform_without_os": outcome(lambda: roslib.manifest.parse("<package><platform version='1'/></package>")),
        "by_path": [roslib.stacks.list_stacks_by_path(root), roslib.packages.list_pkgs_by_path(root, cache=cache),
                    {k: os.path.relpath(v[0], root) for k, v in cache.items()}],
        "stack_version": [roslib.stacks.get_stack_version_by_dir(stack_dir),
                          roslib.stacks.get_stack_version_by_dir(package_dir)],
        "stack_of": roslib.stacks.stack_of("mypkg"),
        "manifest_file": os.path.relpath(str(roslib.manifest.manifest_file("mypkg")), root),
        "load_manifest": roslib.manifest.load_manifest("mypkg").author,
        "constants": [roslib.manifest.MANIFEST_FILE, roslib.stack_manifest.STACK_FILE, roslib.stacks.ROS_STACK,
                      roslib.manifestlib.REQUIRED, roslib.manifestlib.ALLOWXHTML, roslib.manifestlib.VALID],
        "objects": [str(roslib.manifestlib.Platform("ubuntu", "20.04")), roslib.manifestlib.Depend("a").xml(),
                    roslib.manifestlib.StackDepend("s").xml(), roslib.manifestlib.ROSDep("r").xml(),
                    roslib.manifestlib.Depend("a") == roslib.manifestlib.Depend("a"),
                    outcome(lambda: roslib.manifestlib.Depend("")),
                    roslib.manifestlib.VersionControl("git", None).xml()],
    }
    sys.stdout.write(json.dumps(out))


if __name__ == "__main__":
    main()
