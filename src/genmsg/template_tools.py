"""genmsg.template_tools: a language's message, service and module files written from its empy
templates (gencpp's, geneus', ... generator scripts call generate_from_command_line_options).

empy 3 (kame's `genmsg` extra) runs the templates, as in ROS; the generators' templates are
written for its API, which empy 4 changed.
"""

from __future__ import annotations

import errno
import os
import sys
from collections.abc import Mapping, Sequence
from optparse import OptionParser
from typing import Any

from genmsg import command_line, gentools, msg_loader
from genmsg.msg_loader import MsgContext, SearchPath
from genmsg.msgs import MsgSpec
from genmsg.srvs import SrvSpec

__all__ = ["generate_from_command_line_options", "generate_from_file", "generate_module"]

TemplateMap = Mapping[str, str]


def _empy() -> Any:
    try:
        import em
    except ImportError as exc:
        raise ImportError("genmsg's templates need empy 3: pip install 'kame[genmsg]' (empy>=3.3.4,<4)") from exc
    return em


def _expand(template_dir: str, template_file_name: str, output_file: str, globals_: dict[str, Any]) -> None:
    """Write `output_file` from the template; RuntimeError (and no output file) if there is none."""
    em = _empy()
    template_file = os.path.join(template_dir, template_file_name)
    if not os.path.isfile(template_file):
        raise RuntimeError(f"Template file {template_file_name} not found in template dir {template_dir}")
    with open(output_file, "w") as ofile, open(template_file) as template:
        interpreter = em.Interpreter(output=ofile, globals=globals_, options={em.RAW_OPT: True, em.BUFFERED_OPT: True})
        try:
            interpreter.file(template)
        finally:
            interpreter.shutdown()


def _generate_from_spec(input_file: str, output_dir: str, template_dir: str, msg_context: MsgContext,
                        spec: MsgSpec | SrvSpec, template_map: TemplateMap, search_path: SearchPath) -> None:
    md5sum = gentools.compute_md5(msg_context, spec)
    for template_file_name, output_file_name in template_map.items():
        output_file = os.path.join(output_dir, output_file_name.replace("@NAME@", spec.short_name))
        globals_: dict[str, Any] = {"file_name_in": input_file, "spec": spec, "md5sum": md5sum,
                                    "search_path": search_path, "msg_context": msg_context}
        if isinstance(spec, MsgSpec):
            globals_["msg_definition"] = gentools.compute_full_text(msg_context, spec)
        _expand(template_dir, template_file_name, output_file, globals_)


def _load(input_file: str, package_name: str, search_path: SearchPath) -> tuple[MsgContext, MsgSpec | SrvSpec]:
    msg_context = MsgContext.create_default()
    full_type_name = gentools.compute_full_type_name(package_name, os.path.basename(input_file))
    spec: MsgSpec | SrvSpec
    if input_file.endswith(".msg"):
        spec = msg_loader.load_msg_from_file(msg_context, input_file, full_type_name)
    else:
        spec = msg_loader.load_srv_from_file(msg_context, input_file, full_type_name)
    msg_loader.load_depends(msg_context, spec, search_path)
    return msg_context, spec


def generate_from_file(input_file: str, package_name: str, output_dir: str, template_dir: str,
                       include_path: Sequence[str] | None, msg_template_dict: TemplateMap,
                       srv_template_dict: TemplateMap) -> None:
    """The files of one .msg (msg templates), or of one .srv (srv templates for the service, msg
    templates for its request and response), in `output_dir`; `include_path` as -I gives it."""
    input_file = os.path.abspath(input_file)
    output_dir = os.path.abspath(output_dir)
    try:
        os.makedirs(output_dir)
    except OSError as e:
        if e.errno != errno.EEXIST:
            raise
    search_path = command_line.includepath_to_dict(include_path) if include_path else {}
    if not input_file.endswith((".msg", ".srv")):
        raise ValueError(f"Unknown file extension for {input_file}")
    msg_context, spec = _load(input_file, package_name, search_path)
    if isinstance(spec, MsgSpec):
        _generate_from_spec(input_file, output_dir, template_dir, msg_context, spec, msg_template_dict, search_path)
        return
    _generate_from_spec(input_file, output_dir, template_dir, msg_context, spec, srv_template_dict, search_path)
    for half in (spec.request, spec.response):
        _generate_from_spec(input_file, output_dir, template_dir, msg_context, half, msg_template_dict, search_path)


def generate_module(package_name: str, output_dir: str, template_dir: str, template_dict: TemplateMap) -> None:
    """The package's module files (an __init__ listing the generated files, ...) from templates
    given `files` (output_dir's listing) and `package`."""
    files = os.listdir(output_dir)
    for template_file_name, output_file_name in template_dict.items():
        _expand(template_dir, template_file_name, os.path.join(output_dir, output_file_name),
                {"files": files, "package": package_name})


def generate_from_command_line_options(argv: Sequence[str], msg_template_dict: TemplateMap,
                                       srv_template_dict: TemplateMap,
                                       module_template_dict: TemplateMap | None = None) -> None:
    """A generator script's main: `-p PKG -o OUTDIR -e TEMPLATEDIR [-I pkg:dir]... FILE`, or -m
    for the module files; exits with its usage when an option is missing."""
    parser = OptionParser("[options] <srv file>")
    parser.add_option("-p", dest="package", help="ros package the generated msg/srv files belongs to")
    parser.add_option("-o", dest="outdir", help="directory in which to place output files")
    parser.add_option("-I", dest="includepath", help="include path to search for messages", action="append")
    parser.add_option("-m", dest="module", help="write the module file", action="store_true", default=False)
    parser.add_option("-e", dest="emdir", help="directory containing template files", default=sys.path[0])
    options, args = parser.parse_args(list(argv))
    if not options.package or not options.outdir or not options.emdir:
        parser.print_help()
        sys.exit(-1)
    if options.module:
        generate_module(options.package, options.outdir, options.emdir, module_template_dict or {})
    elif len(args) > 1:
        generate_from_file(args[1], options.package, options.outdir, options.emdir, options.includepath,
                           msg_template_dict, srv_template_dict)
    else:
        parser.print_help()
        sys.exit(-1)
