"""Run by Debian's /usr/bin/python3 (real genpy) and by kame's interpreter: genpy.Message's base
constructor, bool arrays read back, the 'rosmsg' decoding handler, generate_initpy and genpy_main,
answered as JSON for the two to be compared. stdin: {"workdir": a scratch folder}."""

import codecs
import io
import json
import logging
import os
import sys

import genpy
import genpy.dynamic
import genpy.generate_initpy
import genpy.genpy_main
import genpy.message


def attempt(function, *args, **kwds):
    try:
        return ["ok", function(*args, **kwds)]
    except BaseException as exc:  # SystemExit from genmain included: its code is compared
        return ["error", type(exc).__name__, str(exc)]


class Pair(genpy.Message):
    __slots__ = ["a", "b"]
    _slot_types = ["int32", "string"]

    def __init__(self, *args, **kwds):
        super().__init__(*args, **kwds)  # genpy-generated code spells it super(Pair, self)
        if self.b is None:
            self.b = "default"


def constructor():
    def fields(*args, **kwds):
        msg = Pair(*args, **kwds)
        return [msg.a, msg.b]

    return [attempt(fields), attempt(fields, 1, "x"), attempt(fields, a=2), attempt(fields, 1),
            attempt(fields, 1, b="x"), attempt(fields, c=3), attempt(fields, 1, "x", 3),
            attempt(lambda: list(genpy.Message().__slots__))]


def bool_arrays():
    definition = "bool[3] fixed\nbool[] var\nbool one\nint32[2] ints\n"
    cls = genpy.dynamic.generate_dynamic("p/Bools", definition)["p/Bools"]
    buff = io.BytesIO()
    cls(fixed=[True, False, True], var=[False, True], one=True, ints=[1, 2]).serialize(buff)
    msg = cls().deserialize(buff.getvalue())
    return [buff.getvalue().hex(), [type(msg.fixed).__name__, msg.fixed], [type(msg.var).__name__, msg.var],
            msg.one, list(msg.ints)]


class Records(logging.Handler):
    def __init__(self):
        super().__init__()
        self.lines = []

    def emit(self, record):
        self.lines.append(record.getMessage())


def unicode_errors():
    records = Records()
    logging.getLogger("rosout").addHandler(records)
    handler = codecs.lookup_error("rosmsg")
    handler.msg_type = "p/Text"
    texts = [b"ok\xff".decode("utf-8", "rosmsg"), b"\xfe".decode("utf-8", "rosmsg")]
    handler.msg_type = None
    texts.append(b"\xfd".decode("utf-8", "rosmsg"))
    logging.getLogger("rosout").removeHandler(records)
    return [texts, records.lines, type(handler).__name__, genpy.message.isstring("s"),
            genpy.message.isstring(b"s")]


class Recording:
    def __init__(self, code):
        self.code = code
        self.calls = []

    def generate_messages(self, package, files, outdir, search_path):
        self.calls.append([package, [os.path.basename(f) for f in files], os.path.basename(outdir), search_path])
        return self.code


def initpy_and_main(workdir):
    out = {}
    folder = os.path.join(workdir, "msg")
    os.makedirs(folder)
    for name in ("_B.py", "_A.py", "__init__.py", "notes.txt"):
        open(os.path.join(folder, name), "w").close()
    out["write_modules"] = [genpy.generate_initpy.write_modules(folder),
                            genpy.generate_initpy.write_modules(os.path.join(workdir, "absent"))]
    with open(os.path.join(folder, "__init__.py")) as f:
        out["init"] = f.read()
    blocker = os.path.join(workdir, "file")
    open(blocker, "w").close()
    out["blocked"] = attempt(genpy.generate_initpy.write_module, blocker, ["_A"])[:2]
    genpy.generate_initpy.write_module(os.path.join(workdir, "made", "srv"), ["_X", "_Y"])
    with open(os.path.join(workdir, "made", "srv", "__init__.py")) as f:
        out["made"] = f.read()
    runs = []
    stderr, sys.stderr = sys.stderr, io.StringIO()
    try:
        for code, argv in ((0, ["prog", "-p", "pkg", "-o", os.path.join(workdir, "out"), "-I", "std_msgs:/x",
                                "-I", "pkg:/y", "A.msg", "B.msg"]),
                           (1, ["prog", "-p", "pkg", "-o", os.path.join(workdir, "out"), "A.msg"]),
                           (0, ["prog", "--initpy", "-o", folder]),
                           (0, ["prog", "--initpy"]),
                           (0, ["prog", "-p", "pkg", "-o", os.path.join(workdir, "out")])):
            gen = Recording(code)
            runs.append([attempt(genpy.genpy_main.genmain, argv, "prog", gen)[:2], gen.calls,
                         os.path.isdir(os.path.join(workdir, "out"))])
    finally:
        sys.stderr = stderr
    out["genmain"] = runs
    return out


def main():
    request = json.load(sys.stdin)
    answer = {"constructor": constructor(), "bools": bool_arrays(), "unicode": unicode_errors(),
              "initpy": initpy_and_main(request["workdir"])}
    json.dump(answer, sys.stdout, default=repr)


if __name__ == "__main__":
    main()
