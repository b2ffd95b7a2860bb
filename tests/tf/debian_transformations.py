"""Run under Debian's /usr/bin/python3: evaluates a JSON batch of tf.transformations calls (its
arcball_drag is imported by the test too, where `tf` is kame's).

stdin: [[function, args, kwargs], ...]; stdout: [result or {"error": type name}, ...], where
numpy arrays become nested lists and tuples lists.
"""

import json
import sys

import numpy

from tf import transformations


def plain(value):
    if isinstance(value, numpy.ndarray):
        return value.tolist()
    if isinstance(value, (tuple, list)):
        return [plain(v) for v in value]
    if isinstance(value, (numpy.floating, numpy.integer, numpy.bool_)):
        return value.item()
    return value


def arcball_drag(initial, center, radius, axes, constrain, down, drag, accelerations):
    """An Arcball driven as a viewer drives it: the matrices after a drag and after each next()."""
    ball = transformations.Arcball(initial)
    ball.place(center, radius)
    if axes:
        ball.setaxes(*axes)
    ball.setconstrain(constrain)
    ball.down(down)
    ball.drag(drag)
    matrices = [ball.matrix()]
    for acceleration in accelerations:
        ball.next(acceleration)
        matrices.append(ball.matrix())
    return matrices


def call(name, args, kwargs):
    try:
        if name == "Arcball":
            return plain(arcball_drag(*args))
        return plain(getattr(transformations, name)(*args, **kwargs))
    except Exception as exc:  # the type is compared
        return {"error": type(exc).__name__}


if __name__ == "__main__":
    json.dump([call(*item) for item in json.load(sys.stdin)], sys.stdout)
