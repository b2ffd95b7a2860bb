"""Tab completion for the ros* tools: what to offer for the word under the cursor.

bash calls `python -m kame.shell.complete CWORD WORD0 WORD1 ...` (its COMP_CWORD and
COMP_WORDS) and takes one candidate a line. Candidates already match the typed prefix.

Each tool is a table: either subcommands, each with the kinds of its positional arguments,
or positional kinds straight away (rosrun PKG EXECUTABLE). The last kind of a list repeats
when it ends with `*`. Options (words starting with `-`) are skipped when counting
positionals; the options named in VALUE_OPTIONS swallow the next word too. Live names
(topics, nodes, services, parameters) come from the master named by ROS_MASTER_URI with a
short timeout, so a missing master costs at most a second and yields nothing.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable, Mapping, Sequence
from functools import cache
from pathlib import Path
from typing import Any

from kame import environ
from kame.msg.catalog import Package
from kame.shell import locate

MASTER_TIMEOUT = 1.0

Kinds = tuple[str, ...]

SUBCOMMANDS: dict[str, dict[str, Kinds]] = {
    "rostopic": {"bw": ("topic*",), "delay": ("topic",), "echo": ("topic",), "find": ("msg",),
                 "hz": ("topic*",), "info": ("topic",), "list": ("namespace",), "pub": ("topic", "topic_type"),
                 "type": ("topic",)},
    "rosnode": {"cleanup": (), "info": ("node*",), "kill": ("node*",), "list": ("namespace",),
                "machine": (), "ping": ("node",)},
    "rosservice": {"args": ("service",), "call": ("service",), "find": ("srv",), "info": ("service",),
                   "list": ("namespace",), "type": ("service",), "uri": ("service",)},
    "rosparam": {"delete": ("param",), "dump": ("file", "namespace"), "get": ("param",), "list": ("namespace",),
                 "load": ("file", "namespace"), "set": ("param",)},
    "rosmsg": {"info": ("msg",), "list": (), "md5": ("msg",), "package": ("msg_package",),
               "packages": (), "show": ("msg",)},
    "rossrv": {"info": ("srv",), "list": (), "md5": ("srv",), "package": ("srv_package",),
               "packages": (), "show": ("srv",)},
    "rospack": {cmd: ("package",) for cmd in (
        "cflags-only-I", "cflags-only-other", "depends", "depends-indent", "depends-manifests", "depends-msgsrv",
        "depends-on", "depends-on1", "depends-why", "depends1", "export", "find", "help", "langs", "libs-only-L",
        "libs-only-l", "libs-only-other", "list", "list-duplicates", "list-names", "plugins", "profile", "rosdep",
        "rosdep0", "vcs", "vcs0")},
    "rosstack": {cmd: ("package",) for cmd in ("contains", "contains-path", "depends", "depends-on", "depends1",
                                               "find", "list", "list-names", "profile")},
    "rosbag": {"check": ("file*",), "compress": ("file*",), "convert": ("file*",), "decompress": ("file*",),
               "filter": ("file*",),
               "fix": ("file*",), "help": (), "info": ("file*",), "play": ("file*",), "record": ("topic*",),
               "reindex": ("file*",)},
    "rosclean": {"check": (), "purge": ()},
    "catkin": {"build": ("ws_package*",), "clean": ("ws_package*",), "config": (), "init": (),
               "list": (), "locate": ("ws_package",)},
}

POSITIONALS: dict[str, Kinds] = {
    "rosrun": ("package", "executable", "file*"),
    "roslaunch": ("package_or_launch", "launch_file", "launch_arg*"),
    "roscd": ("location",),
    "rosls": ("location",),
    "rospd": ("location",),
    "rosed": ("package", "package_file"),
    "roscat": ("package", "package_file"),
    "roscp": ("package", "package_file", "file"),
    "rosversion": ("package",),
    "catkin_create_pkg": ("none", "package*"),
    "catkin_make": ("none*",),
    "roscore": ("none*",),
    "rosmaster": ("none*",),
    "roswtf": ("file*",),
    "rosout": ("none*",),
}

OPTIONS: dict[str, tuple[str, ...]] = {
    "rostopic echo": ("--bag", "--filter", "--nostr", "--noarr", "--offset", "-a", "-b", "-c", "-n", "-p", "-w"),
    "rostopic hz": ("--filter", "--window", "--wall-time", "-w"),
    "rostopic bw": ("--window", "-w"),
    "rostopic delay": ("--window", "-w"),
    "rostopic list": ("--bag", "--host", "--publishers", "--subscribers", "-b", "-p", "-s", "-v"),
    "rostopic pub": ("--file", "--latch", "--once", "--rate", "--substitute-keywords", "-1", "-f", "-l", "-r",
                     "-s", "-v"),
    "rosnode list": ("--all", "--quiet", "-a", "-u"),
    "rosnode ping": ("--all", "--count", "-a", "-c"),
    "rosnode kill": ("--all", "-a"),
    "rosnode info": ("--quiet", "-q"),
    "rosservice list": ("--nodes", "-n"),
    "rosservice call": ("--verbose", "--wait", "-v"),
    "rosparam get": ("--pretty", "-p"),
    "rosparam set": ("--textfile", "--binfile", "--verbose", "-t", "-b", "-v"),
    "rosparam load": ("--verbose", "-v"),
    "rosparam dump": ("--verbose", "-v"),
    "rosmsg show": ("--raw", "-r"),
    "rossrv show": ("--raw", "-r"),
    "rosclean purge": ("-y",),
    "rosrun": ("--debug", "--prefix"),
    "roslaunch": ("--args", "--dump-params", "--files", "--local", "--nodes", "--screen", "--wait", "-p", "-v"),
    "roscore": ("--port", "--timeout", "-p", "-v", "-w"),
    "rosversion": ("--distro", "-d"),
    "catkin_make": ("--cmake-args", "--force-cmake", "--only-pkg-with-deps", "--pkg", "--source", "--build",
                    "-C", "-DCATKIN_BLACKLIST_PACKAGES=", "-DCATKIN_WHITELIST_PACKAGES=", "-j"),
    "catkin_create_pkg": ("--author", "--description", "--license", "--maintainer", "--meta", "--pkg_version",
                          "-D", "-V", "-a", "-l", "-m"),
}

VALUE_OPTIONS = {"-n", "-c", "-w", "-r", "-f", "-b", "-t", "-p", "--offset", "--filter", "--window", "--rate",
                 "--file", "--bag", "--count", "--prefix", "--port", "--timeout", "-C", "--source", "--build",
                 "-j", "-D", "-V", "-a", "-l", "-m", "--description", "--author", "--license", "--maintainer",
                 "--pkg_version", "--host"}


class Sources:
    """Where candidates come from: packages on disk and the live graph. Overridable in tests."""

    def __init__(self, env: Mapping[str, str] | None = None) -> None:
        self.env = dict(os.environ if env is None else env)

    @cache  # noqa: B019 - one Sources per completion
    def packages(self) -> dict[str, Package]:
        return locate.packages(self.env)

    def package_names(self) -> list[str]:
        return sorted(self.packages())

    def locations(self) -> list[str]:
        return locate.list_locations(self.env)

    def subdirs(self, arg: str) -> list[str]:
        return locate.subdirs(arg, self.env)

    def package_files(self, package: str, executable: bool = False) -> list[str]:
        return locate.package_file_names(package, self.env, executable)

    def launch_files(self, package: str) -> list[str]:
        found = self.packages().get(package)
        if found is None:
            return []
        return sorted({p.name for p in found.path.rglob("*.launch")} | {p.name for p in found.path.rglob("*.test")})

    def types(self, kind: str) -> list[str]:
        from kame.msg.catalog import MsgCatalog
        from kame.msg.describe import Kind, all_types

        return all_types(MsgCatalog(self.packages()), Kind(kind))

    def type_packages(self, kind: str) -> list[str]:
        from kame.msg.catalog import MsgCatalog
        from kame.msg.describe import Kind, packages_with

        return packages_with(MsgCatalog(self.packages()), Kind(kind))

    def workspace_packages(self) -> list[str]:
        from kame.catkin.workspace import find_workspace_packages

        here = Path.cwd()
        for folder in (here, *here.parents):
            if (folder / "src").is_dir() and ((folder / ".catkin_workspace").exists() or
                                              (folder / ".catkin_tools").is_dir() or (folder / "devel").is_dir()):
                return sorted(p.name for p in find_workspace_packages(folder / "src"))
        return []

    def _master(self, method: str, *args: object) -> Any:
        from kame.node.master_proxy import MasterProxy

        uri = environ.master_uri(self.env)
        proxy = MasterProxy(uri, "/rosbash_complete", timeout=MASTER_TIMEOUT)
        try:
            return proxy.call(method, *args)
        finally:
            proxy.close()

    @cache  # noqa: B019 - one Sources per completion
    def system_state(self) -> tuple[list[Any], list[Any], list[Any]]:
        try:
            pubs, subs, srvs = self._master("getSystemState")
            return list(pubs), list(subs), list(srvs)
        except Exception:  # no master, or a broken one: nothing to offer
            return [], [], []

    def topics(self) -> list[str]:
        pubs, subs, _ = self.system_state()
        return sorted({str(entry[0]) for entry in [*pubs, *subs]})

    def nodes(self) -> list[str]:
        found: set[str] = set()
        for part in self.system_state():
            for entry in part:
                found.update(str(n) for n in entry[1])
        return sorted(found)

    def services(self) -> list[str]:
        return sorted(str(entry[0]) for entry in self.system_state()[2])

    def params(self) -> list[str]:
        try:
            return sorted(str(n) for n in self._master("getParamNames"))
        except Exception:
            return []

    def topic_type(self, topic: str) -> str | None:
        try:
            for name, type_name in self._master("getTopicTypes"):
                if name == topic:
                    return str(type_name)
        except Exception:
            return None
        return None


def _positionals(words: Sequence[str], start: int, cword: int) -> int:
    """How many positional arguments precede words[cword], counting from words[start]."""
    count = 0
    i = start
    while i < cword:
        word = words[i]
        if word.startswith("-") and len(word) > 1:
            if word in VALUE_OPTIONS and i + 1 < cword:
                i += 1
        elif ":=" not in word:
            count += 1
        i += 1
    return count


def _kind_at(kinds: Kinds, index: int) -> str | None:
    if index < len(kinds):
        return kinds[index].rstrip("*")
    if kinds and kinds[-1].endswith("*"):
        return kinds[-1].rstrip("*")
    return None


def _namespaces(names: list[str]) -> list[str]:
    found = {"/"}
    for name in names:
        parts = name.strip("/").split("/")
        for n in range(1, len(parts)):
            found.add("/" + "/".join(parts[:n]))
    return sorted(found)


def _positional_words(words: Sequence[str], start: int, cword: int) -> list[str]:
    found = []
    i = start
    while i < cword:
        word = words[i]
        if word.startswith("-") and len(word) > 1:
            if word in VALUE_OPTIONS and i + 1 < cword:
                i += 1
        elif ":=" not in word:
            found.append(word)
        i += 1
    return found


def _candidates_for(kind: str, prefix: str, before: list[str], src: Sources, tool: str) -> list[str]:
    providers: dict[str, Callable[[], list[str]]] = {
        "package": src.package_names,
        "ws_package": src.workspace_packages,
        "topic": src.topics,
        "node": src.nodes,
        "service": src.services,
        "param": src.params,
        "msg": lambda: src.types("msg"),
        "srv": lambda: src.types("srv"),
        "msg_package": lambda: src.type_packages("msg"),
        "srv_package": lambda: src.type_packages("srv"),
    }
    if kind in providers:
        return providers[kind]()
    if kind == "namespace":
        live = src.params() if tool == "rosparam" else src.services() if tool == "rosservice" else (
            src.nodes() if tool == "rosnode" else src.topics())
        return _namespaces(live)
    if kind == "location":
        if "/" in prefix:
            return src.subdirs(prefix)
        return [loc + "/" for loc in src.locations()]
    if kind == "executable" and before:
        return src.package_files(before[-1], executable=True)
    if kind == "package_file" and before:
        return src.package_files(before[-1])
    if kind == "package_or_launch":
        return src.package_names()
    if kind == "launch_file" and before:
        return src.launch_files(before[-1])
    if kind == "topic_type" and before:
        found = src.topic_type(before[-1])
        return [found] if found else src.types("msg")
    return []  # files and free text: bash's default completion


def candidates(words: Sequence[str], cword: int, src: Sources | None = None) -> list[str]:
    """What bash should offer for words[cword] (COMP_WORDS, COMP_CWORD)."""
    src = src or Sources()
    if not words or cword < 1:
        return []
    tool = os.path.basename(words[0])
    prefix = words[cword] if cword < len(words) else ""
    found: list[str]
    if tool in SUBCOMMANDS:
        table = SUBCOMMANDS[tool]
        if cword == 1:
            found = sorted(table) if not prefix.startswith("-") else ["-h", "--help"]
        else:
            sub = words[1]
            key = f"{tool} {sub}"
            if prefix.startswith("-"):
                found = [*OPTIONS.get(key, ()), "-h", "--help"]
            else:
                kinds = table.get(sub, ())
                kind = _kind_at(kinds, _positionals(words, 2, cword))
                found = _candidates_for(kind, prefix, _positional_words(words, 2, cword), src, tool) if kind else []
    elif tool in POSITIONALS:
        if prefix.startswith("-"):
            found = [*OPTIONS.get(tool, ()), "-h", "--help"]
        else:
            kinds = POSITIONALS[tool]
            kind = _kind_at(kinds, _positionals(words, 1, cword))
            found = _candidates_for(kind, prefix, _positional_words(words, 1, cword), src, tool) if kind else []
    else:
        return []
    return [c for c in dict.fromkeys(found) if c.startswith(prefix)]


def main(argv: Sequence[str] | None = None) -> int:
    args = list(sys.argv[1:] if argv is None else argv)
    if not args or not args[0].isdigit():
        print("usage: python -m kame.shell.complete COMP_CWORD WORD...", file=sys.stderr)
        return 2
    try:
        found = candidates(args[1:], int(args[0]))
    except Exception:  # completion must never spill a traceback into the prompt
        return 1
    if found:
        sys.stdout.write("\n".join(found) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
