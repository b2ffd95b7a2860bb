"""roslaunch.param_dump: `roslaunch --dump-params`: the parameters of launch files as YAML."""

from __future__ import annotations

import sys
from collections.abc import Sequence

import yaml

__all__ = ["dump_params"]


def dump_params(files: Sequence[str]) -> bool:
    """Print the files' parameters as YAML: False (and why, on stderr) when one cannot be loaded."""
    from roslaunch.config import ROSLaunchConfig
    from roslaunch.xmlloader import XmlLoader

    config = ROSLaunchConfig()
    loader = XmlLoader()
    for f in files:
        try:
            loader.load(f, config, verbose=False)
        except Exception as exc:  # as ROS: any failure to read a file is reported, not raised
            sys.stderr.write(f"Unable to load file {f}: {exc}")
            return False
    params = {str(k): v.value for k, v in config.params.items()}
    sys.stdout.write(yaml.safe_dump(params) + "\n")
    return True
