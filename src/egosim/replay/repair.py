"""Rebuilding the index of a bag whose recorder died before closing it.

A ROS 1 (v2.0) bag is written as chunks, each followed by its index-data
records; the connection records and chunk-info records that make up the
index, and the header's `index_pos`, are written only on close. Everything
needed to rebuild them is inside the chunks, which is what `rosbag reindex`
relies on too. Record encoding is rosbags' own (its reader's and writer's
record helpers); only the scan over an unindexed file is done here.

A crash can only cut the file short: the last record runs past its end, or the index
was being written. A record that is whole but unreadable, or any chunk after the one
that failed, means the file is damaged instead; it is then refused and left as it is,
since cutting it there would throw away everything after the damage.
"""

from __future__ import annotations

import logging
import mmap
import os
from collections import defaultdict
from dataclasses import dataclass, field
from io import BytesIO
from pathlib import Path
from typing import BinaryIO

from rosbags.interfaces import (
    Connection,
    ConnectionExtRosbag1,
    MessageDefinition,
    MessageDefinitionFormat,
)
from rosbags.rosbag1.reader import (
    Header,
    ReaderError,
    RecordType,
    decompressors,
    read_bytes,
    read_uint32,
)
from rosbags.rosbag1.writer import Header as RecordHeader
from rosbags.rosbag1.writer import Writer, serialize_time, serialize_uint32
from rosbags.typesys.msg import normalize_msgtype

from .errors import BagError, BagInUseError
from .recordings import is_recording

log = logging.getLogger(__name__)

MAGIC = b"#ROSBAG V2.0\n"
# How a chunk record's header names its op: a later one means the bag goes on past a failure.
CHUNK_OP_FIELD = b"op=" + bytes([RecordType.CHUNK])


@dataclass(frozen=True)
class RepairReport:
    """What `repair_bag` found and kept."""

    path: Path
    repaired: bool  # False: the bag already had its index, nothing was changed
    chunks: int = 0  # complete chunks kept
    messages: int = 0  # messages in them
    connections: int = 0
    truncated_bytes: int = 0  # bytes of a partly written trailing record dropped


@dataclass
class _ScannedChunk:
    pos: int
    end: int  # file offset just past the chunk record
    index_end: int | None  # past its index-data records, None when they are incomplete
    entries: dict[int, list[tuple[int, int]]] = field(default_factory=dict)  # conn -> (t, ofs)


def needs_repair(path: str | os.PathLike[str]) -> bool:
    """True when `path` is a v2.0 bag whose header does not point to an index."""
    with Path(path).open("rb") as bag:
        return _read_bag_header(bag)[0] == 0


def repair_bag(path: str | os.PathLike[str]) -> RepairReport:
    """Rebuild the index of an unclosed bag in place, dropping a truncated trailing chunk."""
    path = Path(path)
    if is_recording(path):
        raise BagInUseError(f"{path} is being recorded by this process")
    with path.open("r+b") as bag:
        index_pos, header_end = _read_bag_header(bag)
        if index_pos != 0:
            return RepairReport(path, repaired=False)
        size = bag.seek(0, os.SEEK_END)
        chunks, connections, stop = _scan_chunks(bag, header_end)
        damage = _damage_at(bag, stop, size)
        if damage is not None:
            raise BagError(f"{path} is damaged at byte {stop} ({damage}); not repaired")
        kept, index_pos = _rewrite_tail(bag, header_end, chunks, connections)
        _write_bag_header(bag, header_end, index_pos, len(connections), len(chunks))
        bag.flush()
        os.fsync(bag.fileno())
    report = RepairReport(
        path,
        repaired=True,
        chunks=len(chunks),
        messages=sum(len(items) for chunk in chunks for items in chunk.entries.values()),
        connections=len(connections),
        truncated_bytes=size - kept,
    )
    log.warning(
        "repaired unindexed bag %s: %d chunks, %d messages kept, %d trailing bytes dropped",
        path,
        report.chunks,
        report.messages,
        report.truncated_bytes,
    )
    return report


def _read_bag_header(bag: BinaryIO) -> tuple[int, int]:
    """(index_pos, offset past the padded bag-header record)."""
    if bag.read(len(MAGIC)) != MAGIC:
        raise BagError(f"{getattr(bag, 'name', 'file')} is not a ROS 1 v2.0 bag")
    try:
        header = Header.read(bag, RecordType.BAGHEADER)
        index_pos = header.get_uint64("index_pos")
        padding = read_uint32(bag)
    except (ReaderError, KeyError, ValueError) as exc:  # ValueError: names that are not UTF-8
        raise BagError(f"bag header unreadable: {exc}") from exc
    return index_pos, bag.tell() + padding


def _scan_chunks(
    bag: BinaryIO, start: int
) -> tuple[list[_ScannedChunk], dict[int, Connection], int]:
    """The complete chunks from `start` on, the connections declared inside them, and the
    offset of the record the scan stopped at."""
    chunks: list[_ScannedChunk] = []
    connections: dict[int, Connection] = {}
    bag.seek(start)
    while True:
        pos = bag.tell()
        try:
            header = Header.read(bag)
            if header.get_uint8("op") != RecordType.CHUNK:
                break  # a partly written index, or garbage: the chunks end here
            decompress = decompressors[header.get_string("compression")]
            raw = decompress(read_bytes(bag, read_uint32(bag)))
            if len(raw) != header.get_uint32("size"):
                break
            chunk = _ScannedChunk(pos, bag.tell(), None)
            _scan_chunk_records(raw, chunk, connections)
        except (ReaderError, KeyError, ValueError, OSError, EOFError):
            break  # the trailing chunk was cut mid-write
        chunks.append(chunk)
        chunk.index_end = _skip_index_records(bag, len(chunk.entries))
        if chunk.index_end is None:
            pos = chunk.end
            break
    return chunks, connections, pos


def _damage_at(bag: BinaryIO, stop: int, size: int) -> str | None:
    """Why the bytes from `stop` on are damage rather than a write a crash cut short;
    None when they are only that (or nothing)."""
    bag.seek(stop)
    length = bag.read(4)
    header_end = stop + 4 + int.from_bytes(length, "little")
    if len(length) < 4 or header_end > size:
        return None  # the record's header was being written: nothing can follow it
    try:
        bag.seek(stop)
        op = Header.read(bag).get_uint8("op")
    except (ReaderError, KeyError, ValueError, EOFError):
        return "a whole record that cannot be read"
    data_length = bag.read(4)
    if len(data_length) < 4:
        return None
    if op == RecordType.CHUNK and bag.tell() + int.from_bytes(data_length, "little") <= size:
        return "a whole chunk that cannot be read"
    with mmap.mmap(bag.fileno(), 0, access=mmap.ACCESS_READ) as view:
        if view.find(CHUNK_OP_FIELD, header_end) != -1:
            return "chunks follow it"
    return None


def _scan_chunk_records(
    raw: bytes, chunk: _ScannedChunk, connections: dict[int, Connection]
) -> None:
    records = BytesIO(raw)
    entries: dict[int, list[tuple[int, int]]] = defaultdict(list)
    while records.tell() < len(raw):
        offset = records.tell()
        header = Header.read(records)
        op = header.get_uint8("op")
        if op == RecordType.CONNECTION:
            cid = header.get_uint32("conn")
            connections[cid] = _connection(cid, header.get_string("topic"), Header.read(records))
        elif op == RecordType.MSGDATA:
            entries[header.get_uint32("conn")].append((header.get_time("time"), offset))
            records.seek(read_uint32(records), os.SEEK_CUR)
        else:
            raise ReaderError(f"unexpected record {op} inside a chunk")
    chunk.entries = dict(entries)


def _connection(cid: int, topic: str, fields: Header) -> Connection:
    latching = fields.get_string("latching") if "latching" in fields else ""
    return Connection(
        cid,
        topic,
        normalize_msgtype(fields.get_string("type")),
        MessageDefinition(MessageDefinitionFormat.MSG, fields.get_string("message_definition")),
        fields.get_string("md5sum"),
        0,
        ConnectionExtRosbag1(
            fields.get_string("callerid") if "callerid" in fields else None,
            int(latching) if latching else None,
        ),
        None,
    )


def _skip_index_records(bag: BinaryIO, expected: int) -> int | None:
    """Offset past the chunk's `expected` index-data records, None if they are cut short."""
    try:
        for _ in range(expected):
            Header.read(bag, RecordType.IDXDATA)
            read_bytes(bag, read_uint32(bag))
    except ReaderError:
        return None
    return bag.tell()


def _rewrite_tail(
    bag: BinaryIO,
    header_end: int,
    chunks: list[_ScannedChunk],
    connections: dict[int, Connection],
) -> tuple[int, int]:
    """Cut the file after the last complete chunk and append the index.

    Returns the length of the file kept and the offset of the index.
    """
    last = chunks[-1] if chunks else None
    kept = header_end if last is None else last.index_end or last.end
    bag.seek(kept)
    bag.truncate()
    if last is not None and last.index_end is None:
        _write_index_data(bag, last)
    index_pos = bag.tell()
    for cid in sorted(connections):
        Writer.write_connection(connections[cid], bag)
    for chunk in chunks:
        _write_chunk_info(bag, chunk)
    return kept, index_pos


def _write_index_data(bag: BinaryIO, chunk: _ScannedChunk) -> None:
    for cid, items in chunk.entries.items():
        header = RecordHeader()
        header.set_uint32("ver", 1)
        header.set_uint32("conn", cid)
        header.set_uint32("count", len(items))
        header.write(bag, RecordType.IDXDATA)
        bag.write(serialize_uint32(len(items) * 12))
        for stamp, offset in items:
            bag.write(serialize_time(stamp) + serialize_uint32(offset))


def _write_chunk_info(bag: BinaryIO, chunk: _ScannedChunk) -> None:
    stamps = [stamp for items in chunk.entries.values() for stamp, _ in items]
    header = RecordHeader()
    header.set_uint32("ver", 1)
    header.set_uint64("chunk_pos", chunk.pos)
    header.set_time("start_time", min(stamps, default=0))
    header.set_time("end_time", max(stamps, default=0))
    header.set_uint32("count", len(chunk.entries))
    header.write(bag, RecordType.CHUNK_INFO)
    bag.write(serialize_uint32(len(chunk.entries) * 8))
    for cid, items in chunk.entries.items():
        bag.write(serialize_uint32(cid) + serialize_uint32(len(items)))


def _write_bag_header(
    bag: BinaryIO, header_end: int, index_pos: int, conn_count: int, chunk_count: int
) -> None:
    """Point the header at the index, keeping the header record's padded length."""
    bag.seek(len(MAGIC))
    header = RecordHeader()
    header.set_uint64("index_pos", index_pos)
    header.set_uint32("conn_count", conn_count)
    header.set_uint32("chunk_count", chunk_count)
    size = header.write(bag, RecordType.BAGHEADER)
    padding = header_end - len(MAGIC) - size - 4
    bag.write(serialize_uint32(padding) + b" " * padding)
