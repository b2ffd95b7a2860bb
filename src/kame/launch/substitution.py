"""Substitution args in launch attributes: $(find), $(arg), $(env), $(optenv), $(anon), $(dirname), $(eval).

Rules (roslaunch's substitution_args):
- `$(...)` groups are collected by a small state machine; a `$` or `(` inside a group is an
  error. Each group's first word is the command; unknown commands are refused by name.
- env, optenv, dirname, anon and arg are resolved first, then find (so `$(find $(arg p))` works).
- `$(eval EXPR)` must be the whole value: a Python expression over the launch's args (bare names,
  typed as <param> values are, or `arg('n')`), env/optenv/find/anon/dirname, true/false and the
  math names; builtins are limited to list, dict, map, str, float, int; `__` is refused.
  kame adds `installed('module')`: whether Python can import that module, so kame's own launch
  files choose what an optional extra brings (turtlebot_world.launch: the 3-D world with
  kame[gazebo]'s MuJoCo, else the 2-D one); it looks the module up without importing it.
- `$(anon name)` gives the same value for the same name everywhere in one launch.
Pure: the environment, the package finder and the anonymous-name maker are passed in.
"""

from __future__ import annotations

import importlib.util
import math
import os
from collections.abc import Callable, Mapping
from typing import Any

from kame.launch.errors import ArgError, LaunchError
from kame.launch.values import convert_value

VALID = ["find", "env", "optenv", "dirname", "anon", "arg"]
_FIRST = ("env", "optenv", "dirname", "anon", "arg")
_SAFE_BUILTINS = {"list": list, "dict": dict, "map": map, "str": str, "float": float, "int": int}


def collect(text: str) -> list[str]:
    """The contents of each `$(...)` group in `text`, in order."""
    out: list[str] = []
    buff: list[str] = []
    state = "out"
    for c in text:
        if c == "$":
            if state in ("lp", "in"):
                raise LaunchError(f"Dollar signs '$' cannot be inside of substitution args [{text}]")
            state = "dollar"
        elif c == "(":
            if state == "dollar":
                state = "lp"
            elif state != "out":
                raise LaunchError(f"Invalid left parenthesis '(' in substitution args [{text}]")
        elif c == ")":
            if state == "in":
                out.append("".join(buff))
                buff.clear()
            state = "out"
        elif state == "dollar":
            state = "out"
        elif state == "lp":
            state = "in"
        if state == "in":
            buff.append(c)
    return out


class Substituter:
    """Resolves substitution args for one launch (one table of anonymous names)."""

    def __init__(self, env: Mapping[str, str], find_package: Callable[[str], str],
                 make_anon: Callable[[str], str], resolve_anon: bool = True) -> None:
        self.env = env
        self.find_package = find_package
        self.make_anon = make_anon
        self.resolve_anon = resolve_anon
        self.anons: dict[str, str] = {}

    def resolve(self, text: str, args: Mapping[str, str], filename: str | None) -> str:
        if "$" not in text:
            return text
        if text.startswith("$(eval ") and text.endswith(")"):
            return self.evaluate(text[7:-1], args, filename)
        resolved = self._pass(text, args, filename, _FIRST)
        return self._pass(resolved, args, filename, ("find",))

    def _pass(self, text: str, args: Mapping[str, str], filename: str | None, commands: tuple[str, ...]) -> str:
        resolved = text
        for group in collect(text):
            words = [w for w in group.split(" ") if w]
            if not words or words[0] not in VALID:
                raise LaunchError(f"Unknown substitution command [{group}]. Valid commands are {VALID}")
            command, params = words[0], words[1:]
            if command not in commands:
                continue
            if command == "anon" and not self.resolve_anon:
                continue
            value = self._command(command, params, group, args, filename)
            resolved = resolved.replace(f"$({group})", value)
        return resolved

    def _command(self, command: str, params: list[str], group: str, args: Mapping[str, str],
                 filename: str | None) -> str:
        if command == "env":
            if len(params) != 1:
                raise LaunchError(f"$(env var) command only accepts one argument [{group}]")
            return self.env_value(params[0])
        if command == "optenv":
            if not params:
                raise LaunchError(f"$(optenv var) must specify an environment variable [{group}]")
            return self.env.get(params[0], " ".join(params[1:]))
        if command == "dirname":
            return self.dirname(filename)
        if command == "anon":
            if len(params) != 1:
                many = "may only specify one name" if params else "must specify a name"
                raise LaunchError(f"$(anon var) {many} [{group}]")
            return self.anon(params[0])
        if command == "arg":
            if len(params) != 1:
                many = "may only specify one arg" if params else "must specify a variable name"
                raise LaunchError(f"$(arg var) {many} [{group}]")
            return arg_value(params[0], args)
        if len(params) != 1:
            raise LaunchError(f"$(find pkg) command only accepts one argument [{group}]")
        return self.find_package(params[0])

    def env_value(self, name: str) -> str:
        try:
            return self.env[name]
        except KeyError:
            raise LaunchError(f"environment variable '{name}' is not set") from None

    def anon(self, name: str) -> str:
        if name not in self.anons:
            self.anons[name] = self.make_anon(name)
        return self.anons[name]

    @staticmethod
    def dirname(filename: str | None) -> str:
        if not filename:
            raise LaunchError("Cannot substitute $(dirname), no file/directory information available.")
        return os.path.abspath(os.path.dirname(filename))

    def evaluate(self, expression: str, args: Mapping[str, str], filename: str | None) -> str:
        if "__" in expression:
            raise LaunchError("$(eval ...) may not contain double underscore expressions")
        functions: dict[str, Any] = {
            "true": True, "false": False, "True": True, "False": False,
            "env": self.env_value,
            "optenv": lambda name, default="": self.env.get(name, default),
            "find": self.find_package,
            "anon": self.anon,
            "arg": lambda name: convert_value(arg_value(name, args), "auto"),
            "dirname": lambda: self.dirname(filename),
            "installed": installed,
        }
        functions.update({k: v for k, v in vars(math).items() if not k.startswith("_")})
        scope = _Scope(args, functions)
        try:
            return str(eval(expression, {"__builtins__": _SAFE_BUILTINS}, scope))  # as roslaunch does
        except LaunchError:
            raise
        except Exception as exc:
            raise LaunchError(f"$(eval {expression}) failed: {type(exc).__name__}: {exc}") from exc


def installed(module: str) -> bool:
    """Whether Python finds the module (without importing it)."""
    try:
        return importlib.util.find_spec(str(module)) is not None
    except (ImportError, ValueError):  # a parent package that fails, or a blocked import
        return False


def arg_value(name: str, args: Mapping[str, str]) -> str:
    try:
        return args[name]
    except KeyError:
        raise ArgError(name) from None


class _Scope(dict[str, Any]):
    """eval's locals: the functions first, then each arg typed as a <param> value would be."""

    def __init__(self, args: Mapping[str, str], functions: dict[str, Any]) -> None:
        super().__init__()
        self._args = args
        self._functions = functions

    def __missing__(self, key: str) -> Any:
        if key in self._functions:
            return self._functions[key]
        if key in self._args:
            return convert_value(self._args[key], "auto")
        raise KeyError(key)
