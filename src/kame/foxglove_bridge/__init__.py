"""foxglove_bridge: ROS 1 for Foxglove's WebSocket clients (ws-protocol, foxglove.websocket.v1).

`protocol` is the wire format (sans-IO), `graph` what is offered and how it changes (pure),
`bridge` the glue between kame's node and kame.net.websocket_hub, `node` the program.
"""
