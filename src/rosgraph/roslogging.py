"""rosgraph.roslogging: Python logging into ROS's log directory, as rospy and roslaunch set it up.

configure_logging(logname) logs to `<log dir>/<logname>-<pid>.log` (or `filename` below the log
dir, whose folder becomes `latest`) with the configuration ROS_PYTHON_LOG_CONFIG_FILE names
(.conf or .yaml), else ROS's own default: the root logger at INFO into a rotating file, in
ROS's `[name][LEVEL] time: message` format.
"""

from __future__ import annotations

import logging
import logging.config
import logging.handlers
import os
import sys
from collections.abc import Mapping

from kame import param_yaml
from rospkg.environment import get_log_dir

__all__ = ["LoggingException", "configure_logging", "renew_latest_logdir"]

FORMAT = "[%(name)s][%(levelname)s] %(asctime)s: %(message)s"
ROTATE_BYTES = 50_000_000
ROTATE_COUNT = 4


class LoggingException(Exception):
    """The log file cannot be written where it should be."""


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
    try:
        os.makedirs(logfile_dir, exist_ok=True)
    except OSError:
        sys.stderr.write(f"WARNING: cannot create log directory [{logfile_dir}]. "
                         "Please set ROS_LOG_DIR to a writable location.\n")
        return None
    if logfile_dir != log_dir:
        try:
            if not renew_latest_logdir(logfile_dir):
                sys.stderr.write("INFO: cannot create a symlink to latest log directory\n")
        except OSError as exc:
            sys.stderr.write(f"INFO: cannot create a symlink to latest log directory: {exc}\n")
    os.environ["ROS_LOG_FILENAME"] = log_filename
    config_file = os.environ.get("ROS_PYTHON_LOG_CONFIG_FILE")
    if config_file and os.path.isfile(config_file):
        if config_file.endswith((".yaml", ".yml")):
            with open(config_file, encoding="utf-8") as f:
                settings = param_yaml.safe_load(f.read())
            settings.setdefault("version", 1)
            logging.config.dictConfig(settings)
        else:
            logging.config.fileConfig(config_file, disable_existing_loggers=False)
        return log_filename
    handler = logging.handlers.RotatingFileHandler(log_filename, "a", ROTATE_BYTES, ROTATE_COUNT)
    handler.setLevel(logging.DEBUG)
    handler.setFormatter(logging.Formatter(FORMAT))
    root = logging.getLogger()
    root.setLevel(logging.INFO)
    root.addHandler(handler)
    return log_filename
