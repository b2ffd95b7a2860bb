"""dynamic_reconfigure.encoding: the config codec (kame.reconfigure.encoding)."""

from kame.reconfigure.encoding import (
    Config,
    decode_config,
    decode_description,
    encode_config,
    encode_description,
    extract_params,
    get_tree,
    group_dict,
    initial_config,
)

__all__ = ["Config", "decode_config", "decode_description", "encode_config", "encode_description",
           "extract_params", "get_tree", "group_dict", "initial_config"]
