"""dynamic_reconfigure's exceptions, with upstream's names and hierarchy.

Their own module, importing nothing, so that `import dynamic_reconfigure` (whose package
__init__ re-exports them, as upstream's does) stays as cheap as a message package's.
"""


class DynamicReconfigureException(Exception):
    """dynamic_reconfigure's base exception type."""


class DynamicReconfigureParameterException(DynamicReconfigureException):
    """A change names an unknown parameter or a value that does not convert to its type."""


class DynamicReconfigureCallbackException(DynamicReconfigureException):
    """A server's callback returned no configuration, or a server did not accept a change."""
