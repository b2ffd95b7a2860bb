"""rospy, the ROS 1 Python client API, on kame's runtime.

Programs written for rospy run unchanged: `import rospy`, `rospy.init_node(...)`,
Publisher/Subscriber, Service/ServiceProxy, parameters, time, logging.
"""

from kame.client import log as _log
from kame.client import process as _process
from kame.msg.message import Message
from rospy.client import (
    delete_param,
    get_master,
    get_param,
    get_param_cached,
    get_param_names,
    get_published_topics,
    has_param,
    init_node,
    myargv,
    search_param,
    set_param,
    spin,
    wait_for_message,
)
from rospy.core import (
    get_caller_id,
    get_name,
    get_namespace,
    get_node_uri,
    is_shutdown,
    on_shutdown,
    remap_name,
    resolve_name,
    signal_shutdown,
)
from rospy.exceptions import (
    ROSException,
    ROSInitException,
    ROSInternalException,
    ROSInterruptException,
    ROSSerializationException,
    ROSTimeMovedBackwardsException,
)
from rospy.msg import AnyMsg
from rospy.numpy_msg import numpy_msg
from rospy.rostime import Duration, Time, get_rostime, get_time
from rospy.service import Service, ServiceException, ServiceProxy, wait_for_service
from rospy.timer import Rate, Timer, TimerEvent, sleep
from rospy.topics import Publisher, SubscribeListener, Subscriber

DEBUG = _log.DEBUG
INFO = _log.INFO
WARN = _log.WARN
ERROR = _log.ERROR
FATAL = _log.FATAL


def logdebug(msg, *args, **kwargs):
    _log.emit(DEBUG, msg, args)


def loginfo(msg, *args, **kwargs):
    _log.emit(INFO, msg, args)


def logwarn(msg, *args, **kwargs):
    _log.emit(WARN, msg, args)


def logerr(msg, *args, **kwargs):
    _log.emit(ERROR, msg, args)


def logfatal(msg, *args, **kwargs):
    _log.emit(FATAL, msg, args)


logout = loginfo
logerror = logerr


def logdebug_once(msg, *args, **kwargs):
    _log.emit_once(DEBUG, msg, args)


def loginfo_once(msg, *args, **kwargs):
    _log.emit_once(INFO, msg, args)


def logwarn_once(msg, *args, **kwargs):
    _log.emit_once(WARN, msg, args)


def logerr_once(msg, *args, **kwargs):
    _log.emit_once(ERROR, msg, args)


def logfatal_once(msg, *args, **kwargs):
    _log.emit_once(FATAL, msg, args)


def logdebug_throttle(period, msg, *args, **kwargs):
    _log.emit_throttle(period, DEBUG, msg, args)


def loginfo_throttle(period, msg, *args, **kwargs):
    _log.emit_throttle(period, INFO, msg, args)


def logwarn_throttle(period, msg, *args, **kwargs):
    _log.emit_throttle(period, WARN, msg, args)


def logerr_throttle(period, msg, *args, **kwargs):
    _log.emit_throttle(period, ERROR, msg, args)


def logfatal_throttle(period, msg, *args, **kwargs):
    _log.emit_throttle(period, FATAL, msg, args)


def logdebug_throttle_identical(period, msg, *args, **kwargs):
    _log.emit_throttle_identical(period, DEBUG, msg, args)


def loginfo_throttle_identical(period, msg, *args, **kwargs):
    _log.emit_throttle_identical(period, INFO, msg, args)


def logwarn_throttle_identical(period, msg, *args, **kwargs):
    _log.emit_throttle_identical(period, WARN, msg, args)


def logerr_throttle_identical(period, msg, *args, **kwargs):
    _log.emit_throttle_identical(period, ERROR, msg, args)


def logfatal_throttle_identical(period, msg, *args, **kwargs):
    _log.emit_throttle_identical(period, FATAL, msg, args)


_process.rospy_ctrl_c()  # a program that imports rospy takes Ctrl-C as rospy does: no exception, a shutdown

__all__ = [
    "DEBUG", "ERROR", "FATAL", "INFO", "WARN",
    "AnyMsg", "Duration", "Message", "Publisher", "ROSException", "ROSInitException", "ROSInternalException",
    "ROSInterruptException", "ROSSerializationException", "ROSTimeMovedBackwardsException", "Rate", "Service",
    "ServiceException", "ServiceProxy", "SubscribeListener", "Subscriber", "Time", "Timer", "TimerEvent",
    "delete_param", "get_caller_id", "get_master", "get_name", "get_namespace", "get_node_uri", "get_param",
    "get_param_cached", "get_param_names", "get_published_topics", "get_rostime", "get_time", "has_param",
    "init_node", "is_shutdown", "logdebug", "logdebug_once", "logdebug_throttle", "logdebug_throttle_identical",
    "logerr", "logerr_once", "logerr_throttle", "logerr_throttle_identical", "logerror", "logfatal",
    "logfatal_once", "logfatal_throttle", "logfatal_throttle_identical", "loginfo", "loginfo_once",
    "loginfo_throttle", "loginfo_throttle_identical", "logout", "logwarn", "logwarn_once", "logwarn_throttle",
    "logwarn_throttle_identical", "myargv", "numpy_msg", "on_shutdown", "remap_name", "resolve_name", "search_param",
    "set_param", "signal_shutdown", "sleep", "spin", "wait_for_message", "wait_for_service",
]
