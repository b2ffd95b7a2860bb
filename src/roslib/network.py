"""roslib.network: rosgraph.network under its older roslib name."""

from rosgraph.network import (
    ROS_HOSTNAME,
    ROS_IP,
    SIOCGIFADDR,
    SIOCGIFCONF,
    BytesIO,
    ROSHandshakeException,
    create_local_xmlrpc_uri,
    decode_ros_handshake_header,
    encode_ros_handshake_header,
    get_address_override,
    get_bind_address,
    get_host_name,
    get_local_address,
    get_local_addresses,
    is_local_address,
    parse_http_host_and_port,
    python3,
    read_ros_handshake_header,
    write_ros_handshake_header,
)

__all__ = ["ROS_HOSTNAME", "ROS_IP", "SIOCGIFADDR", "SIOCGIFCONF", "BytesIO", "ROSHandshakeException",
           "create_local_xmlrpc_uri", "decode_ros_handshake_header", "encode_ros_handshake_header",
           "get_address_override", "get_bind_address", "get_host_name", "get_local_address", "get_local_addresses",
           "is_local_address", "parse_http_host_and_port", "python3", "read_ros_handshake_header",
           "write_ros_handshake_header"]
