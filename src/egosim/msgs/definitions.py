"""The .msg/.srv files shipped as package data, one folder per morai_msgs release."""

from __future__ import annotations

from dataclasses import dataclass
from importlib import resources
from typing import Final

from .errors import UnknownProfileError

DEFAULT_PROFILE: Final = "26.r1"
PROFILES: tuple[str, ...] = ("26.r1", "24.r2", "2021.08")
# Standard types missing from rosbags' Noetic store, shipped for every profile.
STANDARD_FOLDER = "standard"

SERVICE_SEPARATOR = "---"


@dataclass(frozen=True)
class ServiceText:
    """The two halves of a .srv file, as written."""

    request: str
    response: str


@dataclass(frozen=True)
class PackageDefinitions:
    """Raw texts of every type of one ROS package in one profile."""

    package: str
    messages: dict[str, str]
    services: dict[str, ServiceText]


def split_service(text: str) -> ServiceText:
    """Split a .srv text at its `---` line."""
    lines = text.splitlines(keepends=True)
    for index, line in enumerate(lines):
        if line.strip() == SERVICE_SEPARATOR:
            return ServiceText("".join(lines[:index]), "".join(lines[index + 1 :]))
    return ServiceText(text, "")


def load_package_definitions(profile: str) -> list[PackageDefinitions]:
    """Read every package folder shipped for `profile`, standard types first."""
    if profile not in PROFILES:
        known = ", ".join(PROFILES)
        raise UnknownProfileError(f"unknown protocol profile {profile!r} (known: {known})")
    root = resources.files(__package__).joinpath("definitions")
    package_dirs = [
        package_dir
        for folder in (STANDARD_FOLDER, profile)
        for package_dir in sorted(root.joinpath(folder).iterdir(), key=lambda p: p.name)
    ]
    packages = []
    for package_dir in package_dirs:
        if not package_dir.is_dir():
            continue
        messages: dict[str, str] = {}
        services: dict[str, ServiceText] = {}
        msg_dir = package_dir.joinpath("msg")
        srv_dir = package_dir.joinpath("srv")
        if msg_dir.is_dir():
            for path in msg_dir.iterdir():
                if path.name.endswith(".msg"):
                    messages[path.name[: -len(".msg")]] = path.read_text(encoding="utf-8")
        if srv_dir.is_dir():
            for path in srv_dir.iterdir():
                if path.name.endswith(".srv"):
                    text = path.read_text(encoding="utf-8")
                    services[path.name[: -len(".srv")]] = split_service(text)
        packages.append(PackageDefinitions(package_dir.name, messages, services))
    return packages
