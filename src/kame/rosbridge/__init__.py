"""rosbridge_suite on kame: the rosbridge v2 protocol over WebSocket, and rosapi.

Pure (L1): `conversion` (messages as rosbridge's JSON and CBOR values), `protocol` (frames,
fields, status, fragments, png), `pacing` (throttle_rate and queue_length), `typedefs` (rosapi's
TypeDefs), `globs` (topics_glob and friends). On kame.client (L4): `session` (one client's ops),
`topics`, `services`, `graph`, `server` (rosbridge_websocket) and `rosapi` (rosapi_node). The
WebSocket I/O is kame.net.websocket_listener.
"""
