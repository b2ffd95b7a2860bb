"""gazebo_ros's ROS API (gazebo_ros_api_plugin) on kame: the /gazebo services and topics.

Services (std_srvs/Empty or gazebo_msgs), answered as gazebo_ros 2.9 answers them, status messages
and log lines in its words: spawn_urdf_model, spawn_sdf_model, delete_model, get/set_model_state,
get/set_link_state, get_world_properties, get_model_properties, get_link_properties,
get_joint_properties, get/set_physics_properties, pause_physics, unpause_physics,
reset_simulation, reset_world, apply_body_wrench, apply_joint_effort, clear_joint_forces,
clear_body_wrenches, set_model_configuration, get_light_properties, set_light_properties.
Topics: model_states and link_states (gazebo_msgs, in the world frame, each step while someone
listens, at most every MIN_STATES_PERIOD of simulated time), set_model_state and set_link_state in.
A request with NaN or infinity in a pose, twist, wrench or time is refused with a status message
saying which; nothing a request carries stops the server.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

from kame.client import log as _log
from kame.client import services, topics
from kame.gazebo import description as d
from kame.gazebo.errors import GazeboError
from kame.gazebo.poses import Pose
from kame.gazebo.states import State
from kame.gazebo_ros import relative
from kame.gazebo_ros.conversions import (
    finite,
    finite_pose,
    finite_twist,
    pose_msg,
    pose_of,
    seconds,
    stamp,
    twist_msg,
    vector_msg,
    vector_of,
)
from kame.gazebo_ros.models import ModelFactory, SpawnRefused
from kame.gazebo_ros.simulation import Simulation

MIN_STATES_PERIOD = 0.01  # seconds of simulated time between two model_states (and link_states)
JOINT_TYPES = {"revolute": 0, "continuous": 1, "prismatic": 2, "fixed": 3, "ball": 4, "universal": 5}


def _error(text: str, *args: Any) -> None:
    _log.emit(_log.ERROR, text, args)


class GazeboApi:
    """The services and topics of /gazebo over one Simulation."""

    def __init__(self, sim: Simulation, factory: ModelFactory) -> None:
        from gazebo_msgs.msg import LinkState, LinkStates, ModelState, ModelStates

        self.sim = sim
        self.factory = factory
        self._get_model_state_count: dict[str, int] = {}
        self._states_published = -math.inf
        self.model_states = topics.Publisher("~model_states", ModelStates, queue_size=10)
        self.link_states = topics.Publisher("~link_states", LinkStates, queue_size=10)
        self._inputs = [topics.Subscriber("~set_model_state", ModelState, self._on_model_state, queue_size=10),
                        topics.Subscriber("~set_link_state", LinkState, self._on_link_state, queue_size=10)]
        self._services = self._advertise()
        sim.add_listener(self._publish_states)

    def _advertise(self) -> list[services.Service]:
        from gazebo_msgs import srv
        from std_srvs.srv import Empty

        table: list[tuple[str, type[Any], Any]] = [
            ("spawn_urdf_model", srv.SpawnModel, self.spawn_urdf_model),
            ("spawn_sdf_model", srv.SpawnModel, self.spawn_sdf_model),
            ("delete_model", srv.DeleteModel, self.delete_model),
            ("get_model_properties", srv.GetModelProperties, self.get_model_properties),
            ("get_model_state", srv.GetModelState, self.get_model_state),
            ("get_world_properties", srv.GetWorldProperties, self.get_world_properties),
            ("get_joint_properties", srv.GetJointProperties, self.get_joint_properties),
            ("get_link_properties", srv.GetLinkProperties, self.get_link_properties),
            ("get_link_state", srv.GetLinkState, self.get_link_state),
            ("get_light_properties", srv.GetLightProperties, self.get_light_properties),
            ("set_light_properties", srv.SetLightProperties, self.set_light_properties),
            ("get_physics_properties", srv.GetPhysicsProperties, self.get_physics_properties),
            ("set_physics_properties", srv.SetPhysicsProperties, self.set_physics_properties),
            ("set_model_state", srv.SetModelState, self.set_model_state),
            ("set_model_configuration", srv.SetModelConfiguration, self.set_model_configuration),
            ("set_link_state", srv.SetLinkState, self.set_link_state),
            ("set_link_properties", srv.SetLinkProperties, self.set_link_properties),
            ("set_joint_properties", srv.SetJointProperties, self.set_joint_properties),
            ("apply_body_wrench", srv.ApplyBodyWrench, self.apply_body_wrench),
            ("apply_joint_effort", srv.ApplyJointEffort, self.apply_joint_effort),
            ("clear_joint_forces", srv.JointRequest, self.clear_joint_forces),
            ("clear_body_wrenches", srv.BodyRequest, self.clear_body_wrenches),
            ("pause_physics", Empty, self.pause_physics),
            ("unpause_physics", Empty, self.unpause_physics),
            ("reset_simulation", Empty, self.reset_simulation),
            ("reset_world", Empty, self.reset_world),
        ]
        return [services.Service(f"~{name}", kind, handler) for name, kind, handler in table]

    def close(self) -> None:
        self.sim.remove_listener(self._publish_states)
        for service in self._services:
            service.shutdown()
        for subscriber in self._inputs:
            subscriber.unregister()
        self.model_states.unregister()
        self.link_states.unregister()

    # ------------------------------------------------------------------ topics

    def _publish_states(self, now: float) -> None:
        """After a step, with the world locked."""
        from gazebo_msgs.msg import LinkStates, ModelStates

        if now - self._states_published < MIN_STATES_PERIOD and now >= self._states_published:
            return
        self._states_published = now
        world = self.sim.world
        if self.model_states.get_num_connections() > 0:
            models = world.model_states()
            self.model_states.publish(ModelStates(list(models), [pose_msg(s.pose) for s in models.values()],
                                                  [twist_msg(s.linear, s.angular) for s in models.values()]))
        if self.link_states.get_num_connections() > 0:
            links = world.link_states()
            self.link_states.publish(LinkStates(list(links), [pose_msg(s.pose) for s in links.values()],
                                                [twist_msg(s.linear, s.angular) for s in links.values()]))

    def _on_model_state(self, msg: Any) -> None:
        from gazebo_msgs.srv import SetModelStateRequest

        self.set_model_state(SetModelStateRequest(msg))

    def _on_link_state(self, msg: Any) -> None:
        from gazebo_msgs.srv import SetLinkStateRequest

        self.set_link_state(SetLinkStateRequest(msg))

    # ------------------------------------------------------------------ spawn and delete

    def spawn_urdf_model(self, req: Any) -> Any:
        return self._spawn(req, "urdf")

    def spawn_sdf_model(self, req: Any) -> Any:
        return self._spawn(req, "sdf")

    def _spawn(self, req: Any, service_kind: str) -> Any:
        from gazebo_msgs.srv import SpawnModelResponse

        if not finite_pose(req.initial_pose):
            return SpawnModelResponse(False, "SpawnModel: Failure - initial_pose must be finite (no NaN or infinity)")
        initial = Pose(vector_of(req.initial_pose.position),
                       relative.normalized(pose_of(req.initial_pose).orientation))
        with self.sim.lock:
            world = self.sim.world
            if not relative.is_inertial(req.reference_frame):
                frame = self._entity_state(req.reference_frame)
                if frame is None:
                    return SpawnModelResponse(False, "SpawnModel: reference reference_frame not found, "
                                                     "did you forget to scope the link by model name?")
                initial = relative.carried_into_world(initial, frame.pose)
            if req.model_name in world.model_names():
                _error("SpawnModel: Failure - model name %s already exist.", req.model_name)
                return SpawnModelResponse(False, "SpawnModel: Failure - entity already exists.")
            try:
                self.factory.spawn(req.model_xml, req.model_name, initial, req.robot_namespace, service_kind)
            except SpawnRefused as exc:
                _error("%s", exc)
                return SpawnModelResponse(False, str(exc))
            except GazeboError as exc:
                _error("SpawnModel: Failure - %s", exc)
                return SpawnModelResponse(False, f"SpawnModel: Failure - {exc}")
        return SpawnModelResponse(True, "SpawnModel: Successfully spawned entity")

    def delete_model(self, req: Any) -> Any:
        from gazebo_msgs.srv import DeleteModelResponse

        with self.sim.lock:
            if req.model_name not in self.sim.world.model_names():
                _error("DeleteModel: model [%s] does not exist", req.model_name)
                return DeleteModelResponse(False, "DeleteModel: model does not exist")
            self.factory.delete(req.model_name)
        return DeleteModelResponse(True, "DeleteModel: successfully deleted model")

    # ------------------------------------------------------------------ states

    def _entity_state(self, name: str) -> State | None:
        """A model's or link's state (gazebo_ros's GetEntity: a model name or a scoped link name)."""
        world = self.sim.world
        if name in world.model_names():
            return world.model_state(name)
        try:
            return world.link_state(name)
        except GazeboError:
            return None

    def get_model_state(self, req: Any) -> Any:
        from gazebo_msgs.srv import GetModelStateResponse

        res = GetModelStateResponse()
        with self.sim.lock:
            world = self.sim.world
            if req.model_name not in world.model_names():
                _error("GetModelState: model [%s] does not exist", req.model_name)
                res.success, res.status_message = False, "GetModelState: model does not exist"
                return res
            count = self._get_model_state_count.get(req.model_name, 0) + 1
            self._get_model_state_count[req.model_name] = count
            res.header.seq = count
            res.header.stamp = stamp(world.sim_time)
            res.header.frame_id = req.relative_entity_name
            state = world.model_state(req.model_name)
            frame = None if relative.is_inertial(req.relative_entity_name) else self._entity_state(
                req.relative_entity_name)
        if not relative.is_inertial(req.relative_entity_name):
            if frame is None:
                res.success = False
                res.status_message = ("GetModelState: reference relative_entity_name not found, "
                                      "did you forget to scope the body by model name?")
                return res
            state = _seen_from(state, frame)
        res.pose = pose_msg(state.pose)
        res.twist = twist_msg(state.linear, state.angular)
        res.success, res.status_message = True, "GetModelState: got properties"
        return res

    def set_model_state(self, req: Any) -> Any:
        from gazebo_msgs.srv import SetModelStateResponse

        given = req.model_state
        if not (finite_pose(given.pose) and finite_twist(given.twist)):
            _error("Updating ModelState: model [%s]: the pose and twist must be finite (no NaN or infinity)",
                   given.model_name)
            return SetModelStateResponse(False, "SetModelState: pose and twist must be finite")
        target = State(Pose(vector_of(given.pose.position), relative.normalized(pose_of(given.pose).orientation)),
                       vector_of(given.twist.linear), vector_of(given.twist.angular))
        with self.sim.lock:
            world = self.sim.world
            if given.model_name not in world.model_names():
                _error("Updating ModelState: model [%s] does not exist", given.model_name)
                return SetModelStateResponse(False, "SetModelState: model does not exist")
            if not relative.is_inertial(given.reference_frame):
                frame = self._entity_state(given.reference_frame)
                if frame is None:
                    _error("Updating ModelState: for model[%s], specified reference frame entity [%s] does not exist",
                           given.model_name, given.reference_frame)
                    return SetModelStateResponse(False,
                                                 "SetModelState: specified reference frame entity does not exist")
                target = State(relative.carried_into_world(target.pose, frame.pose),
                               relative.rotate(frame.pose, target.linear), relative.rotate(frame.pose, target.angular))
            world.set_model_state(given.model_name, target)
        return SetModelStateResponse(True, "SetModelState: set model state done")

    def get_link_state(self, req: Any) -> Any:
        from gazebo_msgs.msg import LinkState
        from gazebo_msgs.srv import GetLinkStateResponse

        with self.sim.lock:
            state = self._entity_state(req.link_name) if "::" in req.link_name else None
            frame = None if relative.is_inertial(req.reference_frame) else self._entity_state(req.reference_frame)
        if state is None:
            return GetLinkStateResponse(LinkState(), False, "GetLinkState: link not found, "
                                                            "did you forget to scope the link by model name?")
        if not relative.is_inertial(req.reference_frame):
            if frame is None:
                return GetLinkStateResponse(LinkState(), False, "GetLinkState: reference reference_frame not found, "
                                                                "did you forget to scope the link by model name?")
            state = _seen_from(state, frame)
        link_state = LinkState(req.link_name, pose_msg(state.pose), twist_msg(state.linear, state.angular),
                               req.reference_frame)
        return GetLinkStateResponse(link_state, True, "GetLinkState: got state")

    def set_link_state(self, req: Any) -> Any:
        from gazebo_msgs.srv import SetLinkStateResponse

        given = req.link_state
        if not (finite_pose(given.pose) and finite_twist(given.twist)):
            _error("Updating LinkState: link [%s]: the pose and twist must be finite (no NaN or infinity)",
                   given.link_name)
            return SetLinkStateResponse(False, "SetLinkState: pose and twist must be finite")
        target = State(Pose(vector_of(given.pose.position), relative.normalized(pose_of(given.pose).orientation)),
                       vector_of(given.twist.linear), vector_of(given.twist.angular))
        with self.sim.lock:
            world = self.sim.world
            if "::" not in given.link_name or self._entity_state(given.link_name) is None:
                _error("Updating LinkState: link [%s] does not exist", given.link_name)
                return SetLinkStateResponse(False, "SetLinkState: link does not exist")
            if not relative.is_inertial(given.reference_frame):
                frame = self._entity_state(given.reference_frame)
                if frame is None:
                    _error("Updating LinkState: reference_frame is not a valid entity name")
                    return SetLinkStateResponse(False, "SetLinkState: failed")
                target = State(relative.carried_into_world(target.pose, frame.pose),
                               _plus(relative.rotate(frame.pose, target.linear), frame.linear),
                               _plus(relative.rotate(frame.pose, target.angular), frame.angular))
            try:
                world.set_link_state(given.link_name, target)
            except GazeboError as exc:
                _error("Updating LinkState: %s", exc)
                return SetLinkStateResponse(False, f"SetLinkState: {exc}")
        return SetLinkStateResponse(True, "SetLinkState: success")

    # ------------------------------------------------------------------ properties

    def get_world_properties(self, _req: Any) -> Any:
        from gazebo_msgs.srv import GetWorldPropertiesResponse

        with self.sim.lock:
            return GetWorldPropertiesResponse(self.sim.world.sim_time, self.sim.world.model_names(), True, True,
                                              "GetWorldProperties: got properties")

    def _model(self, name: str) -> d.Model | None:
        world = self.sim.world
        return world.model_description(name) if name in world.model_names() else None

    def get_model_properties(self, req: Any) -> Any:
        from gazebo_msgs.srv import GetModelPropertiesResponse

        with self.sim.lock:
            model = self._model(req.model_name)
        if model is None:
            _error("GetModelProperties: model [%s] does not exist", req.model_name)
            return GetModelPropertiesResponse(success=False, status_message="GetModelProperties: model does not exist")
        return GetModelPropertiesResponse(
            parent_model_name="", canonical_body_name=model.links[0].name if model.links else "",
            body_names=[link.name for link in model.links],
            geom_names=[c.name for link in model.links for c in link.collisions],
            joint_names=[joint.name for joint in model.joints], child_model_names=[], is_static=model.static,
            success=True, status_message="GetModelProperties: got properties")

    def get_link_properties(self, req: Any) -> Any:
        from gazebo_msgs.srv import GetLinkPropertiesResponse

        model_name, _, link_name = req.link_name.rpartition("::")
        with self.sim.lock:
            model = self._model(model_name)
        link = model.link(link_name) if model is not None else None
        if link is None:
            return GetLinkPropertiesResponse(
                success=False,
                status_message="GetLinkProperties: link not found, did you forget to scope the link by model name?")
        inertial = link.inertial
        return GetLinkPropertiesResponse(
            com=pose_msg(Pose(inertial.pose.position)), gravity_mode=link.gravity, mass=inertial.mass,
            ixx=inertial.ixx, ixy=inertial.ixy, ixz=inertial.ixz, iyy=inertial.iyy, iyz=inertial.iyz,
            izz=inertial.izz, success=True, status_message="GetLinkProperties: got properties")

    def set_link_properties(self, req: Any) -> Any:
        from gazebo_msgs.srv import SetLinkPropertiesResponse

        return SetLinkPropertiesResponse(False, "SetLinkProperties: changing a link's mass and inertia while the "
                                                "world runs is not available in kame")

    def _scoped_joint(self, name: str) -> str | None:
        """gazebo_ros's joint lookup: a scoped name, or the first model with a joint of that name."""
        world = self.sim.world
        if "::" in name:
            model, _, local = name.rpartition("::")
            found = self._model(model)
            return name if found is not None and any(j.name == local for j in found.joints) else None
        return next((f"{m}::{name}" for m in world.model_names()
                     if any(j.name == name for j in world.model_description(m).joints)), None)

    def get_joint_properties(self, req: Any) -> Any:
        from gazebo_msgs.srv import GetJointPropertiesResponse

        with self.sim.lock:
            world = self.sim.world
            scoped = self._scoped_joint(req.joint_name)
            if scoped is None:
                return GetJointPropertiesResponse(success=False, status_message="GetJointProperties: joint not found")
            joint = world.joint_description(scoped)
            if joint.type == "fixed":
                position: list[float] = []
                rate: list[float] = []
            else:
                state = world.joint_state(scoped)
                position, rate = list(state.position), list(state.velocity)
        return GetJointPropertiesResponse(type=JOINT_TYPES.get(joint.type, 0), damping=[joint.axis.damping],
                                          position=position, rate=rate, success=True,
                                          status_message="GetJointProperties: got properties")

    def set_joint_properties(self, req: Any) -> Any:
        from gazebo_msgs.srv import SetJointPropertiesResponse

        with self.sim.lock:
            if self._scoped_joint(req.joint_name) is None:
                return SetJointPropertiesResponse(False, "SetJointProperties: joint not found")
        return SetJointPropertiesResponse(False, "SetJointProperties: ODE's joint parameters have no counterpart "
                                                 "in kame's physics (MuJoCo)")

    def _light(self, name: str) -> d.Light | None:
        return next((light for light in self.sim.world.lights if light.name == name), None)

    def get_light_properties(self, req: Any) -> Any:
        from gazebo_msgs.srv import GetLightPropertiesResponse
        from std_msgs.msg import ColorRGBA

        with self.sim.lock:
            light = self._light(req.light_name)
        if light is None:
            return GetLightPropertiesResponse(
                success=False, status_message=f"getLightProperties: Requested light {req.light_name} not found!")
        # kame's lights keep their colour and range, not their attenuation: SDF's defaults are answered
        return GetLightPropertiesResponse(diffuse=ColorRGBA(*light.diffuse), attenuation_constant=1.0,
                                          attenuation_linear=1.0, attenuation_quadratic=0.0, success=True,
                                          status_message="")

    def set_light_properties(self, req: Any) -> Any:
        from gazebo_msgs.srv import SetLightPropertiesResponse

        with self.sim.lock:
            found = self._light(req.light_name) is not None
        if not found:
            return SetLightPropertiesResponse(False, f"setLightProperties: Requested light {req.light_name} not found!")
        return SetLightPropertiesResponse(False, "setLightProperties: changing a light while the world runs is not "
                                                 "available in kame")

    # ------------------------------------------------------------------ physics

    def get_physics_properties(self, _req: Any) -> Any:
        from gazebo_msgs.msg import ODEPhysics
        from gazebo_msgs.srv import GetPhysicsPropertiesResponse

        with self.sim.lock:
            physics = self.sim.world.physics
            paused = self.sim.paused
        return GetPhysicsPropertiesResponse(
            time_step=physics.max_step_size, pause=paused, max_update_rate=physics.real_time_update_rate,
            gravity=vector_msg(physics.gravity), ode_config=ODEPhysics(), success=True,
            status_message="GetPhysicsProperties: got properties")

    def set_physics_properties(self, req: Any) -> Any:
        from gazebo_msgs.srv import SetPhysicsPropertiesResponse

        gravity = vector_of(req.gravity)
        with self.sim.lock:
            world = self.sim.world
            try:
                world.physics = replace(world.physics, max_step_size=req.time_step,
                                        real_time_update_rate=req.max_update_rate, gravity=gravity)
            except GazeboError as exc:
                _error("SetPhysicsProperties: %s", exc)
                return SetPhysicsPropertiesResponse(False, f"SetPhysicsProperties: {exc}")
        return SetPhysicsPropertiesResponse(True, "physics engine updated")

    def pause_physics(self, _req: Any) -> Any:
        from std_srvs.srv import EmptyResponse

        self.sim.set_paused(True)
        return EmptyResponse()

    def unpause_physics(self, _req: Any) -> Any:
        from std_srvs.srv import EmptyResponse

        self.sim.set_paused(False)
        return EmptyResponse()

    def reset_simulation(self, _req: Any) -> Any:
        from std_srvs.srv import EmptyResponse

        with self.sim.lock:
            self.sim.world.reset_simulation()
            self._states_published = -math.inf
            self.factory.reset_plugins()
        return EmptyResponse()

    def reset_world(self, _req: Any) -> Any:
        from std_srvs.srv import EmptyResponse

        with self.sim.lock:
            self.sim.world.reset_world()
            self.factory.reset_plugins()
        return EmptyResponse()

    # ------------------------------------------------------------------ forces

    def apply_body_wrench(self, req: Any) -> Any:
        from gazebo_msgs.srv import ApplyBodyWrenchResponse

        force, torque = vector_of(req.wrench.force), vector_of(req.wrench.torque)
        point = vector_of(req.reference_point)
        if not finite(*force, *torque, *point):
            _error("ApplyBodyWrench: the wrench and reference point must be finite (no NaN or infinity)")
            return ApplyBodyWrenchResponse(False, "ApplyBodyWrench: wrench and reference_point must be finite")
        with self.sim.lock:
            world = self.sim.world
            body = self._entity_state(req.body_name) if "::" in req.body_name else None
            if body is None:
                _error("ApplyBodyWrench: body [%s] does not exist", req.body_name)
                return ApplyBodyWrenchResponse(False, "ApplyBodyWrench: body does not exist")
            if relative.is_inertial(req.reference_frame):
                _log.emit(_log.INFO, "ApplyBodyWrench: reference_frame is empty/world/map, using inertial frame, "
                          "transferring from body relative to inertial frame", ())
            else:
                frame = self._entity_state(req.reference_frame)
                if frame is None:
                    _error("ApplyBodyWrench: reference_frame is not a valid entity name")
                    return ApplyBodyWrenchResponse(False, "ApplyBodyWrench: reference_frame not found")
                # the point given in the reference frame, seen from the body; the wrench in the world's axes
                at = relative.carried_into_world(Pose(point), frame.pose).position
                point = relative.seen_from(Pose(at), body.pose).position
                force, torque = relative.rotate(frame.pose, force), relative.rotate(frame.pose, torque)
            start = max(seconds(req.start_time), world.sim_time)
            try:
                world.apply_body_wrench(req.body_name, force, torque, point, start, req.duration.to_sec())
            except GazeboError as exc:
                return ApplyBodyWrenchResponse(False, f"ApplyBodyWrench: {exc}")
        return ApplyBodyWrenchResponse(True, "")

    def apply_joint_effort(self, req: Any) -> Any:
        from gazebo_msgs.srv import ApplyJointEffortResponse

        if not finite(req.effort):
            return ApplyJointEffortResponse(False, "ApplyJointEffort: effort must be finite")
        with self.sim.lock:
            world = self.sim.world
            scoped = self._scoped_joint(req.joint_name)
            if scoped is None:
                return ApplyJointEffortResponse(False, "ApplyJointEffort: joint not found")
            try:
                world.apply_joint_effort(scoped, req.effort, max(seconds(req.start_time), world.sim_time),
                                         req.duration.to_sec())
            except GazeboError as exc:
                return ApplyJointEffortResponse(False, f"ApplyJointEffort: {exc}")
        return ApplyJointEffortResponse(True, "ApplyJointEffort: effort set")

    def clear_joint_forces(self, req: Any) -> Any:
        from gazebo_msgs.srv import JointRequestResponse

        with self.sim.lock:
            scoped = self._scoped_joint(req.joint_name)
            if scoped is not None:
                self.sim.world.clear_joint_forces(scoped)
        return JointRequestResponse()

    def clear_body_wrenches(self, req: Any) -> Any:
        from gazebo_msgs.srv import BodyRequestResponse

        with self.sim.lock:
            self.sim.world.clear_body_wrenches(req.body_name)
        return BodyRequestResponse()

    def set_model_configuration(self, req: Any) -> Any:
        from gazebo_msgs.srv import SetModelConfigurationResponse

        if len(req.joint_names) != len(req.joint_positions):
            return SetModelConfigurationResponse(False, "SetModelConfiguration: joint name and position list "
                                                        "have different lengths")
        with self.sim.lock:
            world = self.sim.world
            if req.model_name not in world.model_names():
                _error("SetModelConfiguration: model [%s] does not exist", req.model_name)
                return SetModelConfigurationResponse(False, "SetModelConfiguration: model does not exist")
            try:
                world.set_joint_positions(req.model_name, dict(zip(req.joint_names, req.joint_positions,
                                                                   strict=True)))
            except GazeboError as exc:
                _error("SetModelConfiguration: %s", exc)
                return SetModelConfigurationResponse(False, f"SetModelConfiguration: {exc}")
        return SetModelConfigurationResponse(True, "SetModelConfiguration: success")


def _plus(a: tuple[float, float, float], b: tuple[float, float, float]) -> tuple[float, float, float]:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def _seen_from(state: State, frame: State) -> State:
    """A state relative to a moving frame, in its coordinates (Noetic's gazebo_ros)."""
    return State(relative.seen_from(state.pose, frame.pose),
                 relative.velocity_seen_from(state.linear, frame.linear, frame.pose),
                 relative.velocity_seen_from(state.angular, frame.angular, frame.pose))
