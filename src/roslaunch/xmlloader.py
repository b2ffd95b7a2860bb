"""roslaunch.xmlloader: XmlLoader reads launch XML into a ROSLaunchConfig (or anything with its
add_* methods), over kame's launch loader; XmlParseException for a file it cannot read.

XmlLoader is a roslaunch.loader.Loader, as ROS's. Its tag helpers (resolve_args, opt_attrs,
reqd_attrs, ifunless_test) take a DOM element (xml.dom.minidom) and a LoaderContext as ROS's do;
`root_context` is the LoaderContext of the last file loaded: its namespace and the args given.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable, Sequence
from typing import Any, TypeVar
from xml.dom import Node as DomNode
from xml.dom.minidom import parse, parseString

from kame.cli.roslaunch import loader_host
from kame.launch.errors import LaunchError
from kame.launch.loader import LaunchLoader
from kame.launch.model import LaunchConfig
from rosgraph.names import get_ros_namespace, is_legal_name, is_private, make_global_ns, ns_join
from roslaunch import loader, substitution_args
from roslaunch.config import replay
from roslaunch.core import Machine, Node, Param, RLException, Test
from roslaunch.substitution_args import ArgException, SubstitutionException
from rospkg import ResourceNotFound

__all__ = ["CLEAR_PARAMS", "NS", "ArgException", "DomNode", "Machine", "Node", "Param", "ResourceNotFound",
           "SubstitutionException", "Test", "XmlLoader", "XmlParseException", "get_ros_namespace", "ifunless",
           "ifunless_test", "is_legal_name", "is_private", "make_global_ns", "ns_join", "parse", "parseString"]

NS = "ns"
CLEAR_PARAMS = "clear_params"
F = TypeVar("F", bound=Callable[..., Any])


class XmlParseException(RLException):
    """Launch XML that is malformed, or uses an argument, tag or substitution it may not."""


def ifunless_test(obj: XmlLoader, tag: Any, context: loader.LoaderContext) -> bool:
    """Whether `tag` is on, by its `if`/`unless` attribute (XmlParseException if it has both)."""
    if_val, unless_val = obj.opt_attrs(tag, context, ["if", "unless"])
    if if_val is not None and unless_val is not None:
        raise XmlParseException("cannot set both 'if' and 'unless' on the same tag")
    if if_val is not None:
        return bool(loader.convert_value(if_val, "bool"))
    if unless_val is not None:
        return not loader.convert_value(unless_val, "bool")
    return True


def ifunless(f: F) -> F:
    """A tag method `(self, tag, context, ...)` that runs only when the tag is on (ifunless_test)."""

    def call(*args: Any, **kwds: Any) -> Any:
        if ifunless_test(args[0], args[1], args[2]):
            return f(*args, **kwds)
        return None

    return call  # type: ignore[return-value]


class XmlLoader(loader.Loader):
    def __init__(self, resolve_anon: bool = True, args_only: bool = False) -> None:
        self.resolve_anon = resolve_anon
        self.args_only = args_only
        self.root_context: loader.LoaderContext | None = None
        self.ignore_unset_args = False  # load_config_default sets it: a required arg not given is then no error

    def resolve_args(self, args: str | None, context: loader.LoaderContext) -> str | None:
        """`args` with its substitution args resolved in `context`."""
        if args and "$" in args:
            context.resolve_dict["filename"] = context.filename
            return substitution_args.resolve_args(args, context=context.resolve_dict, resolve_anon=self.resolve_anon)
        return args

    def opt_attrs(self, tag: Any, context: loader.LoaderContext, attrs: Sequence[str]) -> list[str | None]:
        """The resolved values of `attrs` on `tag` (None for one it lacks)."""
        return [self.resolve_args(tag.getAttribute(a) if tag.hasAttribute(a) else None, context) for a in attrs]

    def reqd_attrs(self, tag: Any, context: loader.LoaderContext, attrs: Sequence[str]) -> list[str | None]:
        """The resolved values of `attrs` on `tag`; KeyError for one it lacks."""
        return [self.resolve_args(tag.attributes[a].value, context) for a in attrs]

    def _load(self, ros_config: Any, verbose: bool, read: Callable[[LaunchLoader], None], filename: str | None,
              argv: Sequence[str]) -> None:
        config = LaunchConfig()
        launch_loader = LaunchLoader(config, loader_host(os.environ), verbose=verbose, resolve_anon=self.resolve_anon,
                                     args_only=self.args_only, ignore_unset_args=self.ignore_unset_args)
        self.root_context = loader.LoaderContext(get_ros_namespace(argv=list(argv)), filename)
        loader.load_sysargs_into_context(self.root_context, argv)
        try:
            read(launch_loader)
        except LaunchError as exc:
            raise XmlParseException(str(exc)) from exc
        if verbose:
            for line in config.messages:
                print(line)
        arg_dict = self.root_context.resolve_dict["arg"]
        for decl in launch_loader.arg_decls:
            if decl.default is not None:
                arg_dict.setdefault(decl.name, decl.default)
        self.root_context.resolve_dict["arg_doc"] = {d.name: (d.doc, d.default) for d in launch_loader.arg_decls}
        replay(config, ros_config, verbose)

    def load(self, filename: str, ros_config: Any, core: bool = False, argv: Sequence[str] | None = None,
             verbose: bool = True) -> None:
        """Read launch file `filename` (with the `name:=value` arguments of `argv`, sys.argv's by
        default) into `ros_config`."""
        args = list(sys.argv if argv is None else argv)
        self._load(ros_config, verbose, lambda launch_loader: launch_loader.load(filename, args, core=core), filename,
                   args)

    def load_string(self, xml_text: str, ros_config: Any, core: bool = False, verbose: bool = True) -> None:
        self._load(ros_config, verbose, lambda launch_loader: launch_loader.load_string(xml_text, [], core=core),
                   None, [])
