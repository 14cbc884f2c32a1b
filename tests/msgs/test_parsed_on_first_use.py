"""A profile parses a type on its first use: what a type answers does not depend on which
types were parsed before it, and neither do the errors."""

from __future__ import annotations

import threading

import pytest

from egosim.msgs import PROFILES, DefinitionError, Profile, UnknownTypeError
from egosim.msgs import profile as profile_module
from egosim.msgs.definitions import PackageDefinitions, ServiceText
from egosim.msgs.profile import ROSBAGS_INTERNAL

THREADS = 8
JOIN_TIMEOUT_S = 60.0


def message_names(profile: Profile) -> list[str]:
    """Every message type of the profile, service halves and rosbags' own types included."""
    return [
        name.replace("/msg/", "/", 1)
        for name in sorted(profile.complete_store().fielddefs)
        if not name.startswith(ROSBAGS_INTERNAL)
    ]


@pytest.mark.parametrize("release", PROFILES)
def test_a_type_asked_for_first_answers_as_in_a_fully_parsed_profile(release: str) -> None:
    parsed = Profile(release)
    for name in message_names(parsed):
        expected, alone = parsed.message(name), Profile(release).message(name)
        assert (alone.md5sum, alone.definition) == (expected.md5sum, expected.definition), name
        assert alone.serialize(alone.new()) == expected.serialize(expected.new()), name
    for name in parsed.service_names():
        expected_service, alone_service = parsed.service(name), Profile(release).service(name)
        assert alone_service.md5sum == expected_service.md5sum, name
        assert alone_service.definition == expected_service.definition, name


@pytest.mark.parametrize("release", PROFILES)
def test_whether_a_release_has_a_type_is_told_without_parsing_it(
    release: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    """As a fully parsed profile knows it, also for the types only other releases have."""
    complete = {name: Profile(name) for name in PROFILES}
    messages = {name: set(message_names(profile)) for name, profile in complete.items()}
    services = {name: set(profile.service_names()) for name, profile in complete.items()}
    fresh = Profile(release)

    def parse(text: str, name: str) -> object:
        raise AssertionError(f"{name} parsed")

    monkeypatch.setattr(profile_module, "get_types_from_msg", parse)
    for name in sorted(set().union(*messages.values())):
        assert fresh.has_message(name) == (name in messages[release]), name
    for name in sorted(set().union(*services.values())):
        assert fresh.has_service(name) == (name in services[release]), name


@pytest.mark.parametrize("release", PROFILES)
def test_unknown_types_are_reported_alike_before_and_after_every_type_is_parsed(
    release: str,
) -> None:
    fresh, parsed = Profile(release), Profile(release)
    parsed.complete_store()
    for profile in (fresh, parsed):
        with pytest.raises(UnknownTypeError) as message_error:
            profile.message("morai_msgs/NoSuchType")
        assert str(message_error.value) == (
            f"no message type 'morai_msgs/NoSuchType' in profile {release}"
        )
        with pytest.raises(UnknownTypeError) as service_error:
            profile.service("morai_msgs/NoSuchSrv")
        assert str(service_error.value) == (
            f"no service type 'morai_msgs/NoSuchSrv' in profile {release}"
        )


def test_threads_first_using_a_type_together_share_one_message_type() -> None:
    profile = Profile("26.r1")
    names = ["morai_msgs/ObjectStatusList", "morai_msgs/EgoVehicleStatus", "sensor_msgs/Imu"]
    start = threading.Barrier(THREADS)
    found: list[list[object]] = []
    errors: list[BaseException] = []

    def first_use() -> None:
        try:
            start.wait(JOIN_TIMEOUT_S)
            found.append([profile.message(name) for name in names])
            profile.service("morai_msgs/MoraiEventCmdSrv")
        except BaseException as exc:  # reported below, on the test's thread
            errors.append(exc)

    threads = [threading.Thread(target=first_use) for _ in range(THREADS)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(JOIN_TIMEOUT_S)
        assert not thread.is_alive(), f"a thread still looks up its types after {JOIN_TIMEOUT_S} s"
    assert errors == []
    assert len(found) == THREADS
    assert all(a is b for types in found for a, b in zip(types, found[0], strict=True))


def test_a_malformed_definition_is_reported_naming_it_on_first_use(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    package = PackageDefinitions(
        "lab_msgs",
        messages={
            "Broken": "float64[ x\n",
            "Wrapper": "Broken inner\n",
            "Sound": "float64 x\n",
        },
        services={"Ask": ServiceText("Broken question\n", "bool ok\n")},
    )
    monkeypatch.setattr(profile_module, "load_package_definitions", lambda _: [package])
    profile = Profile("lab")
    assert profile.message("lab_msgs/Sound").fields[0][0] == "x"
    for use in (
        lambda: profile.message("lab_msgs/Broken"),
        lambda: profile.message("lab_msgs/Wrapper"),
        lambda: profile.service("lab_msgs/Ask"),
        profile.complete_store,
    ):
        with pytest.raises(DefinitionError, match=r"^lab: cannot parse lab_msgs/Broken: "):
            use()
