"""roslaunch.xmlloader: XmlLoader reads launch XML into a ROSLaunchConfig (or anything with its
add_* methods), over kame's launch loader; XmlParseException for a file it cannot read."""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import Any

from kame.cli.roslaunch import loader_host
from kame.launch.errors import LaunchError
from kame.launch.loader import LaunchLoader
from kame.launch.model import LaunchConfig
from roslaunch.config import replay
from roslaunch.core import RLException

__all__ = ["XmlLoader", "XmlParseException"]


class XmlParseException(RLException):
    """Launch XML that is malformed, or uses an argument, tag or substitution it may not."""


class XmlLoader:
    def __init__(self, resolve_anon: bool = True, args_only: bool = False) -> None:
        self.resolve_anon = resolve_anon
        self.args_only = args_only
        self.ignore_unset_args = False  # load_config_default sets it: a required arg not given is then no error

    def _load(self, ros_config: Any, verbose: bool, read: Any) -> None:
        config = LaunchConfig()
        loader = LaunchLoader(config, loader_host(os.environ), verbose=verbose, resolve_anon=self.resolve_anon,
                              args_only=self.args_only, ignore_unset_args=self.ignore_unset_args)
        try:
            read(loader)
        except LaunchError as exc:
            raise XmlParseException(str(exc)) from exc
        replay(config, ros_config, verbose)

    def load(self, filename: str, ros_config: Any, core: bool = False, argv: Sequence[str] | None = None,
             verbose: bool = True) -> None:
        """Read launch file `filename` (with `name:=value` arguments in `argv`) into `ros_config`."""
        self._load(ros_config, verbose, lambda loader: loader.load(filename, list(argv or []), core=core))

    def load_string(self, xml_text: str, ros_config: Any, core: bool = False, verbose: bool = True) -> None:
        self._load(ros_config, verbose, lambda loader: loader.load_string(xml_text, [], core=core))
