"""A recorded synthetic drive, shared by the replay tests (recorded once per session)."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from tests.replay.drive import record_drive


@pytest.fixture(scope="session")
def recorded_drive(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return record_drive(tmp_path_factory.mktemp("drive") / "drive.bag")


@pytest.fixture
def data_root(tmp_path: Path, recorded_drive: Path) -> Path:
    """A data root holding a copy of the drive as drive.bag."""
    root = tmp_path / "data"
    root.mkdir()
    shutil.copy(recorded_drive, root / "drive.bag")
    return root
