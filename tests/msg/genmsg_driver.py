"""Run by Debian's /usr/bin/python3 (real genmsg and genpy) and by kame's interpreter (kame's):
answers the same questions about genmsg and genpy.generator as JSON, for the two to be compared.

stdin: {"workdir": a scratch folder, "package": {"name", "msg": {Name: text}, "srv": {...}},
        "texts": [[full_name, text]], ...}; stdout: {section: answers}.
"""

import json
import os
import sys
import tempfile

import genmsg
import genmsg.command_line
import genmsg.deps
import genmsg.gentools
import genmsg.msg_loader
import genmsg.msgs
import genmsg.names
import genmsg.srvs
import genmsg.template_tools
import genpy.generator as gen


def attempt(function, *args):
    try:
        return ["ok", function(*args)]
    except Exception as exc:  # the class and text are what is compared
        return ["error", type(exc).__name__, str(exc)]


def spec_view(spec):
    return {"types": list(spec.types), "names": list(spec.names), "package": spec.package,
            "short_name": spec.short_name, "full_name": spec.full_name, "text": spec.text,
            "constants": [[c.type, c.name, c.val, c.val_text, repr(c)] for c in spec.constants],
            "fields": [repr(f) for f in spec.parsed_fields()], "has_header": spec.has_header(), "repr": repr(spec)}


def names_section(request):
    n = genmsg.names
    out = {}
    for name in request["names"]:
        out[name] = [attempt(n.package_resource_name, name), n.resource_name_base(name),
                     n.resource_name_package(name), n.is_legal_resource_name(name),
                     n.is_legal_resource_base_name(name), n.normalize_package_context(name),
                     n.resource_name("std_msgs", name), n.resource_name("std_msgs", name, "std_msgs")]
    return out


def msgs_section(request):
    m = genmsg.msgs
    out = {}
    for t in request["types"]:
        out[t] = [m.bare_msg_type(t), m.resolve_type(t, "pkg"), attempt(m.parse_type, t), m.is_valid_msg_type(t),
                  m.is_valid_constant_type(t), m.is_valid_msg_field_name(t), m.is_header_type(t), m.is_builtin(t)]
    out["constant_eq"] = [m.Constant("int32", " X ", 1, "1") == m.Constant("int32", "X", 1, "01"),
                          str(m.Constant("string", "S", "a", "a"))]
    out["field"] = [repr(m.Field("x", "int32[3]")), m.Field("h", "Header").is_header,
                    m.Field("p", "geometry_msgs/Point").is_builtin]
    out["duplicate"] = attempt(m.MsgSpec, ["int32", "int32"], ["a", "a"], [], "", "p/T")
    spec = m.MsgSpec(["std_msgs/Header", "int32"], ["header", "x"], [], "Header header\nint32 x\n", "p/T")
    out["spec"] = [spec.fields(), spec.has_header(), str(spec), spec == spec, spec != spec, spec.package]
    out["lists"] = [m.PRIMITIVE_TYPES, m.BUILTIN_TYPES, m.HEADER_FULL_NAME, m.TIME_MSG, m.DURATION_MSG]
    return out


def loader_section(request):
    loader = genmsg.msg_loader
    out = {"texts": {}, "constants": []}
    for full_name, text in request["texts"]:
        context = loader.MsgContext.create_default()
        got = attempt(loader.load_msg_from_string, context, text, full_name)
        if got[0] == "ok":
            got = ["ok", spec_view(got[1])]
        else:  # which error, not its wording: kame's parser says where and why in its own words
            got = got[:2]
        out["texts"][full_name + " " + text] = got
    for type_, text in request["constants"]:
        got = attempt(loader.convert_constant_value, type_, text)
        out["constants"].append(got if got[0] == "ok" else got[:2])
    context = loader.MsgContext.create_default()
    srv = loader.load_srv_from_string(context, request["srv_text"], "p/S")
    out["srv"] = [spec_view(srv.request), spec_view(srv.response), srv.text, srv.package, srv.short_name, repr(srv)]
    out["default_context"] = [context.is_registered("time"), spec_view(context.get_registered("duration")),
                              attempt(context.get_registered, "p/Nope")[:2], context.is_registered("p/SRequest[]")]
    return out


def write_package(root, package):
    folders = {}
    for kind in ("msg", "srv"):
        folder = os.path.join(root, package["name"], kind)
        os.makedirs(folder, exist_ok=True)
        folders[kind] = folder
        for name, text in package[kind].items():
            with open(os.path.join(folder, name + "." + kind), "w") as f:
                f.write(text)
    return folders


def relative(root, value):
    if isinstance(value, str):
        return value.replace(root, "<root>")
    if isinstance(value, (list, tuple)):
        return [relative(root, v) for v in value]
    if isinstance(value, dict):
        return {k: relative(root, v) for k, v in value.items()}
    return value


def package_section(request, root):
    loader = genmsg.msg_loader
    package = request["package"]
    name = package["name"]
    folders = write_package(root, package)
    search_path = {name: [folders["msg"]], "std_msgs": ["/usr/share/std_msgs/msg"],
                   "geometry_msgs": ["/usr/share/geometry_msgs/msg"]}
    out = {}
    context = loader.MsgContext.create_default()
    for short in sorted(package["msg"]):
        spec = loader.load_msg_by_type(context, name + "/" + short, search_path)
        depends = loader.load_depends(context, spec, search_path)
        out[short] = [spec_view(spec), depends, context.get_all_depends(spec.full_name),
                      context.get_file(spec.full_name), genmsg.gentools.compute_md5(context, spec),
                      genmsg.gentools.compute_md5_text(context, spec), genmsg.gentools.compute_full_text(context, spec),
                      gen.compute_full_text_escaped(context, spec),
                      sorted(genmsg.deps.find_msg_dependencies(name, os.path.join(folders["msg"], short + ".msg"),
                                                               search_path))]
    for short in sorted(package["srv"]):
        spec = loader.load_srv_by_type(context, name + "/" + short, {name: [folders["srv"]]})
        loader.load_depends(context, spec, search_path)
        out[short] = [spec_view(spec.request), spec_view(spec.response), genmsg.gentools.compute_md5(context, spec),
                      context.get_file(spec.request.full_name),
                      sorted(genmsg.deps.find_srv_dependencies_with_type(
                          name, os.path.join(folders["srv"], short + ".srv"), search_path))]
    out["missing"] = [attempt(loader.load_msg_by_type, context, name + "/Nope", search_path),
                      attempt(loader.load_msg_by_type, context, "nopkg/Nope", search_path),
                      attempt(loader.load_msg_by_type, context, "x/Y", []),
                      attempt(loader.get_srv_file, name, "Nope", {name: [folders["srv"]]}),
                      attempt(loader.get_msg_file, name, "Header", search_path)]
    out["full_type_name"] = [attempt(genmsg.gentools.compute_full_type_name, name, f)
                             for f in ("A.msg", "B.srv", "C.action")]
    out["includepath"] = genmsg.command_line.includepath_to_dict(
        [name + ":" + folders["msg"], "std_msgs:/usr/share/std_msgs/msg", "empty:", "nocolon", name + ":/x"])
    for type_name in request["generate"]:
        loader.load_depends(context, loader.load_msg_by_type(context, type_name, search_path), search_path)
    out["generator"] = generator_section(request, context, name)
    out["templates"] = templates_section(request, root, folders, name)
    return relative(root, out)


def generator_section(request, context, package):
    out = {}
    for type_name in request["generate"]:
        spec = context.get_registered(type_name)
        flat = gen.flatten(context, spec)
        gen.reset_var()
        lines = {"flatten": [flat.types, flat.names]}
        for numpy in (False, True):
            lines["serialize", numpy] = list(gen.serialize_fn_generator(context, spec, numpy))
            lines["deserialize", numpy] = list(gen.deserialize_fn_generator(context, spec, numpy))
        out[type_name] = {repr(k): v for k, v in lines.items()}
    gen.reset_var()
    calls = []
    for type_, name in request["fields"]:
        for serialize in (True, False):
            gen.push_context("self.")
            calls.append(attempt(lambda t=type_, n=name, s=serialize: list(gen.complex_serializer_generator(
                context, package, t, n, s, False)))[:2])
            gen.pop_context()
    out["complex"] = calls
    gen.push_context("")
    out["direct"] = [list(gen.len_serializer_generator("v", False, True)),
                     list(gen.len_serializer_generator("v", True, False)),
                     list(gen.string_serializer_generator(package, "uint8[4]", "data", True)),
                     list(gen.string_serializer_generator(package, "string", "data", False)),
                     list(gen.array_serializer_generator(context, package, "float64[3]", "xs", False, True)),
                     attempt(lambda: list(gen.array_serializer_generator(context, package, "int32", "x", True,
                                                                        False))),
                     list(gen.simple_serializer_generator(context, context.get_registered(request["generate"][0]),
                                                          0, 2, False)),
                     list(gen.serializer_generator(context, genmsg.MsgSpec([], [], [], "", "p/Empty"), True, False)),
                     [gen.next_var(), gen.next_var()]]
    gen.pop_context()
    out["post"] = [gen.compute_post_deserialize(t, "self.x") for t in ("time", "duration", "Header", "int32")]
    out["registered_ex"] = [attempt(gen.get_registered_ex, context, "no/Such"),
                            attempt(lambda: gen.get_registered_ex(context, "time").full_name)]
    out["indent"] = gen.INDENT
    return out


def templates_section(request, root, folders, name):
    templates = os.path.join(root, "templates")
    os.makedirs(templates, exist_ok=True)
    for file_name, text in request["templates"].items():
        with open(os.path.join(templates, file_name), "w") as f:
            f.write(text)
    outdir = os.path.join(root, "out")
    include = [name + ":" + folders["msg"], "std_msgs:/usr/share/std_msgs/msg",
               "geometry_msgs:/usr/share/geometry_msgs/msg"]
    for kind, short in (("msg", sorted(request["package"]["msg"])[0]), ("srv", sorted(request["package"]["srv"])[0])):
        genmsg.template_tools.generate_from_file(os.path.join(folders[kind], short + "." + kind), name, outdir,
                                                 templates, include, {"msg.em": "@NAME@.txt"},
                                                 {"srv.em": "@NAME@_srv.txt"})
    genmsg.template_tools.generate_module(name, outdir, templates, {"module.em": "module.txt"})
    missing = attempt(genmsg.template_tools.generate_module, name, outdir, templates, {"none.em": "none.txt"})
    produced = {}
    for file_name in sorted(os.listdir(outdir)):
        with open(os.path.join(outdir, file_name)) as f:
            produced[file_name] = f.read()
    return {"files": produced, "missing_template": missing[:2]}


def main():
    request = json.load(sys.stdin)
    with tempfile.TemporaryDirectory() as root:
        answer = {"names": names_section(request), "msgs": msgs_section(request), "loader": loader_section(request),
                  "package": package_section(request, root)}
    json.dump(answer, sys.stdout, default=repr)


if __name__ == "__main__":
    main()
