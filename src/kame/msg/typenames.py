"""Field type names: `float64[36]`, `Point[]`, `std_msgs/Header`.

Kept apart from the spec dataclasses so that message classes can use it at run time without
importing the IDL machinery (start-up time of every node).
"""

from __future__ import annotations


def split_array(type_name: str) -> tuple[str, bool, int | None]:
    """'float64[36]' -> ('float64', True, 36); 'Point[]' -> ('Point', True, None)."""
    if not type_name.endswith("]"):
        return type_name, False, None
    base, _, rest = type_name.partition("[")
    size = rest[:-1]
    return base, True, (int(size) if size else None)
