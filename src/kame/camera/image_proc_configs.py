"""image_proc's dynamic_reconfigure configs (its cfg/Debayer.cfg, Rectify.cfg, CropDecimate.cfg
and Resize.cfg), made with kame.reconfigure's ParameterGenerator as catkin would from the files."""

from __future__ import annotations

from collections.abc import Callable
from types import SimpleNamespace
from typing import Any

from kame.reconfigure.generator import (
    GeneratedConfig,
    ParameterGenerator,
    bool_t,
    collect_generated,
    double_t,
    int_t,
    module_names,
)


def _generate(name: str, add: Callable[[ParameterGenerator], None]) -> SimpleNamespace:
    gen = ParameterGenerator()
    add(gen)
    generated: list[GeneratedConfig] = []
    collect_generated(generated)
    try:
        gen.generate("image_proc", "image_proc", name)
    finally:
        collect_generated(None)
    return SimpleNamespace(**module_names(generated[0]))


def _interpolations(gen: ParameterGenerator) -> Any:
    return gen.enum([gen.const("NN", int_t, 0, "Nearest-neighbor sampling"),
                     gen.const("Linear", int_t, 1, "Bilinear interpolation"),
                     gen.const("Cubic", int_t, 2, "Bicubic interpolation over 4x4 neighborhood"),
                     gen.const("Area", int_t, 3, "Resampling using pixel area relation"),
                     gen.const("Lanczos4", int_t, 4, "Lanczos interpolation over 8x8 neighborhood")],
                    "interpolation type")


def debayer_config() -> SimpleNamespace:
    def add(gen: ParameterGenerator) -> None:
        algorithms = gen.enum([gen.const("Bilinear", int_t, 0, "Fast algorithm using bilinear interpolation"),
                               gen.const("EdgeAware", int_t, 1, "Edge-aware algorithm"),
                               gen.const("EdgeAwareWeighted", int_t, 2, "Weighted edge-aware algorithm"),
                               gen.const("VNG", int_t, 3, "Slow but high quality Variable Number of Gradients "
                                                          "algorithm")],
                              "Debayering algorithm")
        gen.add("debayer", int_t, 0, "Debayering algorithm", 0, 0, 3, edit_method=algorithms)

    return _generate("Debayer", add)


def rectify_config() -> SimpleNamespace:
    def add(gen: ParameterGenerator) -> None:
        gen.add("interpolation", int_t, 0, "Interpolation algorithm between source image pixels", 1, 0, 4,
                edit_method=_interpolations(gen))

    return _generate("Rectify", add)


def crop_decimate_config() -> SimpleNamespace:
    def add(gen: ParameterGenerator) -> None:
        gen.add("decimation_x", int_t, 0, "Number of pixels to decimate to one horizontally", 1, 1, 16)
        gen.add("decimation_y", int_t, 0, "Number of pixels to decimate to one vertically", 1, 1, 16)
        gen.add("x_offset", int_t, 0, "X offset of the region of interest", 0, 0, 2447)
        gen.add("y_offset", int_t, 0, "Y offset of the region of interest", 0, 0, 2049)
        gen.add("width", int_t, 0, "Width of the region of interest", 0, 0, 2448)
        gen.add("height", int_t, 0, "Height of the region of interest", 0, 0, 2050)
        gen.add("interpolation", int_t, 0, "Sampling algorithm", 0, 0, 4, edit_method=_interpolations(gen))

    return _generate("CropDecimate", add)


def resize_config() -> SimpleNamespace:
    def add(gen: ParameterGenerator) -> None:
        gen.add("interpolation", int_t, 0, "Interpolation algorithm between source image pixels", 1, 0, 4,
                edit_method=_interpolations(gen))
        gen.add("use_scale", bool_t, 0, "Flag to use scale instead of static size.", True)
        gen.add("scale_height", double_t, 0, "Scale of height.", 1.0, 0.0, 10.0)
        gen.add("scale_width", double_t, 0, "Scale of width", 1.0, 0.0, 10.0)
        gen.add("height", int_t, 0, "Destination height. Ignored if negative.", -1, -1, 10000)
        gen.add("width", int_t, 0, "Destination width. Ignored if negative.", -1, -1, 10000)

    return _generate("Resize", add)
