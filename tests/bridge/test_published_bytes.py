"""Every row's bytes, in every release, are those the bridge published before its rows
wrote their own bytes: the digests of a fixed drive (tests/bridge/published_bytes.py)
recorded then."""

from __future__ import annotations

import json

from tests.bridge.published_bytes import RECORDED, published_digests


def test_every_row_publishes_the_recorded_bytes_in_every_release() -> None:
    recorded = json.loads(RECORDED.read_text())
    published = published_digests()
    assert published.keys() == recorded.keys()
    differing = sorted(key for key, digest in published.items() if recorded[key] != digest)
    assert not differing, f"these topics and releases publish other bytes: {differing}"
