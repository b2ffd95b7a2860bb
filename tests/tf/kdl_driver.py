"""Run by Debian's /usr/bin/python3 (real PyKDL and tf_conversions.posemath) and by kame's
interpreter (kame's): evaluates each case's expression on the same inputs.

stdin: [[expression, {name: encoded value}], ...]; stdout: the encoded results. Encoded values:
numbers, strings, lists, ["V", xyz], ["R", 9 row-major], ["F", 12 (rotation rows, then p)],
["Pose", [x y z qx qy qz qw]], ["A", nested list] (a numpy array); an exception is ["error", its
type's name]. Mutating expressions end with the mutated object, e.g. "(v.Normalize(), v)"."""

import json
import sys

import cv2
import numpy

import PyKDL as K
import tf_conversions
import tf_conversions.posemath as pm
from geometry_msgs.msg import Pose


class Cv:
    """cv2 for both posemaths: upstream's calls the old API's Rodrigues2(src, dst), kame's cv2's Rodrigues."""

    Rodrigues = staticmethod(cv2.Rodrigues)

    @staticmethod
    def Rodrigues2(src, dst):
        dst[...] = cv2.Rodrigues(numpy.asarray(src, dtype=numpy.float64))[0]


def decode(value):
    if isinstance(value, list) and value and isinstance(value[0], str):
        kind, data = value
        if kind == "V":
            return K.Vector(*data)
        if kind == "R":
            return K.Rotation(*data)
        if kind == "F":
            return K.Frame(K.Rotation(*data[:9]), K.Vector(*data[9:]))
        if kind == "Pose":
            pose = Pose()
            pose.position.x, pose.position.y, pose.position.z = data[:3]
            o = pose.orientation
            o.x, o.y, o.z, o.w = data[3:]
            return pose
        if kind == "A":
            return numpy.array(data)
    return value


def encode(value):
    if isinstance(value, K.Vector):
        return ["V", [value[i] for i in range(3)]]
    if isinstance(value, K.Rotation):
        return ["R", [value[i, j] for i in range(3) for j in range(3)]]
    if isinstance(value, K.Frame):
        return ["F", [value.M[i, j] for i in range(3) for j in range(3)] + [value.p[i] for i in range(3)]]
    if isinstance(value, Pose):
        p, o = value.position, value.orientation
        return ["Pose", [p.x, p.y, p.z, o.x, o.y, o.z, o.w]]
    if isinstance(value, numpy.ndarray):
        return ["A", value.astype(float).tolist()]
    if isinstance(value, (tuple, list)):
        return [encode(v) for v in value]
    if isinstance(value, (bool, str)) or value is None:
        return value
    return float(value)


out = []
for expression, inputs in json.load(sys.stdin):
    names = {"K": K, "pm": pm, "tc": tf_conversions, "cv": Cv, "numpy": numpy}
    names.update((k, decode(v)) for k, v in inputs.items())
    try:
        out.append(encode(eval(expression, names)))
    except Exception as e:  # the error's kind is a result too: both must raise the same
        out.append(["error", type(e).__name__])
json.dump(out, sys.stdout)
