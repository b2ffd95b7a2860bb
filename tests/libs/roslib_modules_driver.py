"""roslib's gentools, srvs and msgs helpers and roslib.message's class lookups on fixed cases;
prints JSON. Run by kame's interpreter and Debian's /usr/bin/python3 (its real roslib), with
ROS_PACKAGE_PATH on the same .msg files (Debian's)."""

from __future__ import annotations

import io
import json
import sys
from collections.abc import Callable
from typing import Any

import roslib.gentools as gentools
import roslib.message
import roslib.msgs as msgs
import roslib.srvs as srvs

SHARE = "/usr/share"


def outcome(call: Callable[[], Any]) -> Any:
    try:
        return call()
    except Exception as exc:
        return ["raised", type(exc).__name__, str(exc)]


def class_name(cls: Any) -> Any:
    return cls if cls is None or isinstance(cls, list) else getattr(cls, "_type", cls.__name__)


def gentools_answers() -> dict[str, Any]:
    out: dict[str, Any] = {}
    for name in ("std_msgs/msg/Header.msg", "geometry_msgs/msg/PoseStamped.msg", "geometry_msgs/msg/Polygon.msg",
                 "std_srvs/srv/SetBool.srv", "std_msgs/msg/MultiArrayLayout.msg"):
        deps = gentools.get_file_dependencies(f"{SHARE}/{name}")
        out[name] = {"deps": deps["deps"], "uniquedeps": deps["uniquedeps"], "package": deps["package"],
                     "files": sorted(deps["files"].items()), "md5": gentools.compute_md5(deps),
                     "md5_v2": gentools.compute_md5_v2(deps), "full_text": gentools.compute_full_text(deps)}
        if name.endswith(".msg"):
            out[name]["md5_text"] = gentools.compute_md5_text(deps, deps["spec"])
    import rosmsg

    _, pose = msgs.load_by_type("geometry_msgs/PoseStamped")
    gentools.get_dependencies(pose, "geometry_msgs")  # registers what it embeds
    constants = msgs.load_from_string("int32 A=1\nstring S=x\ngeometry_msgs/Point[] p\n", "pkg")
    out["spec_to_str"] = [rosmsg.spec_to_str(msgs, pose), rosmsg.spec_to_str(msgs, constants, indent="> ")]
    spec = msgs.load_from_string("Header header\nint32 x\n", "pkg")
    no_files = gentools.get_dependencies(spec, "std_msgs", compute_files=False)
    out["no_files"] = [sorted(no_files), gentools.compute_md5(no_files)]
    out["missing_type"] = outcome(lambda: gentools.get_dependencies(msgs.load_from_string("Nope n\n", "std_msgs"),
                                                                    "std_msgs"))
    return out


def srvs_answers() -> dict[str, Any]:
    spec = srvs.load_from_string("int32 a # the a\nHeader h\n--- lenient\nstring b\n", "pkg", "pkg/S", "S")
    name, loaded = srvs.load_from_file(f"{SHARE}/std_srvs/srv/SetBool.srv", "std_srvs")
    specs, failures = srvs.get_pkg_srv_specs("std_srvs")
    return {
        "spec": [repr(spec), spec.text, spec.full_name, spec.short_name, spec.package, spec.request.text,
                 spec.request.full_name, spec.response.short_name, spec.request.types],
        "equal": [spec == srvs.load_from_string(spec.text, "pkg", "pkg/S", "S"), spec == loaded, spec != loaded],
        "loaded": [name, repr(loaded)],
        "pkg": sorted([n, repr(s)] for n, s in specs), "failures": failures,
        "list": srvs.list_srv_types("std_srvs", False), "file": srvs.srv_file("std_srvs", "Empty"),
        "constants": [srvs.EXT, srvs.SEP, srvs.IODELIM, srvs.COMMENTCHAR],
        "bad_name": outcome(lambda: srvs.load_from_file("/nonexistent/1bad.srv", "pkg")),
    }


def msgs_answers() -> dict[str, Any]:
    verbose = [msgs.is_verbose(), srvs.is_verbose()]
    msgs.set_verbose(True)
    srvs.set_verbose(True)
    verbose += [msgs.is_verbose(), srvs.is_verbose()]
    msgs.set_verbose(False)
    srvs.set_verbose(False)
    msgs._init()
    registered = sorted(msgs.REGISTERED_TYPES)
    msgs.load_package("geometry_msgs")
    after_package = sorted(msgs.REGISTERED_TYPES)
    msgs.reinit()
    specs, failures = msgs.get_pkg_msg_specs("std_msgs")
    converted = [outcome(lambda t=t, v=v: msgs._convert_val(t, v)) for t, v in (
        ("int8", "-128"), ("int8", "128"), ("uint8", "-1"), ("uint64", "18446744073709551615"), ("char", "255"),
        ("byte", "-128"), ("float32", "1.5"), ("string", "  padded  "), ("bool", "1"), ("bool", "0"),
        ("bool", "True"), ("int32", "x"), ("time", "1"))]
    parsed = [outcome(lambda t=t: list(msgs.parse_type(t))) for t in (
        "a[", "a[]", "a[3]", "a]", "[", "a[3", "a[]]", "a[x]", "a[3][]", "a[-1]", "")]
    return {"verbose": verbose, "registered": registered, "after_package": after_package,
            "after_reinit": sorted(msgs.REGISTERED_TYPES), "pkg": sorted([n, repr(s)] for n, s in specs),
            "failures": failures, "converted": converted, "parsed": parsed,
            "constants": [msgs.COMMENTCHAR, msgs.CONSTCHAR, msgs.TIME_MSG, msgs.DURATION_MSG, msgs.VERBOSE,
                          sorted((k, repr(v)) for k, v in msgs.EXTENDED_BUILTINS.items())]}


def message_answers() -> dict[str, Any]:
    names = ["String", "std_msgs/String", "Header", "malformed", "", "a/b/c", "no_pkg/X", "std_msgs/Nope",
             "std_msgs/String[]", "time", "duration"]
    return {
        "messages": [class_name(outcome(lambda n=n: roslib.message.get_message_class(n))) for n in names],
        "services": [class_name(outcome(lambda n=n: roslib.message.get_service_class(n)))
                     for n in ("std_srvs/SetBool", "SetBool", "std_srvs/Nope", "a/b/c")],
        "genpy_names": [roslib.message.check_type.__name__, roslib.message.fill_message_args.__name__,
                        roslib.message.get_printable_message_args.__name__,
                        roslib.message.Time(1, 2).to_nsec(), roslib.message.Duration(3).to_sec(),
                        issubclass(roslib.message.Time, roslib.message.TVal)],
    }


def small_modules() -> dict[str, Any]:
    import warnings

    import roslib
    import roslib.exceptions
    import roslib.names
    import roslib.resources
    import roslib.scriptutil

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        import roslib.rosenv as rosenv

        env = {"ROS_ROOT": "/r", "ROS_MASTER_URI": "http://m:1/", "ROS_HOME": "/h"}
        envs = [rosenv.get_ros_root(env=env), rosenv.get_ros_root(False, env={}), rosenv.get_ros_package_path(env=env),
                outcome(lambda: rosenv.get_ros_package_path(True, env={})), rosenv.get_master_uri(env=env, argv=[]),
                rosenv.get_master_uri(env=env, argv=["__master:=http://x:2/"]),
                outcome(lambda: rosenv.get_master_uri(env=env, argv=["__master:="])),
                outcome(lambda: rosenv.get_master_uri(env={}, argv=[])), rosenv.get_ros_home(env),
                rosenv.get_log_dir(env), rosenv.get_log_dir({"ROS_LOG_DIR": "/l"}), rosenv.get_test_results_dir(env),
                outcome(lambda: rosenv.get_ros_root(env={}))[:2]]
        resolved = [roslib.scriptutil.script_resolve_name("tool", n) for n in ("", "/g", "~p", "rel")]
        import roslib.rospack as rospack

        rospack_answers = [rospack.rospack_depends_1("geometry_msgs"), rospack.rospack_depends("geometry_msgs"),
                           sorted(rospack.rospack_depends_on_1("std_msgs")), rospack.rospack_plugins("std_msgs"),
                           outcome(lambda: rospack.rospackexec(["find", "no_such_package"])), rospack.python3]
    interactive = [roslib.is_interactive()]
    roslib.set_interactive(True)
    interactive.append(roslib.is_interactive())
    names = ["/a/b", "~p", "a", "1a", "a-b", "a/b", "a_b"]
    patterns = [roslib.names.RESOURCE_NAME_LEGAL_CHARS_P, roslib.names.NAME_LEGAL_CHARS_P,
                roslib.names.BASE_NAME_LEGAL_CHARS_P, roslib.names.BASE_RESOURCE_NAME_LEGAL_CHARS_P]
    return {"rosenv": envs, "resolved": resolved, "interactive": interactive, "rospack": rospack_answers,
            "patterns": [[bool(p.match(n)) for n in names] for p in patterns],
            "resources": sorted(roslib.resources.list_package_resources("std_srvs", False, "srv")),
            "resources_filtered": sorted(roslib.resources.list_package_resources(
                "geometry_msgs", False, "msg", lambda f: f.endswith("Stamped.msg"))),
            "exception": issubclass(roslib.exceptions.ROSLibException, Exception)}


def main() -> None:
    out = {"small": small_modules(), "gentools": gentools_answers(), "srvs": srvs_answers(), "msgs": msgs_answers(),
           "message": message_answers()}
    sys.stdout = io.StringIO()  # what loading printed is not the answer
    sys.__stdout__.write(json.dumps(out))


if __name__ == "__main__":
    main()
