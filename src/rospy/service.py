"""rospy.service: Service, ServiceProxy, wait_for_service (kame.client.services)."""

from kame.client.services import (
    Service,
    ServiceException,
    ServiceProxy,
    wait_for_service,
)

__all__ = [
    "Service",
    "ServiceException",
    "ServiceProxy",
    "wait_for_service",
]
