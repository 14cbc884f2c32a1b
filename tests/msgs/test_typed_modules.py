"""The committed typed message modules are what the generator writes from the shipped
definitions, and they describe the messages a profile builds."""

from __future__ import annotations

from egosim.msgs import PROFILES, codegen, get_profile
from egosim.msgs.typed import morai_26_r1, standard


def test_committed_typed_modules_are_what_the_generator_writes() -> None:
    for file_name, text in codegen.generated().items():
        committed = (codegen.TYPED_PACKAGE / file_name).read_text(encoding="utf-8")
        assert committed == text, (
            f"src/egosim/msgs/typed/{file_name} is stale: run python -m egosim.msgs.codegen"
        )


def test_every_release_has_a_typed_module() -> None:
    written = set(codegen.generated())
    assert {f"{codegen.module_name(release)}.py" for release in PROFILES} <= written


def test_a_typed_class_names_the_fields_of_the_message_a_profile_builds() -> None:
    status = get_profile("26.r1").message("morai_msgs/EgoVehicleStatus").new()
    described = morai_26_r1.EgoVehicleStatus.__annotations__
    built = [name for name in status.__dataclass_fields__ if name != "__msgtype__"]
    assert list(described) == built
    assert list(standard.Header.__annotations__) == ["seq", "stamp", "frame_id"]
