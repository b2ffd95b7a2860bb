"""rospy's internals on a live node (the master at ROS_MASTER_URI): registration listeners hearing
the node, MasterProxy, the parameter cache, TCPROSTransport subscribing and calling a service
directly and through a TCPROSServer started by init_tcpros, RegManager telling the master. Run by
kame's interpreter and Debian's; prints one JSON answer."""

import json
import os
import threading

import rospy
import rospy.core
import rospy.impl.registration as registration
import rospy.impl.tcpros as tcpros
import rospy.impl.tcpros_base as tcpros_base
import rospy.impl.tcpros_service as tcpros_service
from rospy.impl.paramserver import get_param_server_cache
from rospy.impl.tcpros_pubsub import TCPROSSub
from std_msgs.msg import String
from std_srvs.srv import SetBool, SetBoolRequest, SetBoolResponse

out = {}
events = []
heard_service = threading.Event()


class Recorder(registration.RegistrationListener):
    def reg_added(self, name, type_or_uri, kind):
        if name != "/rosout" and not name.endswith(("/get_loggers", "/set_logger_level")):
            events.append(["added", name, type_or_uri.split(":")[0], kind])
            if kind == "srv":
                heard_service.set()

    def reg_removed(self, name, type_or_uri, kind):
        events.append(["removed", name, type_or_uri.split(":")[0], kind])


rospy.init_node("modules_live")
registration.get_registration_listeners().add_listener(Recorder())
pub = rospy.Publisher("/latched", String, queue_size=1, latch=True)
pub.publish(String(data="kept"))
sub = rospy.Subscriber("/heard", String, lambda m: None)


def answer(req):
    if not req.data:
        raise rospy.ServiceException("asked for false")
    return SetBoolResponse(True, "yes")


srv = rospy.Service("/switch", SetBool, answer)
heard_service.wait(10)
sub.unregister()
out["events"] = list(events)

master = rospy.MasterProxy(os.environ["ROS_MASTER_URI"])
code, _, pid = master.getPid()
out["get_master"] = [isinstance(rospy.get_master(), rospy.MasterProxy), rospy.get_master() is rospy.get_master(),
                     rospy.get_master().getPid()[2] == pid, "/nothing" in rospy.get_master()]
master["/live/p"] = {"a": 1}
out["master_proxy"] = [code, isinstance(pid, int), master["/live/p"], master["live/p/a"], "/live/p" in master,
                       "/live/none" in master, master.search_param("p"), "/live/p/a" in list(master)]
del master["/live/p"]
try:
    master["/live/p"]
except KeyError as exc:
    out["master_proxy"].append(["KeyError", str(exc)])
try:
    del master["/live/p"]
except KeyError as exc:
    out["master_proxy"].append(["KeyError", str(exc)])
code, _, publishers = master.lookupService("switch")
out["master_proxy"].append(code)

rospy.set_param("/cached", 5)
cache = get_param_server_cache()
out["cache"] = [rospy.get_param_cached("/cached")]
try:
    out["cache"].append(cache.get("/cached"))
except KeyError:
    out["cache"].append("KeyError")
cache.set("/only_cached", 7)
out["cache"].append(rospy.get_param_cached("/only_cached"))
cache.update("/only_cached", 8)
out["cache"].append(rospy.get_param_cached("/only_cached"))
cache.delete("/only_cached")
out["cache"].append(rospy.has_param("/only_cached"))


def subscribe(host, port):
    link = tcpros_base.TCPROSTransport(TCPROSSub("/latched", String), "/latched")
    link.connect(host, port, "/modules_live")
    got = [m.data for m in link.receive_once()]
    info = [link.is_latched, link.type, link.md5sum, link.callerid_pub, link.stat_num_msg,
            link.local_endpoint[1] > 0, got]
    link.close()
    return [*info, link.done]


def call(host, port, data):
    link = tcpros_base.TCPROSTransport(tcpros_service.TCPROSServiceClient("/switch", SetBool), "/switch")
    link.connect(host, port, "/modules_live")
    link.send_message(SetBoolRequest(data), 0)
    try:
        return [str(m) for m in link.receive_once()]
    except rospy.ServiceException as exc:
        return ["ServiceException", str(exc)]
    finally:
        link.close()


host, port = tcpros_base.get_tcpros_server_address()
service_host, service_port = rospy.core.parse_rosrpc_uri(master.lookupService("/switch")[2])
out["direct"] = [subscribe(host, port), call(service_host, service_port, True), call(service_host, service_port, False)]
try:
    tcpros_base.TCPROSTransport(TCPROSSub("/nothing", String), "/nothing").connect(host, port, "/x")
except rospy.TransportInitError as exc:
    out["direct"].append(str(exc).split(". Topics are")[0])

tcpros.init_tcpros(0)
tcpros_base.start_tcpros_server()
server_host, server_port = tcpros_base.get_tcpros_server_address()
out["served"] = [subscribe(server_host, server_port), call(server_host, server_port, True)]

manager = registration.RegManager(None)
manager.master_uri = os.environ["ROS_MASTER_URI"]
manager.uri = rospy.get_node_uri()
manager.reg_added("/told", "std_msgs/Empty", registration.Registration.PUB)
publishers = dict(master.getSystemState()[2][0])
out["reg_manager"] = [publishers.get("/told"), dict(master.getTopicTypes()[2]).get("/told")]
manager.reg_removed("/told", "std_msgs/Empty", registration.Registration.PUB)
out["reg_manager"].append(dict(master.getSystemState()[2][0]).get("/told"))
# topic statistics, measured and published on /statistics
from rosgraph_msgs.msg import TopicStatistics  # noqa: E402
from rospy.impl.statistics import SubscriberStatisticsLogger  # noqa: E402

statistics, got_statistics = [], threading.Event()


def heard_statistics(msg):
    # what depends on timing (traffic in the window, deliveries, periods) is checked for its range
    statistics.append([msg.topic, msg.node_sub, msg.node_pub, msg.traffic in (0, 100), msg.delivered_msgs > 0,
                       msg.dropped_msgs, msg.window_stop >= msg.window_start, msg.period_mean.to_sec() >= 0])
    got_statistics.set()


rospy.Subscriber("/statistics", TopicStatistics, heard_statistics)


class Named:
    name = "/measured"


rospy.set_param("/enable_statistics", False)
measuring = SubscriberStatisticsLogger(Named())
out["statistics"] = [SubscriberStatisticsLogger.is_enabled(), measuring.min_elements, measuring.max_window]
rospy.set_param("/enable_statistics", True)
out["statistics"].append(SubscriberStatisticsLogger.is_enabled())
while not got_statistics.wait(0.2):  # until /statistics reaches our own subscriber
    measuring.callback(String(data="m"), "/somebody", 100)
out["statistics"].append(statistics[0])
measuring.shutdown()
out["statistics"].append(measuring.connections)

# publishers asked, connections kept up, the node's logger services
import subprocess  # noqa: E402
import sys  # noqa: E402

from rospy.impl import init, rosout, simtime  # noqa: E402
from rospy.impl.tcpros_pubsub import check_if_still_publisher, robust_connect_subscriber  # noqa: E402
from rospy.logger_level_service_caller import LoggerLevelServiceCaller, ROSConsoleException  # noqa: E402

me = rospy.get_node_uri()
out["still_publisher"] = [check_if_still_publisher("/latched", me), check_if_still_publisher("/nothing", me),
                          check_if_still_publisher("/latched", "http://127.0.0.1:1/")]
received = []
link = tcpros_base.TCPROSTransport(TCPROSSub("/latched", String), "/latched")


def keep(msgs, connection):
    received.extend(m.data for m in msgs)
    connection.close()


robust_connect_subscriber(link, host, port, me, keep, "/latched")
out["robust"] = [received, link.done]
caller = LoggerLevelServiceCaller()
loggers = caller.get_loggers("/modules_live")
out["loggers"] = ["/modules_live" in caller.get_node_names(), "rosout" in loggers, caller.get_levels()]
try:
    caller.get_loggers("/no_such_node")
except ROSConsoleException as exc:
    out["loggers"].append(str(exc).split(":")[0])
console = subprocess.run([sys.executable, "-c", "import rospy.rosconsole as c; c.main()", "list", "/modules_live"],
                         capture_output=True, text=True, timeout=60)
out["rosconsole"] = [console.returncode, "rosout" in console.stdout.split()]
out["init"] = [rosout.init_rosout() is not False, simtime.init_simtime(), init.DEFAULT_MASTER_URI,
               init.DEFAULT_NODE_PORT]
# a service that rospy code registers with the process's ServiceManager reaches the master
import rospy.service  # noqa: E402

manual = rospy.service._Service("/manual", SetBool)
manual.uri = master.lookupService("/switch")[2]
services = registration.get_service_manager()
services.register("/manual", manual)
out["service_manager"] = [master.lookupService("/manual")[0], ["/manual", manual.uri] in
                          [list(pair) for pair in services.get_services()], services.get_service("/manual") is manual]
try:
    services.register("/switch", manual)
except rospy.ServiceException as exc:
    out["service_manager"].append(str(exc))
services.unregister("/manual", manual)
out["service_manager"] += [master.lookupService("/manual")[0], services.get_service("/manual"),
                           isinstance(srv, rospy.service._Service), srv.uri == master.lookupService("/switch")[2]]
# the TCPROS handler connects a subscription to one more publisher (kame's only: rospy's own
# subscription here is connected already, so its answer depends on its threads' timing)
heard_again, heard_event = [], threading.Event()
rospy.Subscriber("/latched", String, lambda m: (heard_again.append(m.data), heard_event.set()))
heard_event.wait(10)
created = tcpros.get_tcpros_handler().create_transport("/latched", me, ["TCPROS", host, port])
out["create_transport"] = [created[0], created[2] == port, heard_again[:1]]

# last: rospy's start_node registers the process's topics and services again for its node, which
# the master then shuts down (a node of the same name registered), unregistering them all
other = init.start_node(os.environ, "/ns/started")
code, _, started = rospy.core.xmlrpcapi(other.uri).getName("/modules_live")
out["start_node"] = [code, started]
other.shutdown("done")
print(json.dumps(out))
rospy.signal_shutdown("done")
