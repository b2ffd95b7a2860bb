"""genpy's base, generate_struct, generate_numpy, check_type, MsgGenerator/SrvGenerator, the
generator's helpers (default_value, compute_import, ...) and msg_generator/srv_generator on one
JSON request; prints the answers as JSON. Run by kame's interpreter and Debian's (real genpy)."""

from __future__ import annotations

import importlib
import io
import json
import sys
import tempfile
import types
from pathlib import Path
from typing import Any

import genpy
from genpy import base, generate_numpy, generate_struct, generator
from genpy.message import check_type


def struct_helpers(patterns: list[str]) -> dict[str, Any]:
    generate_struct.clear_patterns()
    return {
        "simple": [base.SIMPLE_TYPES, base.SIMPLE_TYPES_DICT, [base.is_simple(t) for t in ("int8", "string", "time")]],
        "reduced": [generate_struct.reduce_pattern(p) for p in patterns],
        "computed": [generate_struct.compute_struct_pattern(t) for t in
                     (None, [], ["int32", "float64", "float64", "uint8"], ["int32", "string"])],
        "code": [generate_struct.int32_pack("x"), generate_struct.int32_unpack("x", "str[0:4]"),
                 generate_struct.pack("iii", "a, b, c"), generate_struct.pack2("pattern", "*x"),
                 generate_struct.unpack("(a, b)", "dd", "str[4:20]"), generate_struct.unpack2("x", "pat", "str[0:8]"),
                 generate_struct.unpack3("x", "s", "str[0:8]"), generate_struct.serialize("y"),
                 generate_numpy.unpack_numpy("x", "n", "numpy.float32", "str[a:b]"),
                 generate_numpy.pack_numpy("self.data"), generate_numpy.NUMPY_DTYPE],
        "patterns": generate_struct.get_patterns(),
        "struct_I": genpy.struct_I.format if isinstance(genpy.struct_I.format, str) else genpy.struct_I.format.decode(),
    }


def value(spec: Any) -> Any:
    """JSON -> a value: {"time": [s, ns]}, {"duration": ...}, {"msg": type, "fields": {...}}, {"bytes": text}."""
    if isinstance(spec, dict):
        if "time" in spec:
            return genpy.Time(*spec["time"])
        if "duration" in spec:
            return genpy.Duration(*spec["duration"])
        if "bytes" in spec:
            return spec["bytes"].encode()
        if "tuple" in spec:
            return tuple(value(v) for v in spec["tuple"])
        package, name = spec["msg"].split("/")
        cls = getattr(importlib.import_module(package + ".msg"), name)
        return cls(**{k: value(v) for k, v in spec.get("fields", {}).items()})
    if isinstance(spec, list):
        return [value(v) for v in spec]
    return spec


def type_checks(cases: list[list[Any]]) -> list[str | None]:
    answers: list[str | None] = []
    for field_type, spec in cases:
        try:
            check_type("f", field_type, value(spec))
            answers.append(None)
        except genpy.SerializationError as exc:
            answers.append(str(exc))
    return answers


def generated(package: dict[str, Any]) -> dict[str, Any]:
    answer: dict[str, Any] = {}
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        files: dict[str, list[str]] = {"msg": [], "srv": []}
        for kind in files:
            for name, text in package[kind].items():
                path = root / "src" / package["name"] / kind / f"{name}.{kind}"
                path.parent.mkdir(parents=True, exist_ok=True)
                path.write_text(text)
                files[kind].append(str(path))
        out = root / "out" / package["name"]
        search = {package["name"]: [str(root / "src" / package["name"] / "msg")], **package["search_path"]}
        answer["codes"] = [
            generator.MsgGenerator().generate_messages(package["name"], files["msg"], str(out / "msg"), search),
            generator.SrvGenerator().generate_messages(package["name"], files["srv"], str(out / "srv"), search)]
        answer["files"] = sorted(p.name for p in out.rglob("*.py"))
        (out / "__init__.py").touch()
        for kind in files:  # what genpy's generate_initpy writes
            (out / kind / "__init__.py").write_text("".join(f"from ._{name} import *\n" for name in package[kind]))
        sys.path.insert(0, str(root / "out"))
        classes = {}
        for kind in files:
            for name in package[kind]:
                module = importlib.import_module(f"{package['name']}.{kind}._{name}")
                classes[name] = getattr(module, name)
                if kind == "srv":
                    classes[name + "Request"] = getattr(module, name + "Request")
        for name, cls in sorted(classes.items()):
            buff = io.BytesIO()
            msg = cls()
            if hasattr(msg, "serialize"):
                msg.serialize(buff)
            answer[name] = [cls._type, cls._md5sum, getattr(cls, "__slots__", None), buff.getvalue().hex()]
        bad = generator.MsgGenerator().generate_messages(package["name"], [str(root / "missing" / "msg" / "X.msg")],
                                                         str(out / "bad"), search)
        answer["missing_file_code"] = bad
        try:
            generator.MsgGenerator().generate_messages("bad-name", [], str(out), search)
        except Exception as exc:
            answer["bad_package"] = [type(exc).__name__, str(exc)]
        answer["outfile"] = [generator.compute_outfile_name("/o", "Foo.msg", ".msg"),
                             generator.compute_resource_name("/p/Bar.srv", ".srv")]
    return answer


class Context:
    """The two questions genpy's helpers ask of genmsg's MsgContext, over specs registered here."""

    def __init__(self, specs: dict[str, Any]) -> None:
        self.specs = specs

    def is_registered(self, full_msg_type: str) -> bool:
        return full_msg_type in self.specs

    def get_registered(self, full_msg_type: str) -> Any:
        return self.specs[full_msg_type]


def attempt(function: Any, *args: Any) -> Any:
    try:
        return function(*args)
    except Exception as exc:  # the answer is which exception, compared with upstream's
        return "raises " + type(exc).__name__


def helpers(request: dict[str, Any]) -> dict[str, Any]:
    import roslib.msgs

    context = Context({full: roslib.msgs.load_from_string(text, full.split("/")[0], full, full.split("/")[1])
                       for full, text in request["registered"].items()})
    safe = generator.make_python_safe(roslib.msgs.load_from_string(request["unsafe"], "pkg", "pkg/Unsafe", "Unsafe"))
    return {"pkg_type": [list(p) if isinstance(p := attempt(generator.compute_pkg_type, *case), tuple) else p
                         for case in request["pkg_type"]],
            "defaults": [attempt(generator.default_value, context, t, p) for t, p in request["defaults"]],
            "constructors": [attempt(generator.compute_constructor, context, p, t) for p, t in request["defaults"]],
            "imports": [attempt(generator.compute_import, context, p, t) for p, t in request["imports"]],
            "safe": [safe.types, safe.names, [[c.type, c.name, c.val, c.val_text] for c in safe.constants],
                     safe.full_name, safe.text]}


def _spec(kind: str, path: Path, full_name: str) -> Any:
    try:  # Debian's genpy asks genmsg's loader for the spec
        import genmsg
        import genmsg.msg_loader as loader
    except ImportError:  # kame's generator reads the text and name
        return None, types.SimpleNamespace(text=path.read_text(), full_name=full_name)
    context = genmsg.MsgContext.create_default()
    load = loader.load_msg_from_file if kind == "msg" else loader.load_srv_from_file
    return context, load(context, str(path), full_name)


def generated_by_functions(package: dict[str, Any]) -> dict[str, Any]:
    """msg_generator/srv_generator's module text run: the classes it defines, used."""
    answer: dict[str, Any] = {}
    with tempfile.TemporaryDirectory() as tmp:
        search = dict(package["search_path"])
        for kind, function in (("msg", generator.msg_generator), ("srv", generator.srv_generator)):
            folder = Path(tmp) / package["name"] / kind
            folder.mkdir(parents=True)
            search.setdefault(package["name"], [str(Path(tmp) / package["name"] / "msg")])
            for name, text in sorted(package[kind].items()):
                (folder / f"{name}.{kind}").write_text(text)
            for name in sorted(package[kind]):
                context, spec = _spec(kind, folder / f"{name}.{kind}", f"{package['name']}/{name}")
                namespace: dict[str, Any] = {}
                exec("\n".join(function(context, spec, search)), namespace)  # run as its import would
                cls = namespace[name + "Request" if kind == "srv" else name]
                buff = io.BytesIO()
                cls().serialize(buff)
                answer[name] = [cls._type, cls._md5sum, cls.__slots__, buff.getvalue().hex(),
                                namespace[name]._md5sum]
    return answer


if __name__ == "__main__":
    request = json.load(sys.stdin)
    print(json.dumps({"struct": struct_helpers(request["patterns"]), "check_type": type_checks(request["check_type"]),
                      "generated": generated(request["package"]), "helpers": helpers(request["helpers"]),
                      "by_functions": generated_by_functions(request["package"])}))
