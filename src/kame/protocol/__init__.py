"""Wire protocols as pure functions and state machines: bytes in, values and events out."""
