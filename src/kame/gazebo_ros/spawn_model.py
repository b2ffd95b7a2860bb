"""gazebo_ros's spawn_model: put a URDF or SDF model into a running gzserver through its services.

    rosrun gazebo_ros spawn_model -urdf|-sdf -file FILE|-param PARAM|-stdin -model NAME
        [-x X -y Y -z Z -R ROLL -P PITCH -Y YAW] [-J JOINT POSITION]... [-reference_frame FRAME]
        [-gazebo_namespace /gazebo] [-robot_namespace NS] [-unpause] [-wait MODEL] [-package_to_model] [-b]

The options, log lines and exit codes of Noetic's script (argparse, single-dash long options):
it calls <gazebo_namespace>/spawn_urdf_model or spawn_sdf_model, then set_model_configuration for
-J, then unpause_physics for -unpause; -b deletes the model again when it is interrupted.
-database (Gazebo's online model database) is refused with a clear error: kame has no network
model database; -file with a model:// folder of GAZEBO_MODEL_PATH does that job.
"""

from __future__ import annotations

import argparse
import math
import os
import re
import sys
import threading
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from typing import Any

from kame.client import core, process, services, topics
from kame.client import log as _log
from kame.tf.transformations import quaternion_from_euler

PACKAGE_URI = re.compile(r'(<mesh\s[^>]*filename\s*=\s*["\'])package://')


def parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(description="Spawn a model in gazebo using the ROS API")
    xmlformat = parser.add_mutually_exclusive_group(required=True)
    xmlformat.add_argument("-urdf", action="store_true", help="Incoming xml is in urdf format")
    xmlformat.add_argument("-sdf", action="store_true", help="Incoming xml is in sdf format")
    source = parser.add_mutually_exclusive_group(required=True)
    source.add_argument("-file", type=str, metavar="FILE_NAME", help="Load model xml from file")
    source.add_argument("-param", type=str, metavar="PARAM_NAME", help="Load model xml from ROS parameter")
    source.add_argument("-database", type=str, metavar="MODEL_NAME",
                        help="Load model XML from specified model in Gazebo Model Database")
    source.add_argument("-stdin", action="store_true", help="Load model from stdin")
    parser.add_argument("-model", required=True, type=str, metavar="MODEL_NAME", help="Name of model to spawn")
    parser.add_argument("-reference_frame", type=str, default="",
                        help='Name of the model/body where initial pose is defined. '
                             'If left empty or specified as "world", gazebo world frame is used')
    parser.add_argument("-gazebo_namespace", type=str, default="/gazebo",
                        help="ROS namespace of gazebo offered ROS interfaces.  Default is /gazebo/")
    parser.add_argument("-robot_namespace", type=str, default=core.get_namespace(),
                        help="change ROS namespace of gazebo-plugins")
    parser.add_argument("-unpause", action="store_true", help="!!!Experimental!!! unpause physics after spawning model")
    parser.add_argument("-wait", type=str, metavar="MODEL_NAME", help="!!!Experimental!!! wait for model to exist")
    for axis, what in (("x", "x component of initial position, meters"),
                       ("y", "y component of initial position, meters"),
                       ("z", "z component of initial position, meters"),
                       ("R", "roll angle of initial orientation, radians"),
                       ("P", "pitch angle of initial orientation, radians"),
                       ("Y", "yaw angle of initial orientation, radians")):
        parser.add_argument(f"-{axis}", type=float, default=0, help=what)
    parser.add_argument("-J", dest="joints", default=[], action="append", metavar=("JOINT_NAME", "JOINT_POSITION"),
                        type=str, nargs=2, help="initialize the specified joint at the specified position")
    parser.add_argument("-package_to_model", action="store_true",
                        help='convert urdf <mesh filename="package://..." to <mesh filename="model://..."')
    parser.add_argument("-b", dest="bond", action="store_true",
                        help="bond to gazebo and delete the model when this program is interrupted")
    return parser


def package_to_model(model_xml: str) -> str:
    """What -package_to_model does to a URDF: mesh file names under package:// become model://."""
    return PACKAGE_URI.sub(r"\1model://", model_xml)


def _read_model(args: argparse.Namespace) -> str | None:
    """The model's XML from its source, or None after the error line the script prints."""
    if args.file:
        _log.emit(_log.INFO, "Loading model XML from file %s", (args.file,))
        if not os.path.exists(args.file):
            _log.emit(_log.FATAL, "Error: specified file %s does not exist", (args.file,))
            return None
        if not os.path.isfile(args.file):
            _log.emit(_log.FATAL, "Error: specified file %s is not a file", (args.file,))
            return None
        try:
            with open(args.file, encoding="utf-8") as f:
                model_xml = f.read()
        except (OSError, UnicodeDecodeError) as exc:
            _log.emit(_log.ERROR, "Error reading file %s: %s", (args.file, exc))
            return None
        if model_xml == "":
            _log.emit(_log.ERROR, "Error: file %s is empty", (args.file,))
            return None
        return model_xml
    if args.param:
        _log.emit(_log.INFO, "Loading model XML from ros parameter %s", (args.param,))
        model_xml = process.get_param(args.param, "")
        if not isinstance(model_xml, str) or model_xml == "":
            _log.emit(_log.ERROR, "Error: param does not exist or is empty", ())
            return None
        return model_xml
    if args.database:
        _log.emit(_log.ERROR, "Error: kame has no Gazebo model database to load %s from: put the model's folder "
                  "on GAZEBO_MODEL_PATH and spawn its model.sdf with -file", (args.database,))
        return None
    _log.emit(_log.INFO, "Loading model XML from stdin", ())
    model_xml = sys.stdin.read()
    if model_xml == "":
        _log.emit(_log.ERROR, "Error: stdin buffer was empty", ())
        return None
    return model_xml


def _call(namespace: str, service: str, service_class: type[Any], *request: Any) -> Any:
    name = f"{namespace}/{service}"
    _log.emit(_log.INFO, "Waiting for service %s", (name,))
    services.wait_for_service(name)
    _log.emit(_log.INFO, "Calling service %s", (name,))
    return services.ServiceProxy(name, service_class)(*request)


def _wait_for_model(args: argparse.Namespace) -> bool:
    """-wait: until the model appears in <gazebo_namespace>/model_states; False at shutdown."""
    from gazebo_msgs.msg import ModelStates

    seen = threading.Event()

    def on_states(states: Any) -> None:
        if args.wait in states.name:
            seen.set()

    subscriber = topics.Subscriber(f"{args.gazebo_namespace}/model_states", ModelStates, on_states)
    _log.emit(_log.INFO, "Waiting for model %s before proceeding.", (args.wait,))
    with core.woken_at_shutdown(seen):
        seen.wait()
    subscriber.unregister()
    return not core.is_shutdown()


def run(args: argparse.Namespace) -> int:
    from gazebo_msgs.srv import DeleteModel, SetModelConfiguration, SpawnModel
    from geometry_msgs.msg import Pose, Quaternion
    from std_srvs.srv import Empty

    if args.wait and not _wait_for_model(args):
        return 0
    model_xml = _read_model(args)
    if model_xml is None:
        return 1
    try:
        ET.fromstring(model_xml)
    except ET.ParseError as exc:
        _log.emit(_log.ERROR, "Invalid XML: %s", (exc,))
        return 1
    if args.package_to_model:
        model_xml = package_to_model(model_xml)
    pose = Pose()
    pose.position.x, pose.position.y, pose.position.z = args.x, args.y, args.z
    pose.orientation = Quaternion(*quaternion_from_euler(args.R, args.P, args.Y))
    service = "spawn_urdf_model" if args.urdf else "spawn_sdf_model"
    try:
        answer = _call(args.gazebo_namespace, service, SpawnModel, args.model, model_xml, args.robot_namespace,
                       pose, args.reference_frame)
        _log.emit(_log.INFO, "Spawn status: %s", (answer.status_message,))
    except services.ServiceException as exc:
        print(f"Service call failed: {exc}")
        answer = None
    if answer is None or not answer.success:
        _log.emit(_log.ERROR, "Spawn service failed. Exiting.", ())
        return 1
    if args.joints:
        names = [joint for joint, _ in args.joints]
        try:
            positions = [float(position) for _, position in args.joints]
            if not all(math.isfinite(p) for p in positions):
                raise ValueError("not finite")
        except ValueError:
            _log.emit(_log.ERROR, "-J takes a joint name and a finite position in radians or metres: %s",
                      (" ".join(f"{n} {p}" for n, p in args.joints),))
            return 1
        try:
            configured = _call(args.gazebo_namespace, "set_model_configuration", SetModelConfiguration,
                               args.model, "", names, positions)
            _log.emit(_log.INFO, "Set model configuration status: %s", (configured.status_message,))
            succeeded = bool(configured.success)
        except services.ServiceException as exc:
            print(f"Service call failed: {exc}")
            succeeded = False
        if not succeeded:
            _log.emit(_log.ERROR, "SetModelConfiguration service failed. Exiting.", ())
            return 1
    if args.unpause:
        _log.emit(_log.INFO, "Unpausing physics", ())
        try:
            services.wait_for_service(f"{args.gazebo_namespace}/unpause_physics")
            services.ServiceProxy(f"{args.gazebo_namespace}/unpause_physics", Empty)()
        except services.ServiceException as exc:
            _log.emit(_log.ERROR, "Unpause physics service call failed: %s", (exc,))
            return 1
    if args.bond:
        def delete_model() -> None:
            _log.emit(_log.INFO, "Deleting model %s", (args.model,))
            try:
                services.ServiceProxy(f"{args.gazebo_namespace}/delete_model", DeleteModel)(args.model)
            except services.ServiceException as exc:
                _log.emit(_log.ERROR, "Delete model service call failed: %s", (exc,))

        core.on_shutdown(delete_model)
        _log.emit(_log.INFO, "Waiting for shutdown to delete model %s", (args.model,))
        core.spin()
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    args = parser().parse_args(process.myargv(argv)[1:])
    process.init_node(f"spawn_{args.model}", argv=argv, anonymous=True)
    try:
        return run(args)
    except KeyboardInterrupt:
        return 0
    finally:
        core.signal_shutdown("spawn_model done")
