"""dynamic_reconfigure.parameter_generator_catkin as .cfg files import it (kame.reconfigure.generator)."""

from kame.reconfigure.generator import ParameterGenerator, bool_t, double_t, int_t, str_t

__all__ = ["ParameterGenerator", "bool_t", "double_t", "int_t", "str_t"]
