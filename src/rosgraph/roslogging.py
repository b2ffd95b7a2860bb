"""rosgraph.roslogging: Python logging into ROS's log directory, as rospy and roslaunch set it up.

configure_logging(logname) logs to `<log dir>/<logname>-<pid>.log` (or `filename` below the log
dir, whose folder becomes `latest`) with the configuration ROS_PYTHON_LOG_CONFIG_FILE names,
else the first python_logging.conf (or .yaml) in ROS_HOME/config, the ROS etc folder and the
rosgraph package's conf folder, as rosgraph searches, else ROS's own python_logging.conf, built
in: the root logger at INFO into a rotating file and the `rosout` logger's records on the
console through RosStreamHandler, in ROS's `[name][LEVEL] time: message` format. Importing
the module makes RospyLogger Python's logger class, as rosgraph's does.
"""

from __future__ import annotations

import inspect
import logging
import logging.config
import logging.handlers
import os
import sys
import time
from collections.abc import Mapping
from typing import IO, Any

import rospkg
from kame import param_yaml
from rospkg.environment import ROS_LOG_DIR, get_etc_ros_dir, get_log_dir, get_ros_home

__all__ = ["ROS_LOG_DIR", "LoggingException", "RosStreamHandler", "RospyLogger", "configure_logging",
           "makedirs_with_parent_perms", "renew_latest_logdir"]

FORMAT = "[%(name)s][%(levelname)s] %(asctime)s: %(message)s"
ROTATE_BYTES = 50_000_000
ROTATE_COUNT = 4
_LEVELS = {"DEBUG": ("DEBUG", "\033[32m"), "INFO": ("INFO", None), "WARNING": ("WARN", "\033[33m"),
           "ERROR": ("ERROR", "\033[31m"), "CRITICAL": ("FATAL", "\033[31m")}
_COLOR_RESET = "\033[0m"
_DEFAULT_FORMATTER = logging.Formatter()


class LoggingException(Exception):
    """The log file cannot be written where it should be."""


class RospyLogger(logging.getLoggerClass()):  # type: ignore[misc]
    """A logger whose records name the function that called rospy's log functions (the frame
    above `_base_logger`, as rospy wraps them twice), with its class: `Talker.run`."""

    def findCaller(self, stack_info: bool = False, stacklevel: int = 1) -> tuple[str, int, str, str | None]:
        frame = inspect.currentframe()
        if frame is not None:
            frame = frame.f_back
        while frame is not None and frame.f_code.co_name != "_base_logger" and frame.f_back is not None:
            frame = frame.f_back
        if frame is not None and frame.f_back and frame.f_code.co_name == "_base_logger":
            frame = frame.f_back
            if frame.f_back:
                frame = frame.f_back
        if frame is None:
            return super().findCaller(stack_info, stacklevel)  # type: ignore[no-any-return]
        func_name = frame.f_code.co_name
        owner = frame.f_locals.get("self")
        if owner is not None:
            func_name = f"{type(owner).__name__}.{func_name}"
        return frame.f_code.co_filename, frame.f_lineno, func_name, None


logging.setLoggerClass(RospyLogger)


class RosStreamHandler(logging.Handler):
    """rospy's console lines from Python logging records: ROSCONSOLE_FORMAT's fields (severity,
    message, time, walltime, thread, logger, file, line, function, node), DEBUG and INFO to
    stdout, the rest to stderr, coloured on a terminal when `colorize`."""

    def __init__(self, colorize: bool = True, stdout: IO[str] | None = None, stderr: IO[str] | None = None) -> None:
        super().__init__()
        self._stdout = stdout or sys.stdout
        self._stderr = stderr or sys.stderr
        self._colorize = colorize

    @staticmethod
    def _ros_time(text: str) -> str:
        from kame.client import clock  # the process's ROS clock, as rospy's get_time

        if clock.is_sim_time() and clock.is_rostime_initialized():
            return f"{text}, {clock.get_time():f}"
        return text

    def emit(self, record: logging.LogRecord) -> None:
        from kame.client import core  # the process's node name, as rospy.get_name()

        level, color = _LEVELS[record.levelname]
        msg = os.environ.get("ROSCONSOLE_FORMAT", "[${severity}] [${time}]: ${message}")
        msg = msg.replace("${severity}", level).replace("${message}", str(_DEFAULT_FORMATTER.format(record)))
        msg = msg.replace("${walltime}", f"{time.time():f}")
        while "${walltime:" in msg:
            start = msg.index("${walltime:") + len("${walltime:")
            time_format = msg[start:msg.index("}", start)]
            msg = msg.replace("${walltime:" + time_format + "}", time.strftime(time_format))
        for tag, value in (("thread", record.thread), ("logger", record.name), ("file", record.pathname),
                           ("line", record.lineno), ("function", record.funcName), ("node", core.get_name())):
            msg = msg.replace("${" + tag + "}", str(value))
        msg = msg.replace("${time}", self._ros_time(f"{time.time():f}"))
        while "${time:" in msg:
            start = msg.index("${time:") + len("${time:")
            time_format = msg[start:msg.index("}", start)]
            msg = msg.replace("${time:" + time_format + "}", self._ros_time(time.strftime(time_format)))
        msg += "\n"
        self._write(self._stdout if record.levelno < logging.WARNING else self._stderr, msg, color)

    def _write(self, fd: IO[str], msg: str, color: str | None) -> None:
        if self._colorize and color and hasattr(fd, "isatty") and fd.isatty():
            msg = color + msg + _COLOR_RESET
        fd.write(msg)


def makedirs_with_parent_perms(p: str) -> None:
    """Make folder `p` and its missing parents, each with the owner and mode of its parent (a
    root process logging in a user's folder leaves it the user's)."""
    p = os.path.abspath(p)
    parent = os.path.dirname(p)
    if not os.path.exists(p) and p and parent != p:
        makedirs_with_parent_perms(parent)
        parent_stat = os.stat(parent)
        os.mkdir(p)
        made = os.stat(p)
        if (parent_stat.st_uid, parent_stat.st_gid) != (made.st_uid, made.st_gid):
            os.chown(p, parent_stat.st_uid, parent_stat.st_gid)
        if parent_stat.st_mode != made.st_mode:
            os.chmod(p, parent_stat.st_mode)


# ROS's python_logging.conf (rosgraph/conf), for when no configuration file is found
_DEFAULT_CONFIG: dict[str, Any] = {
    "version": 1,
    "disable_existing_loggers": False,
    "formatters": {"defaultFormatter": {"format": FORMAT}},
    "handlers": {
        "fileHandler": {"class": "logging.handlers.RotatingFileHandler", "level": "DEBUG",
                        "formatter": "defaultFormatter", "filename": "", "mode": "a", "maxBytes": ROTATE_BYTES,
                        "backupCount": ROTATE_COUNT},
        "streamHandler": {"()": RosStreamHandler, "level": "DEBUG", "formatter": "defaultFormatter",
                          "colorize": True},
    },
    "loggers": {"rosout": {"level": "INFO", "handlers": ["streamHandler"], "propagate": True}},
    "root": {"level": "INFO", "handlers": ["fileHandler"]},
}


def _config_file(env: Mapping[str, str]) -> str | None:
    named = os.environ.get("ROS_PYTHON_LOG_CONFIG_FILE")
    if named:
        return named
    folders = [os.path.join(get_ros_home(env), "config"), get_etc_ros_dir(env)]
    try:
        folders.append(os.path.join(rospkg.RosPack().get_path("rosgraph"), "conf"))
    except rospkg.ResourceNotFound:
        pass
    for folder in folders:
        for extension in ("conf", "yaml"):
            path = os.path.join(folder, f"python_logging.{extension}")
            if os.path.isfile(path):
                return path
    return None


def renew_latest_logdir(logfile_dir: str) -> bool:
    """Point `<log dir>/latest` at `logfile_dir`; False when something that is no link is there."""
    latest = os.path.join(os.path.dirname(logfile_dir), "latest")
    if os.path.lexists(latest):
        if not os.path.islink(latest):
            return False
        os.remove(latest)
    os.symlink(logfile_dir, latest)
    return True


def configure_logging(logname: str | None, level: int = logging.INFO, filename: str | None = None,
                      env: Mapping[str, str] | None = None) -> str | None:
    """Set up logging into the ROS log directory; the log file's path, or None when its folder
    cannot be made (said on stderr). `level` is unused, as in rosgraph: the configuration decides."""
    env = os.environ if env is None else env
    logname = logname or "unknown"
    log_dir = get_log_dir(env)
    log_filename = os.path.join(log_dir, filename or f"{logname}-{os.getpid()}.log")
    logfile_dir = os.path.dirname(log_filename)
    if os.path.isfile(logfile_dir):
        raise LoggingException(f"Cannot save log files: file [{logfile_dir}] is in the way")
    if not os.path.exists(logfile_dir):
        try:
            makedirs_with_parent_perms(logfile_dir)
        except OSError:
            if os.path.exists(logfile_dir):
                sys.stderr.write(f"WARNING: Could not change permissions for folder [{logfile_dir}], make sure "
                                 "that the parent folder has correct permissions.\n")
            else:
                sys.stderr.write(f"WARNING: cannot create log directory [{logfile_dir}]. "
                                 f"Please set {ROS_LOG_DIR} to a writable location.\n")
            return None
    if logfile_dir != log_dir:
        try:
            if not renew_latest_logdir(logfile_dir):
                sys.stderr.write("INFO: cannot create a symlink to latest log directory\n")
        except OSError as exc:
            sys.stderr.write(f"INFO: cannot create a symlink to latest log directory: {exc}\n")
    os.environ["ROS_LOG_FILENAME"] = log_filename
    config_file = _config_file(env)
    if config_file is None:
        config = dict(_DEFAULT_CONFIG, handlers=dict(_DEFAULT_CONFIG["handlers"]))
        config["handlers"]["fileHandler"] = dict(config["handlers"]["fileHandler"], filename=log_filename)
        logging.config.dictConfig(config)
    elif not os.path.isfile(config_file):
        sys.stderr.write("WARNING: cannot load logging configuration file, logging is disabled\n")
        logging.getLogger(logname).setLevel(logging.CRITICAL)
    elif config_file.endswith((".yaml", ".yml")):
        with open(config_file, encoding="utf-8") as f:
            settings = param_yaml.safe_load(f.read())
        settings.setdefault("version", 1)
        logging.config.dictConfig(settings)
    else:
        logging.config.fileConfig(config_file, disable_existing_loggers=False)
    return log_filename
