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
print(json.dumps(out))
rospy.signal_shutdown("done")
