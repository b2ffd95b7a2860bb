"""actionlib's exception."""


class ActionException(Exception):
    pass
