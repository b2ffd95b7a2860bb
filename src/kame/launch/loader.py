"""Launch XML into a LaunchConfig, with roslaunch's scoping, typing and wording.

Rules (roslaunch's xmlloader and loader):
- Tags are processed in document order; `if`/`unless` (true/false/1/0) on any tag; unknown tags
  and attributes are configuration warnings (config.errors), not errors.
- A context carries the namespace, remaps (seen by later nodes in scope), env (copied into
  children), args (copied into children; an include starts with only the args passed to it)
  and `~params` (applied to every later node in scope; a group gets its own list, an include
  shares its parent's).
- Args: `arg:=value` from the command line fill top-level <arg default>; `value` is fixed
  (overriding a set arg is an error); `$(arg x)` of an unset arg fails with the file named.
  Include args must be used by the included file unless pass_all_args is set.
- <param> values are typed by kame.launch.values; ~names and params inside a node are private to
  it. <rosparam> YAML dicts are unrolled into one param per leaf, `/` keys stay absolute.
- Errors carry the file and line of the element being processed; nothing is started by loading.
Pure: files are read, but commands (<param command>), packages and anonymous names come from
the `LoaderHost` given.
"""

from __future__ import annotations

import os
import shlex
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import yaml

from kame import names
from kame.launch import xmltree
from kame.launch.errors import ArgError, LaunchError, PackageNotFound
from kame.launch.model import Executable, LaunchConfig, Machine, Node, Param, node_problem
from kame.launch.substitution import Substituter
from kame.launch.values import bool_attr, convert_value, float_attr
from kame.launch.xmltree import Element
from kame.param_yaml import ParamLoader, ParamValueError, check_shape

NODE_ATTRS = ("pkg", "type", "machine", "name", "args", "output", "respawn", "respawn_delay", "cwd", "ns",
              "clear_params", "launch-prefix", "required")
TEST_ATTRS = (*NODE_ATTRS, "test-name", "time-limit", "retry")
PARAM_ATTRS = ("name", "value", "type", "textfile", "binfile", "command")
ROSPARAM_ATTRS = ("command", "ns", "file", "param", "subst_value")
ARG_ATTRS = ("name", "value", "default", "doc")
MACHINE_ATTRS = ("name", "address", "env-loader", "ssh-port", "user", "password", "default", "timeout")
INCLUDE_ATTRS = ("file", "ns", "clear_params", "pass_all_args")
GROUP_ATTRS = ("ns", "clear_params")
REMAP_ATTRS = ("from", "to")
ENV_ATTRS = ("name", "value")


@dataclass(frozen=True)
class LoaderHost:
    """What loading needs from outside: environment, packages, commands, anonymous names."""

    env: Mapping[str, str]
    find_package: Callable[[str], str]  # the package's folder; LaunchError if unknown
    run_command: Callable[[list[str]], tuple[int, str]]  # (exit status, stdout); OSError if it cannot run
    make_anon: Callable[[str], str]


@dataclass(frozen=True)
class ArgDecl:
    name: str
    default: str | None
    doc: str | None


class _Context:
    def __init__(self, ns: str, filename: str, parent: _Context | None = None) -> None:
        self.ns = names.make_global_ns(ns or "/")
        self.filename = filename
        self.parent = parent
        self.remaps: list[tuple[str, str]] = []
        self.params: list[Param] = []
        self.env_args: list[tuple[str, str]] = []
        self.args: dict[str, str] = {}
        self.arg_names: list[str] = []
        self.include_args: dict[str, str] | None = None
        self.args_passed: list[str] = []
        self.pass_all_args = False

    def child(self, ns: str | None) -> _Context:
        if ns:
            child_ns = ns if ns[0] == "/" else names.ns_join(self.ns, ns)
        else:
            child_ns = self.ns
        ctx = _Context(child_ns, self.filename, parent=self)
        ctx.params = self.params
        ctx.env_args = list(self.env_args)
        ctx.args = dict(self.args)
        ctx.arg_names = list(self.arg_names)
        ctx.include_args = self.include_args
        return ctx

    def add_remap(self, src: str, dst: str) -> None:
        src, dst = names.canonicalize(src), names.canonicalize(dst)
        if not src or not dst:
            raise LaunchError("remap from/to attributes cannot be empty")
        for label, name in (("from", src), ("to", dst)):
            if not names.is_legal_name(name):
                raise LaunchError(f"remap {label} [{name}] is not a valid ROS name")
        self.remaps = [r for r in self.remaps if r[0] != src]
        self.remaps.append((src, dst))

    def remap_args(self) -> list[tuple[str, str]]:
        if self.parent is None:
            return list(self.remaps)
        own = {r[0] for r in self.remaps}
        return [r for r in self.parent.remap_args() if r[0] not in own] + self.remaps

    def add_param(self, param: Param) -> None:
        self.params[:] = [p for p in self.params if p.key != param.key]
        self.params.append(param)

    def add_arg(self, name: str, default: str | None, value: str | None) -> None:
        if name in self.arg_names:
            if not self.pass_all_args:
                raise LaunchError(f"arg '{name}' has already been declared")
        else:
            self.arg_names.append(name)
        target = self.args if self.include_args is None else self.include_args
        if value is not None:
            if name in target and not self.pass_all_args:
                raise LaunchError(f"cannot override arg '{name}', which has already been set")
            target[name] = value
        elif default is not None and name not in target:
            target[name] = default


def load_mappings(argv: Sequence[str]) -> dict[str, str]:
    """`name:=value` pairs of a command line, `_param:=value` left out (rosgraph's load_mappings)."""
    found: dict[str, str] = {}
    for arg in argv:
        if ":=" not in arg or not names.is_ros_arg(arg):
            continue
        src, _, dst = (x.strip() for x in arg.partition(":="))
        if src and dst and not (len(src) > 1 and src[0] == "_" and src[1] != "_"):
            found[src] = dst
    return found


class LaunchLoader:
    def __init__(self, config: LaunchConfig, host: LoaderHost, *, verbose: bool = False, resolve_anon: bool = True,
                 ignore_unset_args: bool = False, args_only: bool = False) -> None:
        self.config = config
        self.host = host
        self.verbose = verbose
        self.subst = Substituter(host.env, host.find_package, host.make_anon, resolve_anon)
        self.ignore_unset_args = ignore_unset_args
        self.args_only = args_only
        self.arg_decls: list[ArgDecl] = []  # the top-level file's <arg>s (for --ros-args)
        self._including: list[str] = []

    # ------------------------------------------------------------------ entry points

    def load(self, filename: str, argv: Sequence[str] = (), core: bool = False) -> None:
        try:
            launch = self._parse_file(filename)
            self.config.files.append(filename)
            self._launch(launch, filename, argv, core)
        except ArgError as exc:
            if not self.ignore_unset_args:
                raise LaunchError(f"[{filename}] requires the '{exc.message}' arg to be set",
                                  exc.filename, exc.line) from None
        except RecursionError:
            # each file's nesting is bounded (xmltree.MAX_DEPTH); a long chain of includes is not
            raise LaunchError("launch files nested too deeply (groups within includes within groups)",
                              filename) from None

    def load_string(self, text: str, argv: Sequence[str] = (), core: bool = False) -> None:
        if self.verbose:
            self.config.messages.append("... loading XML")
        launch = self._launch_root(xmltree.parse(text, "string"))
        self._launch(launch, "string", argv, core)

    # ------------------------------------------------------------------ helpers

    def _parse_file(self, filename: str) -> Element:
        if self.verbose:
            self.config.messages.append(f"... loading XML file [{filename}]")
        try:
            with open(filename, "rb") as f:
                data = f.read()
        except OSError as exc:
            raise LaunchError(f"Invalid roslaunch XML syntax: {exc}", filename) from None
        return self._launch_root(xmltree.parse(data, filename))

    @staticmethod
    def _launch_root(root: Element) -> Element:
        found = xmltree.find_all(root, "launch")
        if len(found) != 1:
            raise LaunchError("Invalid roslaunch XML syntax: no root <launch> tag", root.filename, root.line)
        return found[0]

    def _launch(self, launch: Element, filename: str, argv: Sequence[str], core: bool) -> None:
        self._deprecated(launch, filename)
        ns = _ros_namespace(argv, self.host.env)
        root = _Context(ns, filename)
        root.args = load_mappings(argv)
        if xmltree.find_all(launch, "master"):
            self.config.errors.append("WARNING: ignoring defunct <master /> tag")
        self._including = [os.path.abspath(filename)]
        self._recurse(launch.children, root, None, core, top=True)

    def _deprecated(self, launch: Element, filename: str | None) -> None:
        message = launch.get("deprecated")
        if message:
            self.config.errors.append(f"[{filename}] DEPRECATED: {message}" if filename
                                      else f"Deprecation Warning: {message}")

    def _resolve(self, text: str, ctx: _Context) -> str:
        return self.subst.resolve(text, ctx.args, ctx.filename)

    def _opt(self, tag: Element, ctx: _Context, attr: str) -> str | None:
        value = tag.get(attr)
        return None if value is None else self._resolve(value, ctx)

    def _req(self, tag: Element, ctx: _Context, attr: str, missing: str) -> str:
        value = tag.get(attr)
        if value is None:
            raise LaunchError(missing.format(attr=f"'{attr}'", xml=tag.toxml()))
        return self._resolve(value, ctx)

    def _check_attrs(self, tag: Element, ctx: _Context, allowed: Sequence[str]) -> None:
        for attr in tag.attrs:
            if attr not in allowed and attr not in ("if", "unless"):
                self.config.errors.append(f"[{ctx.filename}] unknown <{tag.tag}> attribute '{attr}'")

    def _included(self, tag: Element, ctx: _Context) -> bool:
        """The if/unless test."""
        if_val, unless_val = self._opt(tag, ctx, "if"), self._opt(tag, ctx, "unless")
        if if_val is not None and unless_val is not None:
            raise LaunchError("cannot set both 'if' and 'unless' on the same tag")
        try:
            if if_val is not None:
                return bool(convert_value(if_val, "bool"))
            if unless_val is not None:
                return not convert_value(unless_val, "bool")
        except ValueError as exc:
            raise LaunchError(str(exc)) from None
        return True

    # ------------------------------------------------------------------ the walk

    def _recurse(self, tags: list[Element], ctx: _Context, default_machine: Machine | None, core: bool,
                 top: bool = False) -> Machine | None:
        for tag in tags:
            try:
                default_machine = self._tag(tag, ctx, default_machine, core, top)
            except LaunchError as exc:
                if exc.filename is None:
                    exc.filename, exc.line = tag.filename, tag.line
                raise
        return default_machine

    def _tag(self, tag: Element, ctx: _Context, default_machine: Machine | None, core: bool,
             top: bool) -> Machine | None:
        name = tag.tag
        if name == "arg":
            self._arg_tag(tag, ctx, top)
            return default_machine
        if self.args_only or not self._included(tag, ctx):
            return default_machine
        if name == "group":
            self._check_attrs(tag, ctx, GROUP_ATTRS)
            child = self._ns_clear_params(tag, ctx)
            child.params = list(child.params)
            return self._recurse(tag.children, child, default_machine, core)
        if name in ("node", "test"):
            node = self._node_tag(tag, ctx, default_machine, is_test=name == "test")
            if node.is_test:
                self.config.tests.append(node)
            else:
                self.config.add_node(node, core=core, verbose=self.verbose)
        elif name == "param":
            self._param_tag(tag, ctx)
        elif name == "remap":
            src, dst = self._remap_tag(tag, ctx)
            try:
                ctx.add_remap(src, dst)
            except LaunchError as exc:
                raise LaunchError(f"Invalid <remap> tag: {exc}.\nXML is {tag.toxml()}") from None
        elif name == "machine":
            machine, is_default = self._machine_tag(tag, ctx)
            self._add_machine(machine)
            if is_default:
                return machine
        elif name == "rosparam":
            self._rosparam_tag(tag, ctx)
        elif name == "include":
            return self._include_tag(tag, ctx, default_machine, core)
        elif name == "env":
            self._env_tag(tag, ctx)
        elif name != "master":
            self.config.errors.append(f"unrecognized tag {name}")
        return default_machine

    # ------------------------------------------------------------------ tags

    def _arg_tag(self, tag: Element, ctx: _Context, top: bool) -> None:
        if not self._included(tag, ctx):
            return
        self._check_attrs(tag, ctx, ARG_ATTRS)
        try:
            name = self._req(tag, ctx, "name", "<arg> tag is missing required attribute: {attr}")
            value, default, doc = (self._opt(tag, ctx, a) for a in ("value", "default", "doc"))
            if value is not None and default is not None:
                raise LaunchError("<arg> tag must have one and only one of value/default.")
            ctx.add_arg(name, default=default, value=value)
        except ArgError as exc:
            raise LaunchError(f"arg '{exc.message}' is not defined. \n\nArg xml is {tag.toxml()}") from None
        except PackageNotFound as exc:
            raise PackageNotFound(f"The following package was not found in {tag.toxml()}: {exc}") from None
        except LaunchError as exc:
            raise LaunchError(f"Invalid <arg> tag: {exc}. \n\nArg xml is {tag.toxml()}") from None
        if top and value is None:
            self.arg_decls.append(ArgDecl(name, default, doc))

    def _ns_clear_params(self, tag: Element, ctx: _Context, node_name: str | None = None,
                         include_file: str | None = None) -> _Context:
        ns = None
        if "ns" in tag.attrs:
            ns = self._resolve(tag.attrs["ns"], ctx)
            if not ns:
                raise LaunchError(f"<{tag.tag}> tag has an empty 'ns' attribute")
        child = ctx.child(ns)
        if include_file is not None:
            child.arg_names = []
            child.filename = include_file
            child.include_args = {}
        clear = self._opt(tag, ctx, "clear_params")
        if clear and _bool(clear, False, "clear_params"):
            if tag.tag == "node":
                if not node_name:
                    raise LaunchError("<node> tag must have a 'name' attribute to use 'clear_params' attribute")
                self.config.clear_params.append(names.make_global_ns(names.ns_join(child.ns, node_name)))
            else:
                if not ns:
                    raise LaunchError("'ns' attribute must be set in order to use 'clear_params'")
                self.config.clear_params.append(child.ns)
        return child

    def _node_tag(self, tag: Element, ctx: _Context, default_machine: Machine | None, is_test: bool) -> Node:
        kind = tag.tag
        missing = "<" + kind + "> tag is missing required attribute: {attr}. Node xml is {xml}"
        try:
            self._check_attrs(tag, ctx, TEST_ATTRS if is_test else NODE_ATTRS)
            test_name: str | None = None
            time_limit, retry = 60.0, 0
            if is_test:
                for attr in ("respawn", "respawn_delay", "output"):
                    if attr in tag.attrs:
                        raise LaunchError(f"<test> tags cannot have '{attr}' attribute")
                test_name = self._req(tag, ctx, "test-name", missing)
                time_limit, retry = self._test_limits(tag, ctx)
                name = self._opt(tag, ctx, "name") or test_name
            else:
                name = self._req(tag, ctx, "name", missing)
            if not names.is_legal_name(name):
                self.config.errors.append(f"WARN: illegal <node> name '{name}'.\nhttp://ros.org/wiki/Names\n"
                                          f"This will likely cause problems with other ROS tools.\n"
                                          f"Node xml is {tag.toxml()}")
            child = self._ns_clear_params(tag, ctx, node_name=name)
            param_ns = child.child(name)
            param_ns.params = []
            pkg = self._req(tag, ctx, "pkg", missing)
            node_type = self._req(tag, ctx, "type", missing)
            machine = self._opt(tag, ctx, "machine")
            if not machine and default_machine is not None:
                machine = default_machine.name
            required = _bool(self._opt(tag, ctx, "required"), False, "required")
            respawn = _bool(self._opt(tag, ctx, "respawn"), False, "respawn")
            try:
                respawn_delay = float_attr(self._opt(tag, ctx, "respawn_delay"), 0.0, "respawn_delay")
            except ValueError as exc:
                raise LaunchError(str(exc)) from None
            remap_ctx = ctx.child("")
            env_ctx = ctx.child("")
            for t in tag.children:
                if t.tag == "remap":
                    if self._included(t, ctx):
                        remap_ctx.add_remap(*self._remap_tag(t, ctx))
                elif t.tag == "param":
                    if self._included(t, param_ns):
                        self._param_tag(t, param_ns, force_local=True)
                elif t.tag == "rosparam":
                    if self._included(t, param_ns):
                        self._rosparam_tag(t, param_ns)
                elif t.tag == "env":
                    if self._included(t, env_ctx):
                        self._env_tag(t, env_ctx)
                else:
                    self.config.errors.append(f"WARN: unrecognized '{t.tag}' child tag in the parent tag element: "
                                              f"{tag.toxml()}")
            output = "log" if is_test else self._opt(tag, ctx, "output")
            cwd = self._opt(tag, ctx, "cwd")
            cwd = "ROS_HOME" if cwd == "ros_home" else cwd
            problem = node_problem(pkg, node_type, name, respawn, required, output, cwd)
            if problem is not None:
                raise LaunchError(problem)
            for p in (*ctx.params, *param_ns.params):
                key = p.key[1:] if names.is_private(p.key) else p.key
                self.config.add_param(Param(param_ns.ns + key, p.value), verbose=self.verbose)
            return Node(pkg, node_type, name, namespace=child.ns, machine_name=machine,
                        args=self._opt(tag, ctx, "args") or "",
                        respawn=respawn, respawn_delay=respawn_delay, remap_args=remap_ctx.remap_args(),
                        env_args=list(env_ctx.env_args), output=None if is_test else output,
                        cwd=cwd, launch_prefix=self._opt(tag, ctx, "launch-prefix"),
                        required=required, filename=ctx.filename, line=tag.line, test_name=test_name,
                        time_limit=time_limit, retry=retry)
        except (ArgError, PackageNotFound):
            raise
        except LaunchError as exc:
            if exc.message.startswith(f"<{kind}> tag is missing"):
                raise
            raise LaunchError(f"Invalid <node> tag: {exc}. \n\nNode xml is {tag.toxml()}") from None

    def _test_limits(self, tag: Element, ctx: _Context) -> tuple[float, int]:
        limit_text = self._opt(tag, ctx, "time-limit")
        retry_text = self._opt(tag, ctx, "retry")
        time_limit, retry = 60.0, 0
        if limit_text:
            try:
                time_limit = float(limit_text)
            except ValueError:
                raise LaunchError(f"'time-limit' must be a number: [{limit_text}]") from None
            if time_limit <= 0.0:
                raise LaunchError("'time-limit' must be a positive number")
        if retry_text:
            try:
                retry = int(retry_text)
            except ValueError:
                raise LaunchError(f"'retry' must be a number: [{retry_text}]") from None
        return time_limit, retry

    def _param_tag(self, tag: Element, ctx: _Context, force_local: bool = False) -> None:
        self._check_attrs(tag, ctx, PARAM_ATTRS)
        try:
            ptype = (tag.get("type") or "auto").lower().strip()
            value, textfile, binfile, command = (self._opt(tag, ctx, a)
                                                 for a in ("value", "textfile", "binfile", "command"))
            if sum(v is not None for v in (value, textfile, binfile, command)) != 1:
                raise LaunchError("<param> tag must have one and only one of value/textfile/binfile.")
            if "name" not in tag.attrs:
                raise LaunchError(f"<param> tag is missing required attribute: 'name'. \n\nParam xml is {tag.toxml()}")
            name = self._resolve(tag.attrs["name"].strip(), ctx)
            typed = self._param_value(name, ptype, value, textfile, binfile, command)
        except ValueError as exc:
            raise LaunchError(f"Invalid <param> tag: {exc}. \n\nParam xml is {tag.toxml()}") from None
        if names.is_private(name) or force_local:
            ctx.add_param(Param(name, typed))
        else:
            self.config.add_param(Param(names.ns_join(ctx.ns, name), typed), verbose=self.verbose)

    def _param_value(self, name: str, ptype: str, value: str | None, textfile: str | None, binfile: str | None,
                     command: str | None) -> Any:
        if value is not None:
            return convert_value(value.strip(), ptype)
        if textfile is not None:
            try:
                with open(textfile) as f:
                    return convert_value(f.read(), ptype)
            except OSError as exc:
                raise ValueError(str(exc)) from None
        if binfile is not None:
            try:
                with open(binfile, "rb") as b:
                    return b.read()
            except OSError as exc:
                raise ValueError(str(exc)) from None
        assert command is not None
        if self.verbose:
            self.config.messages.append(f"... executing command param [{command}]")
        argv = shlex.split(command)
        try:
            status, out = self.host.run_command(argv)
        except OSError as exc:
            raise ValueError(f"Cannot load command parameter [{name}]: no such command [{argv}]") from exc
        if status != 0:
            raise ValueError(f"Cannot load command parameter [{name}]: command [{argv}] returned with code [{status}]")
        return convert_value(out, ptype)

    def _rosparam_tag(self, tag: Element, ctx: _Context) -> None:
        self._check_attrs(tag, ctx, ROSPARAM_ATTRS)
        try:
            cmd, ns, file_, param, subst = (self._opt(tag, ctx, a) for a in ROSPARAM_ATTRS)
            subst_value = _bool(subst, False, "subst_value")
            param = names.ns_join(ns or "", param or "")
            self._load_rosparam(ctx, cmd or "load", param, file_, tag.text,
                                (lambda text: self._resolve(text, ctx)) if subst_value else None)
        except ValueError as exc:
            raise LaunchError(f"error loading <rosparam> tag: \n\t{exc}\nXML is {tag.toxml()}") from None

    def _load_rosparam(self, ctx: _Context, cmd: str, param: str, file_: str | None, text: str,
                       subst: Callable[[str], str] | None) -> None:
        if cmd not in ("load", "dump", "delete"):
            raise ValueError("command must be 'load', 'dump', or 'delete'")
        if file_ is not None:
            if cmd == "load" and not os.path.isfile(file_):
                raise ValueError(f"file does not exist [{file_}]")
            if cmd == "delete":
                raise ValueError("'file' attribute is invalid with 'delete' command.")
        full = names.ns_join(ctx.ns, param) if param else ctx.ns
        if cmd == "dump":
            self.config.executables.append(Executable("rosparam", ("dump", file_ or "", full)))
            return
        if cmd == "delete":
            self.config.executables.append(Executable("rosparam", ("delete", full)))
            return
        if file_:
            with open(file_) as f:
                text = f.read()
        if subst is not None:
            text = subst(text)
        try:
            data = yaml.load(text, Loader=ParamLoader)
            check_shape(data)
        except (yaml.YAMLError, RecursionError, ParamValueError) as exc:
            detail = "nested too deeply" if isinstance(exc, RecursionError) else exc
            if file_:
                raise ValueError(f"file {file_} contains invalid YAML:\n{detail}") from None
            raise ValueError(f"Error within YAML block:\n\t{detail}\n\nYAML is:\n{text}") from None
        if data is None:
            data = {}
        if not param and not isinstance(data, dict):
            raise ValueError("'param' attribute must be set for non-dictionary values")
        self._add_unrolled(full, data)

    def _add_unrolled(self, name: str, value: Any) -> None:
        if not name:
            raise ValueError("no parameter name specified")
        if name == "/" and not isinstance(value, dict):
            raise ValueError("Cannot load non-dictionary types into global namespace '/'")
        if isinstance(value, dict):
            for key, item in value.items():
                self._add_unrolled(names.ns_join(name, str(key)), item)
        else:
            self.config.add_param(Param(name, value), verbose=self.verbose)

    def _remap_tag(self, tag: Element, ctx: _Context) -> tuple[str, str]:
        self._check_attrs(tag, ctx, REMAP_ATTRS)
        if "from" not in tag.attrs or "to" not in tag.attrs:
            raise LaunchError(f"<remap> tag is missing required from/to attributes: {tag.toxml()}")
        return self._resolve(tag.attrs["from"], ctx), self._resolve(tag.attrs["to"], ctx)

    def _env_tag(self, tag: Element, ctx: _Context) -> None:
        self._check_attrs(tag, ctx, ENV_ATTRS)
        if "name" not in tag.attrs or "value" not in tag.attrs:
            raise LaunchError(f"<env> tag is missing required name/value attributes: {tag.toxml()}")
        name, value = self._resolve(tag.attrs["name"], ctx), self._resolve(tag.attrs["value"], ctx)
        if not name:
            raise LaunchError(f"Invalid <env> tag: 'name' attribute must be non-empty. \nXML is {tag.toxml()}")
        ctx.env_args.append((name, value))

    def _machine_tag(self, tag: Element, ctx: _Context) -> tuple[Machine, bool]:
        if any(a in tag.attrs for a in ("ros-root", "ros-package-path", "ros-ip", "ros-hostname")):
            raise LaunchError("<machine>: ros-* attributes are not supported since ROS Fuerte.\n"
                              "Please use env-loader instead")
        self._check_attrs(tag, ctx, MACHINE_ATTRS)
        missing = "<machine> tag is missing required attribute: {attr}"
        name = self._req(tag, ctx, "name", missing)
        address = self._req(tag, ctx, "address", missing)
        env_loader, ssh_port, user, password, default, timeout = (
            self._opt(tag, ctx, a) for a in ("env-loader", "ssh-port", "user", "password", "default", "timeout"))
        default = (default or "false").lower()
        if default not in ("true", "false", "never"):
            raise LaunchError(f"Invalid value for 'attribute': {default}")
        for t in tag.children:
            if t.tag == "env":
                raise LaunchError("<machine>: <env> tag is not supported since ROS Fuerte.\n"
                                  "Please use env-loader instead")
            self.config.errors.append(f"unrecognized '{t.tag}' tag in <machine> tag")
        limit: float | None = None
        if timeout == "":
            raise LaunchError("'timeout' cannot be empty")
        if timeout is not None:
            try:
                limit = float(timeout)
            except ValueError:
                raise LaunchError(f"'timeout' be a number: [{timeout}]") from None
            if limit <= 0.0:
                raise LaunchError(f"'timeout' be a positive number: [{timeout}]")
        try:
            port = int(ssh_port or "22")
        except ValueError:
            raise LaunchError(f"invalid ssh-port: [{ssh_port}]") from None
        machine = Machine(name, address, env_loader, port, user, password, default != "never", limit)
        return machine, default == "true"

    def _add_machine(self, machine: Machine) -> None:
        known = self.config.machines.get(machine.name)
        if known is not None and known != machine:
            raise LaunchError(f"Machine [{machine.name}] already added and does not match duplicate entry")
        if known is None:
            self.config.machines[machine.name] = machine
            if self.verbose:
                self.config.messages.append(f"Added machine [{machine.name}]")

    def _include_tag(self, tag: Element, ctx: _Context, default_machine: Machine | None,
                     core: bool) -> Machine | None:
        self._check_attrs(tag, ctx, INCLUDE_ATTRS)
        if "file" not in tag.attrs:
            raise LaunchError(f"<include> tag is missing required attribute: 'file'. XML is {tag.toxml()}")
        inc = self._resolve(tag.attrs["file"], ctx)
        pass_all = _bool(self._opt(tag, ctx, "pass_all_args"), False, "pass_all_args")
        child = self._ns_clear_params(tag, ctx, include_file=inc)
        if pass_all:
            child.pass_all_args = True
            for name, value in ctx.args.items():
                child.add_arg(name, default=None, value=value)
        child.filename = ctx.filename  # <arg> children are resolved in the including file
        for t in tag.children:
            if t.tag == "env":
                if self._included(t, child):
                    self._env_tag(t, child)
            elif t.tag == "arg":
                self._arg_tag(t, child, top=False)
            else:
                self.config.errors.append(f"WARN: unrecognized '{t.tag}' tag in <include> tag")
        child.filename = inc
        passed = child.include_args or {}
        for name in child.arg_names:
            if name not in passed:
                raise LaunchError("include args must have declared values")
        child.args_passed = list(passed)
        child.arg_names = []
        child.args = dict(passed)
        child.include_args = None
        absolute = os.path.abspath(inc)
        if absolute in self._including:
            chain = " -> ".join([*self._including, absolute])
            raise LaunchError(f"include cycle: {chain}")
        try:
            launch = self._parse_file(inc)
            self.config.files.append(inc)
            self._deprecated(launch, inc)
            self._including.append(absolute)
            try:
                default_machine = self._recurse(launch.children, child, default_machine, core)
            finally:
                self._including.pop()
            if not pass_all:
                unused = [a for a in child.args_passed if a not in child.arg_names]
                if unused:
                    raise LaunchError(f"unused args [{', '.join(unused)}] for include of [{inc}]")
        except ArgError as exc:
            if not self.ignore_unset_args:
                raise LaunchError(f"included file [{inc}] requires the '{exc.message}' arg to be set",
                                  exc.filename, exc.line) from None
        except PackageNotFound:
            raise
        except LaunchError as exc:
            if exc.message.startswith(("while processing", "included file", "include cycle")):
                raise
            raise LaunchError(f"while processing {inc}:\n{exc.message}", exc.filename, exc.line) from None
        if self.verbose:
            self.config.messages.append(f"... done importing include file [{inc}]")
        return default_machine


def _bool(value: str | None, default: bool, label: str) -> bool:
    try:
        return bool_attr(value, default, label)
    except ValueError as exc:
        raise LaunchError(str(exc)) from None


def _ros_namespace(argv: Sequence[str], env: Mapping[str, str]) -> str:
    for arg in argv:
        if arg.startswith("__ns:="):
            return names.make_global_ns(arg[len("__ns:="):])
    return names.make_global_ns(env.get("ROS_NAMESPACE", "/") or "/")
