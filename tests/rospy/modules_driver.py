"""rospy's module-level names on fixed inputs, no master: run by kame's interpreter and Debian's,
printing one JSON answer for tests/rospy/test_rospy_modules.py to compare."""

import io
import json
import socket
import sys
import threading

sys.argv = ["prog", "chatter:=/talk", "~p:=q", "__ns:=/n", "_x:=1"]

import rospy  # noqa: E402
import rospy.core as core  # noqa: E402
import rospy.impl.registration as registration  # noqa: E402
import rospy.impl.tcpros as tcpros  # noqa: E402
import rospy.impl.tcpros_base as tcpros_base  # noqa: E402
import rospy.impl.tcpros_service as tcpros_service  # noqa: E402
import rospy.impl.transport as transport  # noqa: E402
import rospy.msg  # noqa: E402
import rospy.names as names  # noqa: E402
import rospy.service  # noqa: E402
from rospy.impl.paramserver import ParamServerCache  # noqa: E402
from std_msgs.msg import String  # noqa: E402
from std_srvs.srv import SetBool, SetBoolResponse  # noqa: E402

out = {}


def attempt(call):
    try:
        return ["ok", call()]
    except Exception as exc:
        return [type(exc).__name__, str(exc)]


# logging to a file, Header and the log calls where rospy has them
import os  # noqa: E402
import tempfile  # noqa: E402

os.environ["ROS_LOG_DIR"] = tempfile.mkdtemp()
core.configure_logging("/ns/node")
out["configure_logging"] = [os.path.basename(core._log_filename), os.path.dirname(core._log_filename) ==
                            os.environ["ROS_LOG_DIR"], attempt(lambda: core.configure_logging("/"))]
from std_msgs.msg import Header  # noqa: E402

out["top_level"] = [rospy.Header is Header, rospy.MasterProxy.__module__, rospy.loginfo is core.loginfo,
                    rospy.logerr_throttle is core.logerr_throttle, rospy.get_ros_root is core.get_ros_root,
                    core.xmlrpcapi("http://127.0.0.1:1/").__class__.__name__ != ""]

out["rosrpc"] = [attempt(lambda u=u: list(rospy.parse_rosrpc_uri(u))) for u in (
    "rosrpc://host:1234", "rosrpc://host:1234/path", "http://host:1", "rosrpc://host", "rosrpc://host:port",
    "rosrpc://a:1:2")]
out["same_parse"] = rospy.parse_rosrpc_uri is core.parse_rosrpc_uri
out["anytype"] = [names.TOPIC_ANYTYPE, names.SERVICE_ANYTYPE, names.isstring("a"), names.isstring(b"a")]
out["validators"] = [attempt(lambda v=v, f=f: f("p", v, "/ns/node")) for v in ("rel", "~priv", "/g", "", "a b", 3)
                     for f in (names.valid_name_validator_resolved, names.valid_name_validator_unresolved)]
out["is_topic"] = [attempt(lambda v=v: core.is_topic("t")(v, "/ns/node")) for v in ("chat", "/", "", "a:b")]
out["valid_name"] = [attempt(lambda v=v: core.valid_name("n")(v, "/ns/node")) for v in ("x", "")]
out["mappings"] = [names.get_mappings()]
out["without_node"] = [attempt(lambda v=v: names.resolve_name_without_node_name(v)) for v in ("chatter", "other", "~p")]
names.reload_mappings(["prog", "a:=b", "~c:=d", "__log:=/tmp/x.log"])
out["mappings"].append(names.get_mappings())
names.initialize_mappings("/ns/node")
out["resolved"] = [names.get_resolved_mappings(), names.resolve_name("a", "/ns/node"),
                   names.resolve_name("~c", "/ns/node")]
out["ros_root"] = [attempt(lambda: core.get_ros_root(env={"ROS_ROOT": "/opt/x"})),
                   attempt(lambda: core.get_ros_root(env={})),
                   attempt(lambda: core.get_ros_root(required=True, env={}))]
out["node_uri"] = [core.get_node_uri()]
core.set_node_uri("http://here:1/")
out["node_uri"] += [core.get_node_uri(), rospy.get_node_uri()]
out["initialized"] = [core.is_initialized()]
core.set_initialized(True)
out["initialized"].append(core.is_initialized())
core.set_initialized(False)
out["xmlrpcapi"] = [core.xmlrpcapi(None) is None, core.xmlrpcapi("nothing") is None,
                    core.xmlrpcapi("http://127.0.0.1:1/") is core.xmlrpcapi("http://127.0.0.1:1/"),
                    core.xmlrpcapi("http://127.0.0.1:1/", cache=False) is core.xmlrpcapi("http://127.0.0.1:1/")]
out["consts"] = [core.MASTER_NAME, core.ROSRPC]
out["bad_hook"] = attempt(lambda: core.add_shutdown_hook("not callable"))

# rospy's message frames
buff = io.BytesIO()
rospy.msg.serialize_message(buff, 7, String(data="hi"))
out["frames"] = [buff.getvalue().hex()]
buff2 = io.BytesIO()
from geometry_msgs.msg import PointStamped  # noqa: E402

stamped = PointStamped()
stamped.header.frame_id = "m"
rospy.msg.serialize_message(buff2, 42, stamped)
out["frames"] += [buff2.getvalue().hex(), stamped.header.seq]
queue = []
stream = io.BytesIO()
stream.write(buff.getvalue() * 3 + buff.getvalue()[:5])
rospy.msg.deserialize_messages(stream, queue, String, queue_size=2)
out["deserialized"] = [[m.data for m in queue], stream.getvalue().hex(), stream.tell()]
queue = []
stream = io.BytesIO()
stream.write(buff.getvalue() * 3)
rospy.msg.deserialize_messages(stream, queue, String, max_msgs=1)
out["deserialized"] += [[m.data for m in queue], stream.getvalue().hex(), stream.tell()]
bad = io.BytesIO()
bad.write(b"\x02\x00\x00\x00\x09\x00")
out["bad_frame"] = attempt(lambda: rospy.msg.deserialize_messages(bad, [], String))[0]

# the parameter cache
cache = ParamServerCache()
steps = [lambda: cache.get("/a"), lambda: cache.update("/a", 1), lambda: cache.delete("/a"),
         lambda: cache.set("/a/b", 1), lambda: cache.get("/a"), lambda: cache.get("/a/b"),
         lambda: cache.update("/a/b", 2),
         lambda: cache.get("/a/b"), lambda: cache.update("/a/c", 3), lambda: cache.set("/a", {"x": {}}),
         lambda: cache.get("/a/x"), lambda: cache.delete("/a/x"), lambda: cache.get("/a"),
         lambda: cache.delete("/"), lambda: cache.set("/", 5), lambda: cache.set("/", {"r": 1}), lambda: cache.get("/"),
         lambda: cache.delete("/r/s")]
notified = []
cache.set_notifier(lambda k, v: notified.append([k, v]))
out["cache"] = [attempt(step) for step in steps] + [notified]

# transports
t1 = transport.Transport(transport.INBOUND, "chat")
t2 = transport.Transport(transport.OUTBOUND)
t1.stat_bytes, t1.stat_num_msg, t1.endpoint_id = 10, 2, "/peer"
t1.local_endpoint, t1.remote_endpoint = ("1.2.3.4", 5), ("6.7.8.9", 10)
closed = []
t1.set_cleanup_callback(lambda t: closed.append(t.name))
dead = transport.DeadTransport(t1)
t1.close()
out["transport"] = [t2.id - t1.id, t1.done, closed, t1.fileno(), t1.transport_type, dead.get_transport_info(),
                    dead.id == t1.id, dead.done, dead.stat_bytes, dead.direction, dead.name,
                    attempt(lambda: t2.write_data(b"x"))[0] != "ok"]
handler = transport.ProtocolHandler()
out["protocol_handler"] = [handler.supports("TCPROS"), handler.get_supported(), handler.shutdown(),
                           attempt(lambda: handler.init_publisher("/t", ["TCPROS"]))[0] != "ok"]

# recv_buff on a socket pair
a, b = socket.socketpair()
a.sendall(b"abc")
got = io.BytesIO()
out["recv_buff"] = [tcpros_base.recv_buff(b, got, 2), got.getvalue().decode()]
b.setblocking(False)
got2 = io.BytesIO()
out["recv_buff"] += [tcpros_base.recv_buff(b, got2, 10), got2.getvalue().decode(), tcpros_base.recv_buff(b, got2, 10)]
b.setblocking(True)
a.close()
out["recv_buff"].append(attempt(lambda: tcpros_base.recv_buff(b, got2, 10)))
b.close()
out["exceptions"] = [tcpros_base.TransportInitError is rospy.TransportInitError,
                     tcpros_base.TransportTerminated is rospy.TransportTerminated,
                     issubclass(rospy.TransportInitError, rospy.TransportException)]

# the TCPROS side of services
out["convert"] = [attempt(lambda r=r: str(tcpros_service.convert_return_to_response(r, SetBoolResponse)))
                  for r in (SetBoolResponse(True, "m"), {"success": True, "message": "d"}, (False, "t"), [True, "l"],
                            None, True, {"nope": 1}, (1, 2, 3))]
client = tcpros_service.TCPROSServiceClient("/svc", SetBool, headers={"persistent": "1"})
server = tcpros_service.TCPService("/svc", SetBool)
out["service_protocols"] = [client.get_header_fields(), server.get_header_fields(), client.recv_data_class.__name__,
                            server.recv_data_class.__name__, client.direction, client.buff_size]
response = io.BytesIO()
response.write(b"\x01")
rospy.msg.serialize_message(response, 0, SetBoolResponse(True, "ok"))
msgs = []
client.read_messages(response, msgs, None)
error = io.BytesIO()
error.write(b"\x00\x04\x00\x00\x00boom")
out["service_read"] = [[str(m) for m in msgs], attempt(lambda: client.read_messages(error, [], None))]
tcpros_handler = tcpros.get_tcpros_handler()
out["tcpros_handler"] = [tcpros_handler is tcpros.get_tcpros_handler(), tcpros_handler.get_supported(),
                         tcpros_handler.supports("UDPROS"), tcpros_handler.shutdown(),
                         list(tcpros_handler.create_transport("/t", "http://h:1/", "bad")),
                         list(tcpros_handler.create_transport("/t", "http://h:1/", ["UDPROS", "h", 1]))]
proto = tcpros_base.TCPROSTransportProtocol("/t", String, queue_size=3)
out["protocol"] = [proto.get_header_fields(), proto.direction, proto.buff_size,
                   attempt(lambda: tcpros_base.TCPROSTransportProtocol("/t", dict))]
plain = tcpros_base.TCPROSTransport(proto, "/t")
out["tcpros_transport"] = [plain.transport_type, plain.endpoint_id, plain.is_latched, plain.fileno(),
                           attempt(lambda: plain.write_data(b"x")),
                           attempt(lambda: plain.receive_once()),
                           attempt(lambda: tcpros_base.TCPROSTransport(proto, ""))]

# registration listeners and the service manager
events = []


class Recorder(registration.RegistrationListener):
    def reg_added(self, name, type_or_uri, kind):
        events.append(["added", name, type_or_uri, kind])

    def reg_removed(self, name, type_or_uri, kind):
        events.append(["removed", name, type_or_uri, kind])


listeners = registration.RegistrationListeners()
listeners.add_listener(Recorder())
out["bad_listener"] = attempt(lambda: listeners.add_listener(object()))[0]
listeners.notify_added("/t", "std_msgs/String", registration.Registration.PUB)
manager = rospy.service.ServiceManager(listeners)
service = rospy.service._Service("svc", SetBool)
service.uri = "rosrpc://h:1"
manager.register("/svc", service)
out["service_manager"] = [attempt(lambda: manager.register("/svc", service)), manager.get_services(),
                          manager.get_service("/svc") is service, manager.get_service("/none")]
manager.unregister("/svc", service)
out["service_manager"] += [manager.get_services(), events,
                           [service.resolved_name, service.request_class.__name__, service.response_class.__name__]]
listeners.clear()
out["cleared"] = listeners.listeners
registration.set_topic_manager("tm")
registration.set_service_manager("sm")
out["managers"] = [registration.get_topic_manager(), registration.get_service_manager()]

# rospy.client's names, the ROS clock's condition
import rospy.client  # noqa: E402
import rospy.rostime  # noqa: E402

out["client"] = [rospy.client.TIMEOUT_READY, [rospy.client.DEBUG, rospy.client.INFO, rospy.client.WARN,
                 rospy.client.ERROR, rospy.client.FATAL], rospy.client.GetLoggers._type, rospy.client.Logger._type,
                 rospy.client.SetLoggerLevelResponse._type, rospy.client.Log._type,
                 rospy.client.Service is rospy.Service]
cond = rospy.rostime.get_rostime_cond()
woken = []


def wait_for_change():
    with cond:
        ready.set()
        woken.append(cond.wait(30))


ready = threading.Event()
waiter = threading.Thread(target=wait_for_change)
waiter.start()
ready.wait(30)
with cond:  # the waiter is in cond.wait once it gave the lock up
    pass
rospy.rostime._set_rostime(rospy.Time(3, 4))
waiter.join(30)
rospy.rostime.switch_to_wallclock()
out["rostime_cond"] = woken

# masterslave's API validation
import rospy.impl.masterslave as masterslave  # noqa: E402


class Api(masterslave.XmlRpcHandler):
    @masterslave.apivalidate(0, (core.is_topic("topic"), None))
    def call(self, caller_id, topic, other):
        return 1, "fine", [topic, other]

    @masterslave.apivalidate(-1, ())
    def broken(self, caller_id):
        raise RuntimeError("inside")


api = Api()
out["apivalidate"] = [api.call("/me", "chat", 5), api.call("/me", "/", 5), api.call("/me"), api.call(),
                      api.call(3, "chat", 5), api.broken("/me"), api.call.__name__,
                      [masterslave.STATUS, masterslave.MSG, masterslave.VAL, masterslave.LOG_API],
                      masterslave.is_publishers_list("p"), api._ready("http://x:1/"), api._shutdown("r")]

# Poller and QueuedConnection
from rospy.impl.tcpros_pubsub import QueuedConnection  # noqa: E402
from rospy.topics import Poller  # noqa: E402

left, right = socket.socketpair()
poller = Poller()
poller.add_fd(right.fileno())
out["poller"] = [list(poller.error_iter())]
left.close()
out["poller"].append(list(poller.error_iter()) == [right.fileno()])
poller.remove_fd(right.fileno())
out["poller"].append(list(poller.error_iter()))
right.close()


class Collecting(transport.Transport):
    def __init__(self):
        super().__init__(transport.OUTBOUND, "collect")
        self.written = []
        self.all_written = threading.Event()

    def write_data(self, data):
        self.written.append(data.decode())
        if data == b"last":
            self.all_written.set()
        return True


target = Collecting()
queued = QueuedConnection(target, 2)
out["queued"] = [queued.write_data(b"a"), queued.name, queued.direction]
queued.write_data(b"last")
target.all_written.wait(30)
target.close()
queued._thread.join(30)
out["queued"] += [target.written[0], target.written[-1], queued._thread.is_alive()]

# shutdown: hook order and the flags each hook sees
seen = []


def look(tag):
    return lambda *reason: seen.append([tag, list(reason), core.is_shutdown(), core.is_shutdown_requested(),
                                        core._shutdown_flag, core._in_shutdown])


core.add_shutdown_hook(look("shutdown"))
core.add_preshutdown_hook(look("pre"))
core.add_client_shutdown_hook(look("client"))
rospy.on_shutdown(lambda: look("on_shutdown")())  # rospy's hooks take no argument
out["hook_lists"] = [len(core._shutdown_hooks) >= 1, len(core._preshutdown_hooks) >= 1,
                     len(core._client_shutdown_hooks) >= 1]
out["before"] = [core.is_shutdown(), core._shutdown_flag, core._in_shutdown]
core.signal_shutdown("driver done")
core.add_shutdown_hook(look("late"))
out["seen"] = seen
out["after"] = [core.is_shutdown(), core._shutdown_flag, core._in_shutdown, core._shutdown_hooks,
                core._preshutdown_hooks, core._client_shutdown_hooks]
print(json.dumps(out))
