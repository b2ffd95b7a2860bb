"""catkin's files from a .cfg, written (the texts are kame.reconfigure.catkin_files'): the
ParameterGenerator .cfg files import (dynamic_reconfigure.parameter_generator_catkin), whose
generate() writes them when catkin's command runs the .cfg with its four arguments."""

from __future__ import annotations

import sys
import traceback
from collections.abc import Sequence
from pathlib import Path

from kame.reconfigure import generator
from kame.reconfigure.catkin_files import outputs
from kame.reconfigure.generator import GeneratedConfig


def write_files(generated: GeneratedConfig, share: Path, include: Path, python: Path) -> None:
    """Write catkin's five files (and cfg/__init__.py when missing) into the package's devel folders."""
    folders = {"share": share, "include": include, "python": python}
    for folder, name, text in outputs(generated):
        target = folders[folder] / name
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(text)
    (python / "cfg" / "__init__.py").touch()


def write_from_arguments(generated: GeneratedConfig, folders: Sequence[str]) -> int:
    """generate() run by catkin's command: `<cfg> <dynamic_reconfigure dir> <share> <include> <python>`."""
    share, include, python = (Path(folder) for folder in folders)
    print(f"Generating reconfiguration files for {generated.name} in {generated.package}")
    try:
        write_files(generated, share, include, python)
    except (OSError, KeyError, ValueError, TypeError):
        print(f"Error building srv {generated.name}.srv")
        traceback.print_exc()
        raise SystemExit(1) from None
    print(f"Wrote header file in {include / (generated.name + 'Config.h')}")
    return 0


class ParameterGenerator(generator.ParameterGenerator):
    """The generator .cfg files import (dynamic_reconfigure.parameter_generator_catkin): run by
    catkin's command with its four arguments, generate() writes catkin's files."""

    def write(self, generated: GeneratedConfig) -> int:
        if len(sys.argv) < 5:
            return super().write(generated)
        return write_from_arguments(generated, sys.argv[2:5])
