"""genpy.generate_struct: the code-text helpers genpy's generator writes struct calls with.

They return Python source lines (genpy's generated modules call `_get_struct_<pattern>()`);
kame's own codegen (kame.msg.codegen) writes its modules differently, but tools that emit
genpy-style code, and genpy's tests, use these. Patterns used are recorded per generation run.
"""

from __future__ import annotations

from genpy.base import SIMPLE_TYPES_DICT

__all__ = ["add_pattern", "clear_patterns", "compute_struct_pattern", "get_patterns", "int32_pack", "int32_unpack",
           "pack", "pack2", "reduce_pattern", "serialize", "unpack", "unpack2", "unpack3"]

_context_patterns: list[str] = []


def add_pattern(p: str) -> None:
    """Record a struct pattern a generated module uses."""
    _context_patterns.append(p)


def clear_patterns() -> None:
    del _context_patterns[:]


def get_patterns() -> list[str]:
    return _context_patterns[:]


def compute_struct_pattern(types: list[str] | None) -> str | None:
    """The struct format of `types` when every one is simple, else None."""
    if not types:
        return None
    codes = [SIMPLE_TYPES_DICT.get(t) for t in types]
    return None if None in codes else "".join(str(c) for c in codes)


def reduce_pattern(pattern: str | None) -> str | None:
    """Runs of one code as a count ('iiiB' -> '3iB'); a pattern holding % is left alone, and so
    are runs of the digits 0-8 (genpy's rule, which leaves 9 out)."""
    if not pattern or len(pattern) == 1 or "%" in pattern:
        return pattern
    out = []
    previous, count = pattern[0], 1
    for code in pattern[1:]:
        if code == previous and code not in "012345678":
            count += 1
            continue
        out.append(f"{count}{previous}" if count > 1 else previous)
        previous, count = code, 1
    out.append(f"{count}{previous}" if count > 1 else previous)
    return "".join(out)


def serialize(expr: str) -> str:
    """The line writing `expr` to the serialization buffer."""
    return f"buff.write({expr})"


def int32_pack(var: str) -> str:
    return serialize(f"_struct_I.pack({var})")


def int32_unpack(var: str, buff: str) -> str:
    return f"({var},) = _struct_I.unpack({buff})"


def pack(pattern: str, vars_: str) -> str:
    """A pack call on the generated module's cached Struct for the string `pattern`."""
    reduced = reduce_pattern(pattern)
    add_pattern(str(reduced))
    return serialize(f"_get_struct_{reduced}().pack({vars_})")


def pack2(pattern: str, vars_: str) -> str:
    """A pack call where `pattern` names a variable holding the format."""
    return serialize(f"struct.Struct({pattern}).pack({vars_})")


def unpack(var: str, pattern: str, buff: str) -> str:
    reduced = reduce_pattern(pattern)
    add_pattern(str(reduced))
    return f"{var} = _get_struct_{reduced}().unpack({buff})"


def unpack2(var: str, pattern: str, buff: str) -> str:
    return f"{var} = struct.unpack({pattern}, {buff})"


def unpack3(var: str, struct_var: str, buff: str) -> str:
    return f"{var} = {struct_var}.unpack({buff})"
