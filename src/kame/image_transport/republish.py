"""image_transport's republish: `rosrun image_transport republish raw in:=/camera/image_raw compressed
out:=/camera/image_repub`.

As image_transport names them, a base topic's raw transport is the topic itself
(sensor_msgs/Image) and its compressed transport `<base>/compressed` (CompressedImage). The
node subscribes to `in`'s transport `in_transport` and publishes on `out` in `out_transport`, or
in every transport it has when none is given. The compressed publisher's parameters live under
`<out>/compressed` (format, jpeg_quality, png_level...), read at start and changed while it runs
through the dynamic_reconfigure server there, as compressed_image_transport's. A message is
decoded and encoded only while someone subscribes to an output, once for all of its subscribers.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from types import SimpleNamespace
from typing import Any

from kame.client import log
from kame.client.core import resolve_name
from kame.client.process import init_node, myargv, spin
from kame.client.topics import Publisher, SubscribeListener, Subscriber
from kame.image_transport.compressed import CompressionError, Settings, compress, decompress, default_codec
from kame.reconfigure.generator import (
    GeneratedConfig,
    ParameterGenerator,
    bool_t,
    collect_generated,
    int_t,
    module_names,
    str_t,
)
from kame.reconfigure.server import Server
from sensor_msgs.msg import CompressedImage, Image

USAGE = "Usage: %s in_transport in:=<in_base_topic> [out_transport] out:=<out_base_topic>\n"
TRANSPORTS = ("raw", "compressed")


def publisher_config() -> SimpleNamespace:
    """compressed_image_transport's CompressedPublisherConfig (its cfg/CompressedPublisher.cfg)."""
    gen = ParameterGenerator()
    formats = gen.enum([gen.const("jpeg", str_t, "jpeg", "JPEG lossy compression"),
                        gen.const("png", str_t, "png", "PNG lossless compression")],
                       "Enum to set the compression format")
    gen.add("format", str_t, 0, "Compression format", "jpeg", edit_method=formats)
    gen.add("jpeg_quality", int_t, 0, "JPEG quality percentile", 80, 1, 100)
    gen.add("jpeg_progressive", bool_t, 0, "Enable compression to progressive JPEG", False)
    gen.add("jpeg_optimize", bool_t, 0, "Enable JPEG compress optimization", False)
    gen.add("jpeg_restart_interval", int_t, 0, "JPEG restart interval", 0, 0, 65535)
    gen.add("png_level", int_t, 0, "PNG compression level", 9, 1, 9)
    generated: list[GeneratedConfig] = []
    collect_generated(generated)
    try:
        gen.generate("compressed_image_transport", "CompressedPublisher", "CompressedPublisher")
    finally:
        collect_generated(None)
    return SimpleNamespace(**module_names(generated[0]))


@dataclass
class Output:
    """One transport of the out topic: its publisher and how an Image becomes its message."""

    publisher: Publisher
    convert: Callable[[Any], Any]


class CompressedOutput:
    def __init__(self, base_topic: str, listener: SubscribeListener | None = None) -> None:
        self.settings = Settings()
        self.publisher = Publisher(base_topic + "/compressed", CompressedImage, subscriber_listener=listener,
                                   queue_size=1)
        self.server = Server(publisher_config(), self._configure, base_topic + "/compressed")

    def _configure(self, config: Any, _level: int) -> Any:
        self.settings = Settings(format=config["format"], jpeg_quality=config["jpeg_quality"],
                                 jpeg_progressive=config["jpeg_progressive"], jpeg_optimize=config["jpeg_optimize"],
                                 jpeg_restart_interval=config["jpeg_restart_interval"], png_level=config["png_level"])
        return config

    def convert(self, image: Any) -> Any:
        return compress(image, self.settings)


def _output(transport: str, base_topic: str) -> Output:
    if transport == "raw":
        return Output(Publisher(base_topic, Image, queue_size=1), lambda image: image)
    compressed = CompressedOutput(base_topic)
    return Output(compressed.publisher, compressed.convert)


class Republisher:
    def __init__(self, in_topic: str, in_transport: str, outputs: list[Output]) -> None:
        self.outputs = outputs
        self.decode: Callable[[Any], Any] = decompress if in_transport == "compressed" else lambda image: image
        in_type = CompressedImage if in_transport == "compressed" else Image
        self.subscriber = Subscriber(in_topic + ("/compressed" if in_type is CompressedImage else ""), in_type,
                                     self._republish, queue_size=1)

    def _republish(self, message: Any) -> None:
        wanted = [output for output in self.outputs if output.publisher.get_num_connections()]
        if not wanted:
            return
        try:
            image = self.decode(message)
        except CompressionError as exc:
            log.emit(log.ERROR, "%s", (exc,))
            return
        for output in wanted:  # one transport's refusal does not hold back the others
            try:
                output.publisher.publish(output.convert(image))
            except CompressionError as exc:
                log.emit(log.ERROR, "%s", (exc,))


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    args = myargv(argv)
    if len(args) < 2:
        sys.stdout.write(USAGE % args[0])
        return 0
    for transport in args[1:3]:
        if transport not in TRANSPORTS:
            sys.stderr.write(f"Unable to load plugin for transport '{transport}': kame's image_transport has "
                             f"{' and '.join(TRANSPORTS)}\n")
            return 1
    out_transports = args[2:3] or list(TRANSPORTS)
    if "compressed" in (args[1], *out_transports):
        try:
            default_codec()
        except CompressionError as exc:
            sys.stderr.write(f"{exc}\n")
            return 1
    init_node("image_republisher", argv, anonymous=True)
    out_topic = resolve_name("out")
    outputs = [_output(transport, out_topic) for transport in out_transports]
    Republisher(resolve_name("in"), args[1], outputs)
    spin()
    return 0
