"""dynamic_reconfigure.parameter_generator_catkin as .cfg files import it (kame.reconfigure.generator;
its ParameterGenerator from kame.catkin.reconfigure_files, which writes catkin's files when the
.cfg is run with catkin's arguments)."""

from kame.catkin.reconfigure_files import ParameterGenerator
from kame.reconfigure.generator import bool_t, double_t, int_t, str_t

__all__ = ["ParameterGenerator", "bool_t", "double_t", "int_t", "str_t"]
