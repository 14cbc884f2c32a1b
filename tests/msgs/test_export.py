"""`egosim msgs --export` / `--export-python` give a user morai_msgs as MORAI's own package:
Debian's genpy imports it with every md5 of the profile, catkin builds it into the very
same modules, and Debian's rosmsg/rossrv show what `egosim msgs TYPE` shows."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from egosim.msgs import PROFILES, get_profile
from egosim.msgs.export import PACKAGE, write_catkin_package
from egosim.msgs.show import show_message, show_service
from tests.debian_ros import ROS_PYTHON, require_ros

PEERS = Path(__file__).parent / "peers"
CATKIN_TIMEOUT_S = 900


def export_python(directory: Path, profile: str) -> None:
    subprocess.run(
        [
            sys.executable,
            "-m",
            "egosim",
            "msgs",
            "--export-python",
            str(directory),
            "--profile",
            profile,
        ],
        check=True,
        capture_output=True,
        timeout=300,
    )


def morai_md5s(profile: str) -> dict[str, str]:
    """Every morai_msgs message and service of the profile with egosim's md5sum."""
    types = get_profile(profile)
    md5s = {
        name: types.message(name).md5sum
        for name in types.message_names()
        if name.startswith(f"{PACKAGE}/")
    }
    md5s.update({name: types.service(name).md5sum for name in types.service_names()})
    return md5s


@pytest.mark.parametrize("profile", PROFILES)
def test_catkin_package_lists_every_shipped_file(tmp_path: Path, profile: str) -> None:
    written = write_catkin_package(get_profile(profile), tmp_path)
    manifest = ET.parse(tmp_path / "package.xml").getroot()
    assert manifest.findtext("name") == PACKAGE
    assert {d.text for d in manifest.findall("depend")} == {"geometry_msgs", "std_msgs"}
    assert manifest.findtext("build_depend") == "message_generation"
    cmake = (tmp_path / "CMakeLists.txt").read_text()
    assert "project(morai_msgs)" in cmake
    for path in written:
        if path.endswith((".msg", ".srv")):
            assert f"  {Path(path).name}\n" in cmake
    listed = {p for p in written if p.endswith((".msg", ".srv"))}
    assert len(listed) == len(morai_md5s(profile))


@pytest.mark.ros
@pytest.mark.parametrize("profile", PROFILES)
def test_exported_modules_import_with_every_md5(tmp_path: Path, profile: str) -> None:
    require_ros()
    # Over an export of another release: none of its modules may stay behind.
    export_python(tmp_path, "2021.08" if profile == "26.r1" else "26.r1")
    export_python(tmp_path, profile)
    result = subprocess.run(
        [ROS_PYTHON, str(PEERS / "exported_md5s.py"), PACKAGE],
        env={"PYTHONPATH": str(tmp_path), "PATH": "/usr/bin:/bin"},
        capture_output=True,
        text=True,
        check=True,
        timeout=120,
    )
    genpy_md5s = json.loads(result.stdout)
    assert genpy_md5s == morai_md5s(profile)
    # The packages morai_msgs embeds come along, and do not hide the rest of an installed
    # copy (Debian ships std_msgs' modules; its other modules stay importable).
    assert sorted(p.name for p in tmp_path.iterdir()) == ["geometry_msgs", PACKAGE, "std_msgs"]


@pytest.mark.ros
def test_rosmsg_and_rossrv_show_what_egosim_msgs_shows(tmp_path: Path) -> None:
    require_ros()
    profile = get_profile("26.r1")
    write_catkin_package(profile, tmp_path / "src" / PACKAGE)
    names = [f"msg:{n}" for n in profile.message_names() if n.startswith(f"{PACKAGE}/")]
    names += [f"srv:{n}" for n in profile.service_names()]
    result = subprocess.run(
        [ROS_PYTHON, str(PEERS / "rosmsg_show.py"), *names],
        env={"ROS_PACKAGE_PATH": f"{tmp_path / 'src'}:/usr/share", "PATH": "/usr/bin:/bin"},
        capture_output=True,
        text=True,
        check=True,
        timeout=120,
    )
    shown = json.loads(result.stdout)
    assert len(shown) == len(names)
    for name, text in shown.items():
        if name in profile.service_names():
            ours = show_service(profile.service(name))
        else:
            ours = show_message(profile.message(name))
        assert ours.rstrip("\n") == text.rstrip("\n"), name


@pytest.mark.ros
@pytest.mark.timeout(CATKIN_TIMEOUT_S)
def test_catkin_builds_the_exported_package_into_the_exported_modules(tmp_path: Path) -> None:
    require_ros()
    if shutil.which("catkin_make") is None:
        pytest.skip("catkin_make is not installed (apt-get install catkin)")
    workspace = tmp_path / "catkin_ws"
    subprocess.run(
        [sys.executable, "-m", "egosim", "msgs", "--export", str(workspace / "src" / PACKAGE)],
        check=True,
        capture_output=True,
        timeout=120,
    )
    # Only the rospy target: the C++ and Lisp generators add minutes and nothing to check.
    build = subprocess.run(
        ["catkin_make", f"-DPYTHON_EXECUTABLE={ROS_PYTHON}", "morai_msgs_generate_messages_py"],
        cwd=workspace,
        env={"PATH": "/usr/bin:/bin", "HOME": str(tmp_path)},
        capture_output=True,
        text=True,
        check=False,
        timeout=CATKIN_TIMEOUT_S - 60,
    )
    assert build.returncode == 0, build.stdout[-3000:] + build.stderr[-3000:]
    built = workspace / "devel" / "lib" / "python3" / "dist-packages" / PACKAGE
    exported = tmp_path / "exported"
    export_python(exported, "26.r1")

    def files(root: Path) -> dict[str, bytes]:
        return {
            str(p.relative_to(root)): p.read_bytes()
            for p in sorted(root.rglob("*.py"))
            if "__pycache__" not in p.parts
        }

    built_files = files(built)
    assert len(built_files) > 100
    assert files(exported / PACKAGE) == built_files
