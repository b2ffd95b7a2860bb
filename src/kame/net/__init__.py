"""I/O runtime: the only package that touches sockets, the event loop and processes.

It moves bytes and runs tasks; it knows nothing of the master or of messages.
"""
