"""rospkg: kame's against Debian's real rospkg on the same package trees, and the packages kame
ships found without any setup."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import pytest

import rospkg

from . import debian
from .rospkg_driver import run

DRIVER = Path(__file__).with_name("rospkg_driver.py")


def package_xml(name: str, *depends: str, metapackage: bool = False, version: str = "1.2.3") -> str:
    deps = "".join(f"<exec_depend>{d}</exec_depend><test_depend>{d}_t</test_depend>" for d in depends)
    export = "<export><metapackage/></export>" if metapackage else \
        '<export><rosdoc config="doc.yaml"/><cpp cflags="-I${prefix}/include"/></export>'
    return (f'<?xml version="1.0"?><package format="2"><name>{name}</name><version>{version}</version>'
            f"<description>The {name} package</description>"
            f'<maintainer email="m@example.org">Maintainer M</maintainer><author>A. Author</author>'
            f'<license>BSD</license><license>MIT</license><url type="website">http://example.org/{name}</url>'
            f"<buildtool_depend>catkin</buildtool_depend>{deps}{export}</package>")


def make_tree(root: Path, broken: bool = False) -> list[str]:
    layout = {
        "ws1/src/alpha": package_xml("alpha", "beta", "roscpp"),
        "ws1/src/group/beta": package_xml("beta", "gamma"),
        "ws1/src/group/nested/gamma": package_xml("gamma"),
        "ws1/src/renamed_folder": package_xml("delta"),
        "ws1/src/meta": package_xml("meta_pkg", "alpha", metapackage=True),
        "ws1/src/ignored/hidden_pkg": package_xml("ignored_pkg"),
        "ws1/src/.hidden/secret": package_xml("secret"),
        "ws1/src/alpha/inner": package_xml("inside_alpha"),
        "ws1/src/nosub/below": package_xml("below_nosubdirs"),
        "ws2/alpha_copy": package_xml("alpha", version="9.9.9"),
        "ws2/epsilon": package_xml("epsilon", "alpha"),
    }
    for folder, text in layout.items():
        (root / folder).mkdir(parents=True)
        (root / folder / "package.xml").write_text(text)
    (root / "ws1/src/ignored/CATKIN_IGNORE").write_text("")
    (root / "ws1/src/nosub/rospack_nosubdirs").write_text("")
    if broken:  # catkin_pkg refuses it: get_manifest raises, and so do get_depends_on's walks
        (root / "ws1/src/broken").mkdir()
        (root / "ws1/src/broken/package.xml").write_text("<package><name>broken</name></package>")
    (root / "ws1/src/alpha/scripts").mkdir()
    return [str(root / "ws1/src"), str(root / "ws2")]


@pytest.fixture
def tree(tmp_path: Path, request: pytest.FixtureRequest) -> dict[str, Any]:
    paths = make_tree(tmp_path, broken="debian" in request.node.name)
    return {"paths": paths, "env": {"ROS_HOME": str(tmp_path / "home"), "ROS_ROOT": str(tmp_path) + "/x/../r"},
            "probe": [str(tmp_path / "ws1/src/alpha/scripts"), str(tmp_path / "ws1/src/renamed_folder"),
                      str(tmp_path)],
            "expand": ["alpha", "meta_pkg", "nothing"]}


@pytest.mark.skipif(not debian.has("rospkg", "catkin_pkg"), reason="Debian's rospkg is not installed")
def test_same_answers_as_debians_rospkg(tree: dict[str, Any]) -> None:
    theirs = debian.run(DRIVER, tree)
    ours = run(tree)
    assert "alpha" in theirs["packages"] and theirs["stacks"] == ["meta_pkg"]
    assert ours == theirs


def test_depends_follow_the_manifests(tree: dict[str, Any]) -> None:
    rospack = rospkg.RosPack(tree["paths"])
    assert rospack.get_depends("alpha", implicit=False) == ["beta"]  # roscpp and catkin are not on these paths
    assert sorted(rospack.get_depends("alpha")) == ["beta", "gamma"]
    assert sorted(rospack.get_depends_on("gamma")) == ["alpha", "beta", "epsilon"]
    assert rospack.get_depends_on("gamma", implicit=False) == ["beta"]
    assert "roscpp" in rospack.get_rosdeps("alpha", implicit=False)
    assert rospack.get_manifest("alpha").get_export("rosdoc", "config") == ["doc.yaml"]
    assert rospack.stack_of("alpha") is None
    with pytest.raises(rospkg.ResourceNotFound) as caught:
        rospack.get_path("zeta")
    assert str(caught.value).splitlines() == ["zeta", f"ROS path [0]={tree['paths'][0]}",
                                              f"ROS path [1]={tree['paths'][1]}"]


def test_the_packages_kame_ships_are_found_without_setup(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.delenv("ROS_ROOT", raising=False)
    monkeypatch.setenv("ROS_PACKAGE_PATH", os.pathsep.join(make_tree(tmp_path)))
    rospack = rospkg.RosPack()
    assert Path(rospack.get_path("std_msgs"), "msg", "String.msg").is_file()
    assert rospack.get_path("alpha") == str(tmp_path / "ws1/src/alpha")
    assert "std_msgs" in rospack.get_depends("rospy_tutorials")
    assert rospkg.RosPack.get_instance() is rospkg.RosPack.get_instance()
    assert rospkg.on_ros_path(str(tmp_path / "ws2/epsilon")) and not rospkg.on_ros_path(str(tmp_path))
