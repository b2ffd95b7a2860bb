"""genmsg.srvs: a service spec, its request and response MsgSpecs and its text."""

from __future__ import annotations

from genmsg.msgs import MsgSpec
from genmsg.names import is_legal_resource_base_name, is_legal_resource_name, package_resource_name, resource_name

__all__ = ["SrvSpec", "is_legal_resource_base_name", "is_legal_resource_name", "package_resource_name",
           "resource_name"]


class SrvSpec:
    def __init__(self, request: MsgSpec, response: MsgSpec, text: str, full_name: str = "", short_name: str = "",
                 package: str = "") -> None:
        alt_package, alt_short_name = package_resource_name(full_name)
        self.request = request
        self.response = response
        self.text = text
        self.full_name = full_name
        self.short_name = short_name or alt_short_name
        self.package = package or alt_package

    def __eq__(self, other: object) -> bool:
        if not other or not isinstance(other, SrvSpec):
            return False
        return (self.request == other.request and self.response == other.response and self.text == other.text
                and self.full_name == other.full_name and self.short_name == other.short_name
                and self.package == other.package)

    def __ne__(self, other: object) -> bool:
        return not self.__eq__(other)

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        return f"SrvSpec[{self.request!r}, {self.response!r}]"
