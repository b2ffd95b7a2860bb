"""Property: no SDF or URDF text, however wrong, gets anything out of the simulator but a World or
a GazeboError (the ci profile's few derandomized examples in the normal run; HYPOTHESIS_PROFILE=nightly
for many). The documents are built from SDF's and URDF's own tags with numbers, NaN, infinities,
words and nothing as their values, so the readers' every branch meets bad values."""

from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st

from tests.gazebo import require_engine

require_engine()

from kame.gazebo import GazeboError, World  # noqa: E402  (MuJoCo loads once require_engine has checked it can)

SDF_TAGS = ["model", "link", "joint", "visual", "collision", "geometry", "box", "sphere", "cylinder", "plane", "mesh",
            "size", "radius", "length", "pose", "inertial", "mass", "inertia", "ixx", "iyy", "izz", "parent", "child",
            "axis", "xyz", "limit", "lower", "upper", "effort", "dynamics", "damping", "friction", "static",
            "sensor", "ray", "scan", "horizontal", "vertical", "samples", "min_angle", "max_angle", "range", "min",
            "max", "camera", "image", "width", "height", "horizontal_fov", "clip", "near", "far", "imu", "noise",
            "plugin", "include", "uri", "name", "light", "direction", "diffuse", "material", "script", "physics",
            "max_step_size", "gravity", "frame", "surface", "ode", "mu", "mu2", "update_rate", "sonar", "self_collide"]
VALUES = st.sampled_from(["", "1", "0", "-1", "0.5", "1 2 3", "1 2 3 4 5 6", "0 0 1", "nan", "inf", "-inf",
                          "1e400", "true", "x", "1 nan 0 0 0 0", "model://box", "world", "l", "a"])
ATTRIBUTES = st.dictionaries(st.sampled_from(["name", "type", "relative_to", "frame", "filename", "reference",
                                              "version", "expressed_in"]),
                             st.sampled_from(["m", "l", "a", "world", "ray", "camera", "revolute", "ball", "fixed",
                                              "continuous", "prismatic", "imu", "", "__model__"]), max_size=3)


def element(tags: list[str]) -> st.SearchStrategy[str]:
    def render(tag: str, attrs: dict[str, str], body: str) -> str:
        attributes = "".join(f' {k}="{v}"' for k, v in attrs.items())
        return f"<{tag}{attributes}>{body}</{tag}>"

    leaf = st.builds(render, st.sampled_from(tags), ATTRIBUTES, VALUES)
    return st.recursive(leaf, lambda inner: st.builds(render, st.sampled_from(tags), ATTRIBUTES,
                                                      st.lists(inner, max_size=4).map("".join)), max_leaves=25)


@given(st.lists(element(SDF_TAGS), max_size=4).map("".join))
def test_any_sdf_world_is_a_world_or_a_gazebo_error(body: str) -> None:
    for text in (f'<sdf version="1.6"><world name="w">{body}</world></sdf>', f'<sdf version="1.4">{body}</sdf>'):
        try:
            world = World.from_sdf(text)
        except GazeboError:
            continue
        world.step(5)
        for sensor in world.sensors():
            try:
                if sensor.type == "ray":
                    world.ray_scan(sensor)
                elif sensor.type == "imu":
                    world.imu_reading(sensor)
            except GazeboError:
                pass
        world.close()


URDF_TAGS = ["link", "joint", "visual", "collision", "geometry", "box", "cylinder", "sphere", "mesh", "origin",
             "inertial", "mass", "inertia", "parent", "child", "axis", "limit", "dynamics", "material", "color",
             "gazebo", "mu1", "mu2", "sensor", "plugin", "static", "selfCollide"]


@given(st.lists(element(URDF_TAGS), max_size=4).map("".join))
def test_any_urdf_spawns_or_is_a_gazebo_error(body: str) -> None:
    world = World.empty()
    try:
        world.spawn_urdf(f'<robot name="r">{body}</robot>')
    except GazeboError:
        return
    world.step(5)


SKELETON = """<model name="m"><static>{}</static><pose>{}</pose>
  <link name="a"><pose>{}</pose><inertial><mass>{}</mass><inertia><ixx>{}</ixx><iyy>{}</iyy><izz>{}</izz></inertia>
    </inertial><collision name="c"><pose>{}</pose><geometry><box><size>{}</size></box></geometry>
      <surface><friction><ode><mu>{}</mu><mu2>{}</mu2></ode></friction></surface></collision>
    <visual name="v"><geometry><cylinder><radius>{}</radius><length>{}</length></cylinder></geometry>
      <material><diffuse>{}</diffuse><script><name>{}</name></script></material></visual>
    <sensor name="laser" type="ray"><pose>{}</pose><update_rate>{}</update_rate><ray><scan><horizontal>
      <samples>{}</samples><resolution>{}</resolution><min_angle>{}</min_angle><max_angle>{}</max_angle></horizontal>
      </scan><range><min>{}</min><max>{}</max></range><noise><type>gaussian</type><mean>{}</mean>
      <stddev>{}</stddev></noise></ray></sensor>
    <sensor name="imu" type="imu"><imu><noise><type>gaussian</type><rate><mean>{}</mean><stddev>{}</stddev></rate>
      </noise></imu></sensor></link>
  <link name="b"><pose>{}</pose><collision name="c"><geometry><sphere><radius>{}</radius></sphere></geometry>
    </collision></link>
  <joint name="j" type="{}"><parent>a</parent><child>b</child><pose>{}</pose><axis><xyz>{}</xyz>
    <limit><lower>{}</lower><upper>{}</upper><effort>{}</effort></limit><dynamics><damping>{}</damping>
    <friction>{}</friction></dynamics></axis></joint></model>"""
JOINT_TYPES = st.sampled_from(["revolute", "continuous", "prismatic", "fixed", "ball", "screw", ""])
# mostly empty (each element's default), so that most examples get past the first values to the deep ones
FILLS = st.sampled_from([""] * 12 + ["1", "0", "-1", "0.5", "1e9", "nan", "x", "inf", "1 2 3", "0 0 1",
                                     "1 2 3 4 5 6", "true", "Gazebo/Red"])


@given(st.lists(FILLS, min_size=SKELETON.count("{}") - 1, max_size=SKELETON.count("{}") - 1), JOINT_TYPES)
def test_a_model_with_any_values_is_a_world_or_a_gazebo_error(values: list[str], joint_type: str) -> None:
    at = 29  # the joint's type among the placeholders
    filled = SKELETON.format(*values[:at], joint_type, *values[at:])
    try:
        world = World.from_sdf(f'<sdf version="1.6"><world name="w">{filled}</world></sdf>')
    except GazeboError:
        return
    world.step(20)
    for sensor in world.sensors():
        try:
            world.ray_scan(sensor) if sensor.type == "ray" else world.imu_reading(sensor)
        except GazeboError:
            pass
