#!/usr/bin/env python3
"""catkin_make, kame's beside Debian's, on the same 10-package mixed workspace (stdlib only).

The workspace: five Python packages (a message package, a setup.py library, three with scripts)
and five C++ packages (a hello node, a Twist publisher, a node including the Python message
package's header, a package with its own message, a library with a program linking it).
Each implementation builds its own copy from scratch (clean), then again with nothing changed
(rebuild); then the same for the five Python packages alone. Debian's catkin_make runs with
the system's environment (/usr/bin first, no ROS variables); kame's from the project venv.

  python3 bench/catkin_bench.py [--reps 2] [--jobs 2]
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
VENV_BIN = REPO / ".venv" / "bin"

PACKAGE_XML = """<?xml version="1.0"?>
<package format="2">
  <name>%s</name>
  <version>0.1.0</version>
  <description>catkin_bench's %s</description>
  <maintainer email="bench@example.com">bench</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
%s</package>
"""

SCRIPT = "#!/usr/bin/env python3\nimport rospy\nprint('%s')\n"

NODE = """#include <ros/ros.h>
%s
int main(int argc, char** argv) {
  ros::init(argc, argv, "%s");
  ros::NodeHandle nh;
  %s
  return 0;
}
"""


def cmake(name: str, components: str, body: str) -> str:
    return ("cmake_minimum_required(VERSION 3.0.2)\nproject(%s)\n"
            "find_package(catkin REQUIRED COMPONENTS %s)\n%s" % (name, components, body))


def package(src: Path, name: str, depends: list[str], cmake_text: str, files: dict[str, str]) -> None:
    folder = src / name
    folder.mkdir(parents=True)
    deps = "".join("  <depend>%s</depend>\n" % d for d in depends)
    (folder / "package.xml").write_text(PACKAGE_XML % (name, name, deps))
    (folder / "CMakeLists.txt").write_text(cmake_text)
    for rel, text in files.items():
        path = folder / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
        if rel.startswith("scripts/"):
            path.chmod(0o755)


def python_packages(src: Path) -> None:
    package(src, "bench_msgs", ["std_msgs", "message_generation", "message_runtime"],
            cmake("bench_msgs", "std_msgs message_generation",
                  "add_message_files(FILES Num.msg)\ngenerate_messages(DEPENDENCIES std_msgs)\n"
                  "catkin_package(CATKIN_DEPENDS message_runtime std_msgs)\n"),
            {"msg/Num.msg": "int64 num\nstd_msgs/Header header\n"})
    package(src, "bench_lib", ["rospy"],
            cmake("bench_lib", "rospy", "catkin_python_setup()\ncatkin_package()\n"),
            {"setup.py": "from setuptools import setup\nfrom catkin_pkg.python_setup import generate_distutils_setup\n"
                         "setup(**generate_distutils_setup(packages=['bench_lib'], package_dir={'': 'src'}))\n",
             "src/bench_lib/__init__.py": "VALUE = 42\n"})
    for name in ("bench_talker", "bench_tools", "bench_nodes"):
        package(src, name, ["rospy", "bench_msgs"],
                cmake(name, "rospy bench_msgs", "catkin_package()\ncatkin_install_python(PROGRAMS scripts/%s.py "
                      "DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})\n" % name),
                {"scripts/%s.py" % name: SCRIPT % name})


def executable(name: str, target: str, source: str) -> str:
    return ("catkin_package()\ninclude_directories(${catkin_INCLUDE_DIRS})\n"
            "add_executable(%s %s)\ntarget_link_libraries(%s ${catkin_LIBRARIES})\n"
            "add_dependencies(%s ${catkin_EXPORTED_TARGETS})\n" % (target, source, target, target))


def cpp_packages(src: Path) -> None:
    package(src, "cpp_hello", ["roscpp"], cmake("cpp_hello", "roscpp", executable("cpp_hello", "hello", "hello.cpp")),
            {"hello.cpp": NODE % ("", "hello", 'ROS_INFO_STREAM("Hello, ROS!");')})
    package(src, "cpp_pub", ["roscpp", "geometry_msgs"],
            cmake("cpp_pub", "roscpp geometry_msgs", executable("cpp_pub", "pub", "pub.cpp")),
            {"pub.cpp": NODE % ("#include <geometry_msgs/Twist.h>", "pub",
                                'nh.advertise<geometry_msgs::Twist>("cmd_vel", 1);')})
    package(src, "cpp_num", ["roscpp", "bench_msgs"],
            cmake("cpp_num", "roscpp bench_msgs", executable("cpp_num", "num", "num.cpp")),
            {"num.cpp": NODE % ("#include <bench_msgs/Num.h>", "num", "bench_msgs::Num n; n.num = 1;")})
    package(src, "cpp_own", ["roscpp", "std_msgs", "message_generation", "message_runtime"],
            cmake("cpp_own", "roscpp std_msgs message_generation",
                  "add_message_files(FILES Reading.msg)\ngenerate_messages(DEPENDENCIES std_msgs)\n"
                  "catkin_package(CATKIN_DEPENDS message_runtime)\ninclude_directories(${catkin_INCLUDE_DIRS})\n"
                  "add_executable(own own.cpp)\ntarget_link_libraries(own ${catkin_LIBRARIES})\n"
                  "add_dependencies(own ${${PROJECT_NAME}_EXPORTED_TARGETS})\n"),
            {"msg/Reading.msg": "float64 value\n",
             "own.cpp": NODE % ("#include <cpp_own/Reading.h>", "own", "cpp_own::Reading r; r.value = 1;")})
    package(src, "cpp_lib", ["roscpp"],
            cmake("cpp_lib", "roscpp",
                  "catkin_package(LIBRARIES cpp_lib)\ninclude_directories(${catkin_INCLUDE_DIRS})\n"
                  "add_library(cpp_lib lib.cpp)\nadd_executable(uses uses.cpp)\n"
                  "target_link_libraries(uses cpp_lib ${catkin_LIBRARIES})\n"),
            {"lib.cpp": "int answer() { return 42; }\n",
             "uses.cpp": NODE % ("int answer();", "uses", "ROS_INFO(\"%d\", answer());")})


def environments() -> dict[str, tuple[list[str], dict[str, str]]]:
    base = {k: v for k, v in os.environ.items() if not k.startswith("ROS_") and k not in
            ("PYTHONPATH", "CMAKE_PREFIX_PATH", "VIRTUAL_ENV", "LD_LIBRARY_PATH", "PKG_CONFIG_PATH")}
    debian = dict(base, PATH="/usr/bin:/bin")
    kame = dict(base, PATH="%s:/usr/bin:/bin" % VENV_BIN, ROS_DISTRO="noetic")
    return {"debian": (["/usr/bin/catkin_make"], debian), "kame": ([str(VENV_BIN / "catkin_make")], kame)}


def timed(cmd: list[str], cwd: Path, env: dict[str, str]) -> float:
    start = time.perf_counter()
    env = dict(env, PWD=str(cwd))  # catkin_make takes the workspace from $PWD
    done = subprocess.run(cmd, cwd=cwd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    elapsed = time.perf_counter() - start
    if done.returncode != 0:
        raise SystemExit("%s failed in %s:\n%s" % (" ".join(cmd), cwd, done.stderr[-3000:]))
    return elapsed


def measure(kind: str, reps: int, jobs: int, root: Path) -> dict[str, dict[str, list[float]]]:
    results: dict[str, dict[str, list[float]]] = {}
    for _ in range(reps):
        for impl, (cmd, env) in environments().items():  # interleaved
            ws = root / ("%s-%s" % (kind, impl))
            if ws.exists():
                shutil.rmtree(ws)
            python_packages(ws / "src")
            if kind == "mixed":
                cpp_packages(ws / "src")
            runs = results.setdefault(impl, {"clean": [], "rebuild": []})
            runs["clean"].append(timed([*cmd, "-j%d" % jobs], ws, env))
            runs["rebuild"].append(timed([*cmd, "-j%d" % jobs], ws, env))
    return results


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--reps", type=int, default=2)
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args()
    if not Path("/usr/bin/catkin_make").exists():
        print("Debian's catkin_make is not installed (scripts/install-ros-peers.sh)", file=sys.stderr)
        return 1
    with tempfile.TemporaryDirectory(prefix="catkin_bench-") as tmp:
        print("%-34s %10s %10s %10s" % ("workspace, build", "debian s", "kame s", "kame/deb"))
        for kind, label in (("mixed", "10 packages (5 C++)"), ("python", "5 Python packages")):
            results = measure(kind, args.reps, args.jobs, Path(tmp))
            for phase in ("clean", "rebuild"):
                deb = statistics.median(results["debian"][phase])
                kame = statistics.median(results["kame"][phase])
                print("%-34s %10.2f %10.2f %9.2fx" % ("%s, %s" % (label, phase), deb, kame, kame / deb))
    return 0


if __name__ == "__main__":
    sys.exit(main())
