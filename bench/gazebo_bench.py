"""kame's 3-D simulator core (kame.gazebo on MuJoCo): simulated seconds per wall second.

    .venv/bin/python bench/gazebo_bench.py [--seconds 5] [--only physics,lasers,camera]

The world: a ground plane, a 10 m x 10 m room of static walls, six loose boxes and cylinders,
and two-wheeled robots (a Kobuki-sized chassis on two driven wheels and two casters), each
driving a circle (its wheels held at their speeds by World.drive_joint), stepped at Gazebo's
0.001 s.
- physics: one robot, no sensors. Target >= 10x real time.
- lasers: ten robots, each with a 360-degree laser of 720 rays out to 10 m cast at 20 Hz.
  Target >= 1x.
- camera: one robot with the laser and a 640x480 camera (horizontal fov 1.047, as the
  Kinect's) rendered at 30 Hz, RGB and depth each frame, and a scan read off the depth image's
  middle row (depthimage_to_laserscan's way). Target >= 1x.
Each scenario also reports simulated seconds per CPU second of the process (all its threads:
on a machine shared with other work, what a core of its own would give) and where its wall time
went (physics steps, rays, renders), so a missed target says why. MuJoCo renders through EGL
(Mesa's llvmpipe on a machine without a GPU).
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from dataclasses import dataclass, replace

from kame_bytecode import compile_kame

STEP = 0.001
LASER = """<sensor name="laser" type="ray"><pose>0 0 0.15 0 0 0</pose><update_rate>20</update_rate><ray><scan>
  <horizontal><samples>720</samples><resolution>1</resolution><min_angle>-3.14159</min_angle>
  <max_angle>3.14159</max_angle></horizontal></scan><range><min>0.12</min><max>10</max></range></ray></sensor>"""
CAMERA = """<sensor name="camera" type="depth"><pose>0.1 0 0.25 0 0 0</pose><update_rate>30</update_rate><camera>
  <horizontal_fov>1.047</horizontal_fov><image><width>640</width><height>480</height><format>R8G8B8</format>
  </image><clip><near>0.05</near><far>8</far></clip></camera></sensor>"""


def robot(name: str, x: float, y: float, yaw: float, sensors: str) -> str:
    radius, separation = 0.035, 0.23  # Kobuki's wheels

    def wheel(side: str, offset: float) -> str:
        return f"""<link name="{side}_wheel"><pose>0 {offset} {radius} -1.5707963 0 0</pose>
          <inertial><mass>0.1</mass><inertia><ixx>4e-5</ixx><iyy>4e-5</iyy><izz>6e-5</izz></inertia></inertial>
          <collision name="collision"><geometry><cylinder><radius>{radius}</radius><length>0.02</length></cylinder>
          </geometry></collision><visual name="visual"><geometry><cylinder><radius>{radius}</radius>
          <length>0.02</length></cylinder></geometry><material><script><name>Gazebo/DarkGrey</name></script>
          </material></visual></link>
          <joint name="{side}_wheel_joint" type="continuous"><parent>base</parent><child>{side}_wheel</child>
          <axis><xyz>0 0 1</xyz></axis></joint>"""

    casters = "".join(f"""<collision name="caster_{i}"><pose>{x_} 0 -0.027 0 0 0</pose><geometry><sphere>
        <radius>0.017</radius></sphere></geometry><surface><friction><ode><mu>0</mu><mu2>0</mu2></ode></friction>
        </surface></collision>""" for i, x_ in enumerate((0.12, -0.12)))
    return f"""<model name="{name}"><pose>{x} {y} 0 0 0 {yaw}</pose><link name="base"><pose>0 0 0.047 0 0 0</pose>
      <inertial><mass>2.4</mass><inertia><ixx>0.02</ixx><iyy>0.02</iyy><izz>0.03</izz></inertia></inertial>
      <collision name="body"><pose>0 0 0.04 0 0 0</pose><geometry><cylinder><radius>0.17</radius>
      <length>0.08</length></cylinder></geometry></collision>{casters}
      <visual name="body"><pose>0 0 0.04 0 0 0</pose><geometry><cylinder><radius>0.17</radius><length>0.08</length>
      </cylinder></geometry><material><script><name>Gazebo/FlatBlack</name></script></material></visual>
      {sensors}</link>{wheel("left", separation / 2)}{wheel("right", -separation / 2)}</model>"""


def playground(robots: str) -> str:
    walls = "".join(f"""<collision name="{n}"><pose>{x} {y} 0.5 0 0 {yaw}</pose><geometry><box><size>10 0.2 1</size>
      </box></geometry></collision><visual name="{n}"><pose>{x} {y} 0.5 0 0 {yaw}</pose><geometry><box>
      <size>10 0.2 1</size></box></geometry><material><script><name>Gazebo/Bricks</name></script></material>
      </visual>""" for n, x, y, yaw in (("n", 0, 5, 0), ("s", 0, -5, 0), ("e", 5, 0, 1.5708), ("w", -5, 0, 1.5708)))
    objects = "".join(f"""<include><uri>model://{kind}</uri><name>{kind}_{i}</name>
      <pose>{3.5 * math.cos(i)} {3.5 * math.sin(i)} 0.5 0 0 0</pose></include>"""
                      for i, kind in enumerate(("box", "cylinder", "box", "cylinder", "box", "cylinder")))
    return f"""<sdf version="1.6"><world name="playground"><include><uri>model://ground_plane</uri></include>
      <include><uri>model://sun</uri></include><model name="walls"><static>true</static><link name="link">{walls}
      </link></model>{objects}{robots}</world></sdf>"""


@dataclass
class Timing:
    steps: float = 0.0
    rays: float = 0.0
    renders: float = 0.0


def run(robots: int, laser: bool, camera: bool, seconds: float) -> tuple[float, float, Timing]:
    from kame.gazebo import World

    placed = "".join(robot(f"robot_{i}", 2.0 * math.cos(2 * math.pi * i / robots),
                           2.0 * math.sin(2 * math.pi * i / robots), 2 * math.pi * i / robots + math.pi / 2,
                           (LASER if laser else "") + (CAMERA if camera and i == 0 else ""))
                     for i in range(robots))
    world = World.from_sdf(playground(placed))
    world.physics = replace(world.physics, max_step_size=STEP)
    for i in range(robots):
        world.drive_joint(f"robot_{i}::left_wheel_joint", 8.0, 1.0)
        world.drive_joint(f"robot_{i}::right_wheel_joint", 10.0, 1.0)
    lasers = [s for s in world.sensors() if s.type == "ray"]
    cameras = [s for s in world.sensors() if s.type == "depth"]
    timing = Timing()
    next_scan, next_frame = 0.0, 0.0
    cpu = time.process_time()
    start = time.perf_counter()
    while time.perf_counter() - start < seconds:
        began = time.perf_counter()
        world.step(1)
        timing.steps += time.perf_counter() - began
        if lasers and world.sim_time >= next_scan:
            began = time.perf_counter()
            for sensor in lasers:
                world.ray_scan(sensor)
            timing.rays += time.perf_counter() - began
            next_scan += 1 / 20
        if cameras and world.sim_time >= next_frame:
            began = time.perf_counter()
            for sensor in cameras:
                frame = world.camera_frame(sensor, rgb=True, depth=True)
                assert frame.depth is not None
                frame.depth[240]  # the scan depthimage_to_laserscan would publish
            timing.renders += time.perf_counter() - began
            next_frame += 1 / 30
    wall = time.perf_counter() - start
    cpu = time.process_time() - cpu  # every thread's, Mesa's rendering threads too
    world.close()
    return world.sim_time / wall, world.sim_time / cpu, timing


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds", type=float, default=5.0, help="wall seconds a scenario runs")
    parser.add_argument("--only", default="physics,lasers,camera")
    options = parser.parse_args()
    compile_kame()
    scenarios = {"physics": ("1 robot, physics alone", 1, False, False, 10.0),
                 "lasers": ("10 robots, 720-ray lasers at 20 Hz", 10, True, False, 1.0),
                 "camera": ("1 robot, laser + 640x480 RGB and depth at 30 Hz", 1, True, True, 1.0)}
    print(f"loadavg {' '.join(f'{v:.2f}' for v in os.getloadavg())}, MUJOCO_GL={os.environ.get('MUJOCO_GL', 'egl')}",
          file=sys.stderr, flush=True)
    print(f"{'scenario':50} {'real-time factor':>17} {'per CPU second':>15} {'target':>7}  where the wall time went")
    for key in options.only.split(","):
        title, robots, laser, camera, target = scenarios[key]
        factor, per_cpu, timing = run(robots, laser, camera, options.seconds)
        spent = timing.steps + timing.rays + timing.renders
        parts = ", ".join(f"{name} {share / spent:.0%}" for name, share in
                          (("steps", timing.steps), ("rays", timing.rays), ("renders", timing.renders)) if share)
        print(f"{title:50} {factor:16.2f}x {per_cpu:14.2f}x {target:6.0f}x  {parts}", flush=True)
    print(f"loadavg after {' '.join(f'{v:.2f}' for v in os.getloadavg())}", file=sys.stderr)


if __name__ == "__main__":
    main()
