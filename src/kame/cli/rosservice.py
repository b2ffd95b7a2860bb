"""rosservice: list, call, type, info, find, uri and args, as ros_comm's rosservice behaves.

A service's type is learnt by probing it (a TCPROS header exchange with `probe=1`); the
service class is then imported like any message package (kame's, or a workspace's through
the import hook). `call` fills the request from YAML arguments with genpy's rules
(kame.msg.fill) and prints the response in the echo style. Failures print one `ERROR:` line
(multi-line where the real tool's message is) and exit 2, as the real tool does, also when
no master is reachable. Unlike the real tool, `call` does not register a node with the
master (no init_node): it only needs a caller id for the service connection.
"""

from __future__ import annotations

import io
import os
import sys
import time
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from typing import Any

import yaml

from kame import param_yaml
from kame.cli._options import OptionParser
from kame.cli._tool import Master, ToolError, run, script_resolve_name, strip_remappings
from kame.msg import lookup
from kame.msg.catalog import MsgCatalog
from kame.msg.describe import describe_srv, load_srv
from kame.msg.errors import MessageError, SerializationError
from kame.msg.fill import FillError, fill_message_args, printable_message_args
from kame.msg.message import find_type_problem
from kame.net.handshake import HandshakeError
from kame.node.master_proxy import MasterError
from kame.node.remote_poll import poll_remote
from kame.node.services import ServiceClient, ServiceError, probe_service
from kame.rostime import Time

NAME = "rosservice"
ID = "/rosservice"
STATUS = 2  # every rosservice failure exits 2
PROBE_TIMEOUT = 5.0

USAGE = """Commands:
\trosservice args\tprint service arguments
\trosservice call\tcall the service with the provided args
\trosservice find\tfind services by service type
\trosservice info\tprint information about service
\trosservice list\tlist active services
\trosservice type\tprint service type
\trosservice uri\tprint service ROSRPC uri

Type rosservice <command> -h for more detailed usage, e.g. 'rosservice call -h'
"""


class Tool:
    """The master, and the caller id that probes and calls go out under."""

    def __init__(self, caller_id: str = ID) -> None:
        self.master = Master(caller_id, no_master_status=STATUS)
        self.caller_id = caller_id

    def close(self) -> None:
        self.master.close()

    def probe(self, service: str, timeout: float = PROBE_TIMEOUT) -> dict[str, str]:
        """The service's TCPROS header (MasterError when the master does not know the service)."""
        return probe_service(self.master.proxy, self.caller_id, service, timeout)

    # -------------------------------------------------------------- master lookups

    def services(self, namespace: str | None = None) -> list[tuple[str, list[str]]]:
        services = self.master.system_state()[2]
        if namespace:
            prefix = namespace.rstrip("/") + "/"
            services = [s for s in services if s[0] == namespace or s[0].startswith(prefix)]
        return services

    def uri(self, service: str) -> str | None:
        try:
            return str(self.master.call("lookupService", service))
        except MasterError:
            return None

    def provider(self, service: str) -> str | None:
        for name, nodes in self.services():
            if name == service and nodes:
                return nodes[0]
        return None

    def type(self, service: str) -> str | None:
        """The type a service's probe header names; None when the master does not know it."""
        uri = self.uri(service)
        if uri is None:
            return None
        try:
            header = self.probe(service)
        except MasterError:
            return None
        except (OSError, HandshakeError, ServiceError):
            raise ToolError(f"Unable to communicate with service [{service}], address [{uri}]", STATUS) from None
        return header.get("type")

    def service_class(self, service: str) -> Any:
        service_type = self.type(service)
        if not service_type:
            if service not in [name for name, _ in self.services()]:
                raise ToolError(f"Service [{service}] is not available.", STATUS)
            raise ToolError(f"Unable to determine type of service [{service}].", STATUS)
        cls = load_service_class(service_type)
        if cls is None:
            package = service_type.partition("/")[0] if "/" in service_type else None
            raise ToolError(f"Unable to load type [{service_type}].\nHave you typed 'make' in [{package}]?", STATUS)
        return cls


@contextmanager
def tool(caller_id: str = ID) -> Iterator[Tool]:
    t = Tool(caller_id)
    try:
        yield t
    finally:
        t.close()


def load_service_class(service_type: str) -> Any:
    """`pkg/Name` -> the service class, or None (kame's packages and the workspace's alike)."""
    try:
        return lookup.service_class(service_type)
    except MessageError:
        return None


def _srv_text(service_type: str) -> str:
    try:
        catalog = MsgCatalog.from_environment()
        return describe_srv(catalog, load_srv(catalog, service_type))
    except MessageError:
        return ""


def arg_summary(args: list[Any]) -> str:
    return "\n".join(f" * {a} (type {type(a).__name__})" for a in args)


def yaml_args(texts: Sequence[str]) -> list[Any]:
    """Each command-line argument as YAML; an empty argument is the empty string."""
    values: list[Any] = []
    for text in texts:
        try:
            values.append(param_yaml.safe_load(text if text != "" else "''"))
        except (yaml.YAMLError, param_yaml.ParamValueError) as exc:
            raise ToolError(f"Invalid YAML in argument [{text}]: {' '.join(str(exc).split())}", STATUS) from None
    return values


def _bytes_text(message: str, prefix: str) -> str:
    """rospy prints a server's error text as Python 3 shows bytes: b'...'."""
    if message.startswith(prefix):
        return prefix + repr(message[len(prefix):].encode("utf-8", "surrogateescape"))
    return message


def call(t: Tool, service: str, service_class: Any, args: list[Any], verbose: bool) -> None:
    request = service_class._request_class()
    now = Time.from_sec(time.time())
    keys: dict[str, Any] = {"now": now}
    try:
        from std_msgs.msg import Header

        keys["auto"] = Header(stamp=now)
    except ImportError:
        pass
    try:
        fill_message_args(request, args, keys)
    except FillError as exc:
        raise ToolError(
            f"Incompatible arguments to call service:\n{exc}\nProvided arguments are:\n{arg_summary(args)}\n\n"
            f"Service arguments are: [{printable_message_args(request)}]", STATUS) from None
    buff = io.BytesIO()
    try:
        request.serialize(buff)
    except (SerializationError, TypeError, ValueError, AttributeError) as exc:
        problem = find_type_problem(request) or str(exc)
        raise ToolError("Unable to send request. One of the fields has an incorrect type:\n"
                        f"  {problem}\n\nsrv file:\n{_srv_text(service_class._type)}", STATUS) from None
    client = ServiceClient(t.master.proxy, t.caller_id, service, service_class._type, service_class._md5sum,
                           persistent=False)
    try:
        data = client.call(buff.getvalue())
    except MasterError:
        raise ToolError(f"service [{service}] unavailable", STATUS) from None
    except ServiceError as exc:
        raise ToolError(_bytes_text(str(exc), f"service [{service}] responded with an error: "), STATUS) from None
    except OSError as exc:
        raise ToolError(f"unable to contact master: {exc}", STATUS) from None
    finally:
        client.close()
    try:
        response = service_class._response_class().deserialize(data)
    except MessageError as exc:
        raise ToolError(f"cannot read the response of [{service}]: {exc}", STATUS) from None
    if verbose:
        print(str(request))
        print("---")
    print(str(response), flush=True)


def _stdin_documents() -> Iterator[Any]:
    """YAML documents from stdin, separated by `---` lines (what the real tool reads)."""
    buff: list[str] = []
    for line in sys.stdin:
        if line.strip() == "---":
            if buff:
                yield param_yaml.safe_load("".join(buff))
            buff = []
        else:
            buff.append(line)
    if "".join(buff).strip():
        yield param_yaml.safe_load("".join(buff))


def _wait_for_service(t: Tool, service: str) -> None:
    t.master.call("getPid")

    def answers() -> bool | None:
        try:
            t.probe(service, timeout=2.0)
            return True
        except (OSError, MasterError, ServiceError, HandshakeError, ValueError):
            return None

    poll_remote(answers)  # until it answers; Ctrl-C ends it


# ------------------------------------------------------------------ commands


def _parser(usage: str) -> OptionParser:
    return OptionParser(usage=usage, prog=NAME)


def _service_only(cmd: str, argv: list[str]) -> str:
    parser = _parser(f"usage: %prog {cmd} /service")
    parsed = parser.parse_args(argv)
    args = parsed.args
    if not args:
        parser.error("service must be specified")
    if len(args) > 1:
        parser.error("you may only specify one input service")
    return script_resolve_name(NAME, args[0])


def cmd_list(argv: list[str]) -> None:
    parser = _parser("usage: %prog list [/namespace]")
    parser.add_argument("-n", "--nodes", dest="print_nodes", default=False, action="store_true",
                      help="print nodes that provide service(s)")
    options = parser.parse_args(argv)
    args = options.args
    namespace = None
    if len(args) == 1:
        namespace = script_resolve_name(NAME, args[0])
    elif len(args) > 1:
        parser.error("you may only specify one input namespace")
    with tool() as t:
        services = sorted(t.services(namespace), key=lambda s: s[0])
    for name, nodes in services:
        print(f"{name} {','.join(nodes)}" if options.print_nodes else name)


def cmd_type(argv: list[str]) -> None:
    service = _service_only("type", argv)
    with tool() as t:
        service_type = t.type(service)
    if service_type is None:
        raise ToolError(f"Unknown service [{service}]", 1, prefix="")
    print(service_type)


def cmd_uri(argv: list[str]) -> None:
    service = _service_only("uri", argv)
    with tool() as t:
        uri = t.uri(service)
    if not uri:
        raise ToolError(f"Unknown service: {service}", 1, prefix="")
    print(uri)


def cmd_node(argv: list[str]) -> None:
    service = _service_only("node", argv)
    with tool() as t:
        node = t.provider(service)
    if not node:
        raise ToolError(f"Unknown service: {service}", 1, prefix="")
    print(node)


def cmd_args(argv: list[str]) -> None:
    service = _service_only("args", argv)
    with tool() as t:
        cls = t.service_class(service)
    print(printable_message_args(cls._request_class()))


def cmd_info(argv: list[str]) -> None:
    parser = _parser("usage: %prog info /service")
    parsed = parser.parse_args(argv)
    args = parsed.args
    if len(args) > 1:
        parser.error("you may only specify one service")
    if not args:
        parser.error("you must specify a service name")
    service = script_resolve_name(NAME, args[0])
    with tool() as t:
        node = t.provider(service)
        if not node:
            raise ToolError("unknown service", 1)
        print(f"Node: {node}")
        uri = t.uri(service)
        if not uri:
            print("ERROR: service is no longer available", file=sys.stderr)
            return
        print(f"URI: {uri}")
        service_type = t.type(service)
        if not service_type:
            print("ERROR: service is no longer available", file=sys.stderr)
            return
        print(f"Type: {service_type}", flush=True)
        cls = t.service_class(service)
        print(f"Args: {printable_message_args(cls._request_class())}")


def cmd_find(argv: list[str]) -> None:
    parser = _parser("usage: %prog find msg-type")
    parsed = parser.parse_args(argv)
    args = parsed.args
    if not args:
        parser.error("please specify a message type")
    if len(args) > 1:
        parser.error("you may only specify one message type")
    matches: list[str] = []
    with tool() as t:
        for service, _ in t.services():
            try:
                if t.type(service) == args[0]:
                    matches.append(service)
            except ToolError:
                continue
    print("\n".join(matches))


def _is_negative_number(arg: str) -> bool:
    return len(arg) > 1 and arg[0] == "-" and (arg[1].isdigit() or (arg[1] == "." and arg[2:3].isdigit()))


def cmd_call(argv: list[str]) -> None:
    parser = _parser("usage: %prog call /service [args...]")
    parser.add_argument("-v", dest="verbose", default=False, action="store_true", help="print verbose output")
    parser.add_argument("--wait", dest="wait", default=False, action="store_true",
                      help="wait for service to be advertised")
    # Values such as -3 or -.5 are arguments, not options (the real tool needs `--` for them).
    negatives = {f"\0{i}": arg for i, arg in enumerate(argv) if _is_negative_number(arg)}
    options = parser.parse_args([f"\0{i}" if _is_negative_number(a) else a for i, a in enumerate(argv)])
    args = options.args
    args = [negatives.get(a, a) for a in args]
    if not args:
        parser.error("service must be specified")
    service = script_resolve_name(NAME, args[0])
    caller_id = f"/rosservice_{os.getpid()}_{int(time.time() * 1000)}"
    with tool(caller_id) as t:
        if options.wait:
            _wait_for_service(t, service)
        cls = t.service_class(service)
        values = yaml_args(args[1:])
        if values or not cls._request_class.__slots__:
            call(t, service, cls, values, options.verbose)
            return
        if sys.stdin.isatty():
            parser.error("Please specify service arguments")
        try:
            for document in _stdin_documents():
                if document:
                    call(t, service, cls, document if isinstance(document, list) else [document], options.verbose)
        except (yaml.YAMLError, param_yaml.ParamValueError) as exc:
            raise ToolError(f"Invalid YAML: {' '.join(str(exc).split())}", STATUS) from None


def _main(argv: list[str]) -> int:
    if not argv:
        sys.stdout.write(USAGE + "\n")
        return getattr(os, "EX_USAGE", 1)
    argv = strip_remappings(argv)
    command, rest = argv[0], argv[1:]
    commands = {"list": cmd_list, "info": cmd_info, "type": cmd_type, "uri": cmd_uri, "node": cmd_node,
                "call": cmd_call, "args": cmd_args, "find": cmd_find}
    if command not in commands:
        sys.stdout.write(USAGE + "\n")
        return getattr(os, "EX_USAGE", 1)
    commands[command](rest)
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    return run(_main, argv)


if __name__ == "__main__":
    sys.exit(main())

