"""rospy.impl.tcpros_service: where rospy's Service, ServiceProxy and wait_for_service live
(programs import them from here too): kame.client.services."""

from kame.client.services import Service, ServiceException, ServiceImpl, ServiceProxy, wait_for_service

__all__ = ["Service", "ServiceException", "ServiceImpl", "ServiceProxy", "wait_for_service"]
