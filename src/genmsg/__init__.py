"""genmsg, as genpy's generator and catkin's build scripts import it: message and service specs,
their loading along a search path, md5sums and definition texts. The definitions are parsed by
kame's parser (kame.msg.parser) and the md5sums and texts computed by kame.msg.md5, so a spec
genmsg loads means what kame's own message classes mean."""

from genmsg import base, command_line, gentools, msg_loader, msgs, names, srvs
from genmsg.base import (
    EXT_MSG,
    EXT_SRV,
    MSG_DIR,
    SEP,
    SRV_DIR,
    InvalidMsgSpec,
    MsgGenerationException,
    log,
    log_verbose,
    plog,
)
from genmsg.gentools import compute_full_text, compute_md5, compute_md5_text
from genmsg.msg_loader import MsgContext, MsgNotFound, load_depends, load_msg_by_type, load_srv_by_type
from genmsg.msgs import DURATION, HEADER, TIME, Constant, Field, MsgSpec
from genmsg.names import (
    is_legal_resource_base_name,
    is_legal_resource_name,
    package_resource_name,
    resource_name,
    resource_name_base,
    resource_name_package,
)
from genmsg.srvs import SrvSpec

__all__ = ["DURATION", "EXT_MSG", "EXT_SRV", "HEADER", "MSG_DIR", "SEP", "SRV_DIR", "TIME", "Constant", "Field",
           "InvalidMsgSpec", "MsgContext", "MsgGenerationException", "MsgNotFound", "MsgSpec", "SrvSpec", "base",
           "command_line", "compute_full_text", "compute_md5", "compute_md5_text", "gentools",
           "is_legal_resource_base_name", "is_legal_resource_name", "load_depends", "load_msg_by_type",
           "load_srv_by_type", "log", "log_verbose", "msg_loader", "msgs", "names", "package_resource_name", "plog",
           "resource_name", "resource_name_base", "resource_name_package", "srvs"]
