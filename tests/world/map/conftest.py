import pytest

from egosim.world.map import LaneMap, build_builtin_map


@pytest.fixture(scope="session")
def town() -> LaneMap:
    return build_builtin_map("town")


@pytest.fixture(scope="session")
def straight() -> LaneMap:
    return build_builtin_map("straight")


@pytest.fixture(scope="session")
def loop() -> LaneMap:
    return build_builtin_map("loop")
