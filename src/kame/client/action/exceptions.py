"""ActionException (actionlib's)."""


class ActionException(Exception):
    pass
