"""interactive_markers' protocol without I/O: what a server sends on <ns>/update and
<ns>/update_full and does with <ns>/feedback (server_state), the menu entries model
(menu), and what a client such as rviz does with what a server sends (client_state)."""
