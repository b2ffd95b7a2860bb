"""rqt_logger_level's calls: which nodes offer logger services, their loggers, and setting a level.

Any node that offers `<node>/get_loggers` and `<node>/set_logger_level` (roscpp's services,
which rospy and kame's nodes offer too) is listed. Calls go through kame's service client with
a timeout, so a hung node costs the timeout, not the tool.
"""

from __future__ import annotations

from kame.node.master_proxy import MasterError, MasterProxy
from kame.node.services import ServiceClient, ServiceError
from kame.node.topics import serialize_payload
from kame.protocol.xmlrpc import XmlRpcError

LEVELS = ("debug", "info", "warn", "error", "fatal")
GET = "/get_loggers"
SET = "/set_logger_level"
CALL_TIMEOUT = 3.0


class LoggerError(Exception):
    """A node did not answer, or refused."""


class LoggerLevels:
    def __init__(self, master_uri: str, caller_id: str, timeout: float = CALL_TIMEOUT) -> None:
        self.master = MasterProxy(master_uri, caller_id, timeout=timeout)
        self.caller_id = caller_id
        self.timeout = timeout

    def nodes(self) -> list[str]:
        """The nodes with both logger services, sorted."""
        try:
            services = {str(name) for name, _ in self.master.call("getSystemState")[2]}
        except (OSError, MasterError, XmlRpcError) as exc:
            raise LoggerError(f"cannot reach the master at {self.master.uri}: {exc}") from exc
        return sorted(s[:-len(GET)] for s in services if s.endswith(GET) and s[:-len(GET)] + SET in services)

    def _call(self, service: str, srv: type, request: object) -> object:
        client = ServiceClient(self.master, self.caller_id, service, srv._type, srv._md5sum,  # type: ignore[attr-defined]
                               persistent=False)
        try:
            payload = client.call(serialize_payload(request), timeout=self.timeout)
        except (OSError, ServiceError, MasterError, XmlRpcError) as exc:
            raise LoggerError(f"{service}: {exc}") from exc
        finally:
            client.close()
        return srv._response_class().deserialize(payload)  # type: ignore[attr-defined]

    def loggers(self, node: str) -> list[tuple[str, str]]:
        """(logger, level) of each of the node's loggers, levels in lower case."""
        from roscpp.srv import GetLoggers, GetLoggersRequest

        response = self._call(node + GET, GetLoggers, GetLoggersRequest())
        return [(str(lg.name), str(lg.level).lower()) for lg in response.loggers]  # type: ignore[attr-defined]

    def set_level(self, node: str, logger: str, level: str) -> None:
        from roscpp.srv import SetLoggerLevel, SetLoggerLevelRequest

        if level.lower() not in LEVELS:
            raise LoggerError(f"unknown level {level!r}: one of {', '.join(LEVELS)}")
        self._call(node + SET, SetLoggerLevel, SetLoggerLevelRequest(logger=logger, level=level.lower()))

    def close(self) -> None:
        self.master.close()
