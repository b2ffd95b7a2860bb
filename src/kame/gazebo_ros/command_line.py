"""gzserver's command line, as Gazebo 11 reads it (boost program_options), without I/O.

    gzserver [-u|--pause] [-r|--record] [--verbose] [-e|--physics ENGINE] [-s|--server-plugin LIB]...
             [--seed N] [--iters N] [--lockstep] [-o|--profile NAME] [world_file]

Options kame's server cannot honour are kept and reported by the caller (one line each), never
silently dropped: recording, another physics engine than MuJoCo's, profiles, server plugins other
than gazebo_ros's own.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

USAGE = ("Usage: gzserver [options] <world_file>\n"
         "  -u [ --pause ]            Start the server in a paused state.\n"
         "  -e [ --physics ] arg      Specify a physics engine (ode|bullet|dart|simbody): kame steps MuJoCo.\n"
         "  -r [ --record ]           Record state data (not available in kame).\n"
         "  -s [ --server-plugin ] arg  Load a plugin.\n"
         "  --seed arg                Start with a given random number seed.\n"
         "  --iters arg               Number of iterations to simulate.\n"
         "  --lockstep                Lockstep simulation so sensor update rates are respected.\n"
         "  -o [ --profile ] arg      Physics preset profile name from the options in the world file.\n"
         "  --verbose                 Increase the messages written to the terminal.\n"
         "  -h [ --help ]             Produce this help message.")

DEFAULT_WORLD = "worlds/empty.world"
# the server plugins gazebo_ros's scripts load: kame's server is both of them
ROS_SERVER_PLUGINS = ("libgazebo_ros_api_plugin.so", "libgazebo_ros_paths_plugin.so")


class CommandLineError(ValueError):
    """A gzserver command line that cannot be run; the message is what to print."""


@dataclass(frozen=True)
class ServerOptions:
    world: str = DEFAULT_WORLD
    paused: bool = False
    record: bool = False
    verbose: bool = False
    physics: str = "ode"
    server_plugins: tuple[str, ...] = ()
    seed: int | None = None
    iterations: int | None = None
    profile: str | None = None
    lockstep: bool = False
    help: bool = False
    ignored: tuple[str, ...] = field(default=())  # extra positional arguments after the world

    def foreign_plugins(self) -> list[str]:
        return [p for p in self.server_plugins if p not in ROS_SERVER_PLUGINS]


_FLAGS = {"-u": "paused", "--pause": "paused", "-r": "record", "--record": "record", "--verbose": "verbose",
          "--lockstep": "lockstep", "-h": "help", "--help": "help"}
_VALUED = {"-e": "physics", "--physics": "physics", "-s": "server_plugins", "--server-plugin": "server_plugins",
           "--seed": "seed", "--iters": "iterations", "-o": "profile", "--profile": "profile"}


def _whole(option: str, text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise CommandLineError(f"Error. the argument ('{text}') for option '{option}' is invalid") from None


def parse(args: Sequence[str]) -> ServerOptions:
    """The options of a gzserver command line (remappings already taken out)."""
    values: dict[str, object] = {}
    plugins: list[str] = []
    positional: list[str] = []
    items = [a for a in args if a != ""]  # roslaunch passes the empty command_argN of empty_world.launch
    i = 0
    while i < len(items):
        arg = items[i]
        name, _, inline = arg.partition("=") if arg.startswith("--") else (arg, "", "")
        if name in _FLAGS:
            values[_FLAGS[name]] = True
        elif name in _VALUED:
            if inline:
                value = inline
            elif i + 1 < len(items):
                i += 1
                value = items[i]
            else:
                raise CommandLineError(f"Error. the required argument for option '{name}' is missing")
            key = _VALUED[name]
            if key == "server_plugins":
                plugins.append(value)
            elif key in ("seed", "iterations"):
                values[key] = _whole(name, value)
            else:
                values[key] = value
        elif arg.startswith("-") and len(arg) > 1:
            raise CommandLineError(f"Error. unrecognised option '{arg}'\n{USAGE}")
        else:
            positional.append(arg)
        i += 1
    iterations = values.get("iterations")
    seed = values.get("seed")
    if isinstance(iterations, int) and iterations < 0:
        raise CommandLineError("Error. --iters must be a number of iterations, 0 or more")
    return ServerOptions(
        world=positional[0] if positional else DEFAULT_WORLD,
        paused=bool(values.get("paused", False)), record=bool(values.get("record", False)),
        verbose=bool(values.get("verbose", False)), physics=str(values.get("physics", "ode")),
        server_plugins=tuple(plugins), seed=seed if isinstance(seed, int) else None,
        iterations=iterations if isinstance(iterations, int) else None,
        profile=str(values["profile"]) if "profile" in values else None,
        lockstep=bool(values.get("lockstep", False)), help=bool(values.get("help", False)),
        ignored=tuple(positional[1:]))
