"""genpy.genpy_main: the command line of genpy's generator scripts (genmsg_py.py and gensrv_py.py
call genmain with a MsgGenerator or SrvGenerator): `-p PKG -o OUTDIR -I pkg:dir ... FILES`, or
`--initpy -o OUTDIR` for the folder's __init__.py."""

from __future__ import annotations

import os
import sys
import traceback
from collections.abc import Iterable, Mapping, Sequence
from optparse import OptionParser
from typing import Protocol

import genmsg
import genmsg.command_line
from genmsg import MsgGenerationException
from genpy.generate_initpy import write_modules

__all__ = ["MsgGenerationException", "genmain", "usage", "write_modules"]


class _Generator(Protocol):
    def generate_messages(self, package: str, package_files: Iterable[str], outdir: str,
                          search_path: Mapping[str, Iterable[str]]) -> int: ...


def usage(progname: str) -> None:
    print(f"{progname} file(s)")


def genmain(argv: Sequence[str], progname: str, gen: _Generator) -> None:
    """Run the generator on argv[1:] and exit: 0, 1 for a definition that cannot be parsed (or a
    failed file), 2 for one that cannot be generated, 3 for anything else (with its traceback)."""
    parser = OptionParser(f"{progname} file")
    parser.add_option("--initpy", dest="initpy", action="store_true", default=False)
    parser.add_option("-p", dest="package")
    parser.add_option("-o", dest="outdir")
    parser.add_option("-I", dest="includepath", action="append")
    options, args = parser.parse_args(list(argv))
    try:
        if options.initpy:
            if not options.outdir:
                parser.error("Missing args")
            retcode = write_modules(options.outdir)
        else:
            if len(args) < 2:
                parser.error("please specify args")
            # several generators may run at once: another may make the folder first
            os.makedirs(options.outdir, exist_ok=True)
            search_path = genmsg.command_line.includepath_to_dict(options.includepath)
            retcode = gen.generate_messages(options.package, args[1:], options.outdir, search_path)
    except genmsg.InvalidMsgSpec as e:
        print("ERROR: ", e, file=sys.stderr)
        retcode = 1
    except MsgGenerationException as e:
        print("ERROR: ", e, file=sys.stderr)
        retcode = 2
    except Exception as e:  # genpy's last resort: the traceback, then code 3
        traceback.print_exc()
        print("ERROR: ", e)
        retcode = 3
    sys.exit(retcode or 0)
