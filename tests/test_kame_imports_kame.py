"""kame's own programs stand on kame: no module of src/kame (but the example packages in
kame/share, which are users' programs) imports the compatibility packages (rospy, rosbag,
actionlib, roslaunch, genpy, roslib, rosgraph, rospkg, the tools as modules, the tf ones, ...), which are names over
kame for users' scripts."""

from __future__ import annotations

import ast
from pathlib import Path

KAME = Path(__file__).resolve().parents[1] / "src" / "kame"
FACADES = {"rospy", "rosbag", "actionlib", "roslaunch", "genpy", "genmsg", "roslib", "rosgraph", "rospkg",
           "message_filters",
           "cv_bridge", "rostopic", "rosservice", "rosnode", "rosparam", "rosmsg", "rosmaster",
           "tf", "tf2_ros", "tf2_geometry_msgs", "tf_conversions", "PyKDL", "interactive_markers",
           "camera_calibration_parsers"}


def facade_imports(path: Path) -> list[str]:
    found = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            found += [alias.name for alias in node.names if alias.name.split(".")[0] in FACADES]
        elif isinstance(node, ast.ImportFrom) and not node.level and (node.module or "").split(".")[0] in FACADES:
            found.append(str(node.module))
    return found


def test_no_kame_module_imports_a_compatibility_package() -> None:
    offenders = {
        str(path.relative_to(KAME)): names
        for path in sorted(KAME.rglob("*.py"))
        if "share" not in path.relative_to(KAME).parts[:1] and (names := facade_imports(path))
    }
    assert offenders == {}


def test_the_check_sees_imports_inside_functions(tmp_path: Path) -> None:
    module = tmp_path / "m.py"
    module.write_text("def f():\n    from rospy import core\n    import rosbag.bag\nfrom std_msgs.msg import String\n")
    assert facade_imports(module) == ["rospy", "rosbag.bag"]
