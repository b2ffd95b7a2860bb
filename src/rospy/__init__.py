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
    get_ros_root,
    is_shutdown,
    logdebug,
    logdebug_once,
    logdebug_throttle,
    logdebug_throttle_identical,
    logerr,
    logerr_once,
    logerr_throttle,
    logerr_throttle_identical,
    logerror,
    logfatal,
    logfatal_once,
    logfatal_throttle,
    logfatal_throttle_identical,
    loginfo,
    loginfo_once,
    loginfo_throttle,
    loginfo_throttle_identical,
    logout,
    logwarn,
    logwarn_once,
    logwarn_throttle,
    logwarn_throttle_identical,
    on_shutdown,
    parse_rosrpc_uri,
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
    TransportException,
    TransportInitError,
    TransportTerminated,
)
from rospy.impl import tcpros_service as _impl_tcpros_service  # noqa: F401  (loaded by rospy's too)
from rospy.msg import AnyMsg
from rospy.msproxy import MasterProxy
from rospy.numpy_msg import numpy_msg
from rospy.rostime import Duration, Time, get_rostime, get_time
from rospy.service import Service, ServiceException, ServiceProxy, wait_for_service
from rospy.timer import Rate, Timer, TimerEvent, sleep
from rospy.topics import Publisher, SubscribeListener, Subscriber
from std_msgs.msg import Header

DEBUG = _log.DEBUG
INFO = _log.INFO
WARN = _log.WARN
ERROR = _log.ERROR
FATAL = _log.FATAL


_process.rospy_ctrl_c()  # a program that imports rospy takes Ctrl-C as rospy does: no exception, a shutdown

__all__ = [
    "DEBUG", "ERROR", "FATAL", "INFO", "WARN", "AnyMsg", "Duration", "Header", "MasterProxy", "Message", "Publisher",
    "ROSException", "ROSInitException", "ROSInternalException", "ROSInterruptException", "ROSSerializationException",
    "ROSTimeMovedBackwardsException", "Rate", "Service", "ServiceException", "ServiceProxy", "SubscribeListener",
    "Subscriber", "Time", "Timer", "TimerEvent", "TransportException", "TransportInitError", "TransportTerminated",
    "delete_param", "get_caller_id", "get_master", "get_name", "get_namespace", "get_node_uri", "get_param",
    "get_param_cached", "get_param_names", "get_published_topics", "get_ros_root", "get_rostime", "get_time",
    "has_param", "init_node", "is_shutdown", "logdebug", "logdebug_once", "logdebug_throttle",
    "logdebug_throttle_identical", "logerr", "logerr_once", "logerr_throttle", "logerr_throttle_identical",
    "logerror", "logfatal", "logfatal_once", "logfatal_throttle", "logfatal_throttle_identical", "loginfo",
    "loginfo_once", "loginfo_throttle", "loginfo_throttle_identical", "logout", "logwarn", "logwarn_once",
    "logwarn_throttle", "logwarn_throttle_identical", "myargv", "numpy_msg", "on_shutdown", "parse_rosrpc_uri",
    "remap_name", "resolve_name", "search_param", "set_param", "signal_shutdown", "sleep", "spin", "wait_for_message",
    "wait_for_service",
]
