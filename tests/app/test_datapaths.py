"""Names from the network never escape the data roots."""

from __future__ import annotations

from pathlib import Path

import pytest

from egosim.datapaths import PathOutsideRootsError, resolve_in_roots


@pytest.fixture
def roots(tmp_path: Path) -> list[Path]:
    first, second = tmp_path / "scenarios", tmp_path / "more"
    for root in (first, second):
        root.mkdir()
    (first / "a.yaml").write_text("a")
    (second / "b.yaml").write_text("b")
    (tmp_path / "secret.txt").write_text("s")
    return [first, second]


def test_relative_names_resolve_in_each_root(roots: list[Path]) -> None:
    assert resolve_in_roots("a.yaml", roots) == (roots[0] / "a.yaml").resolve()
    assert resolve_in_roots("b.yaml", roots) == (roots[1] / "b.yaml").resolve()


def test_absolute_name_inside_a_root_is_accepted(roots: list[Path]) -> None:
    path = str((roots[1] / "b.yaml").resolve())
    assert resolve_in_roots(path, roots) == Path(path)


@pytest.mark.parametrize("name", ["../secret.txt", "/etc/passwd", "a/../../secret.txt"])
def test_escapes_are_refused(roots: list[Path], name: str) -> None:
    with pytest.raises(PathOutsideRootsError):
        resolve_in_roots(name, roots)


def test_symlink_out_of_a_root_is_refused(roots: list[Path], tmp_path: Path) -> None:
    (roots[0] / "link.yaml").symlink_to(tmp_path / "secret.txt")
    with pytest.raises(PathOutsideRootsError):
        resolve_in_roots("link.yaml", roots)


def test_missing_file_is_not_found(roots: list[Path]) -> None:
    with pytest.raises(FileNotFoundError):
        resolve_in_roots("nope.yaml", roots)


def test_new_file_may_be_named_when_not_required_to_exist(roots: list[Path]) -> None:
    assert (
        resolve_in_roots("out/new.pcd", roots, must_exist=False)
        == (roots[0] / "out" / "new.pcd").resolve()
    )


@pytest.mark.parametrize("name", ["", "a\x00b"])
def test_empty_or_nul_names_are_refused(roots: list[Path], name: str) -> None:
    with pytest.raises(PathOutsideRootsError):
        resolve_in_roots(name, roots)
