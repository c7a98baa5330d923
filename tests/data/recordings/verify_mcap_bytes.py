#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""verify_mcap_bytes.py -- byte-level check of the MCAP fixtures, written from the MCAP spec
(no MCAP library): record walk, every CRC (chunk uncompressed_crc, DataEnd data_section_crc,
Footer summary_crc) recomputed with zlib.crc32, chunks decompressed with python3-lz4's lz4.frame
(liblz4) and the `zstd` command line tool (libzstd), messages decoded with fixture_check.py's CDR
decoder and compared with the expected CSVs.

Usage: /usr/bin/python3 verify_mcap_bytes.py      (exit status 1 on any mismatch)
"""
import struct
import subprocess
import sys
import zlib

sys.dont_write_bytecode = True  # keep the source tree free of __pycache__
from fixture_check import HERE, Mismatch, cdr_custom, cdr_pc2, compare, load_expected

try:
    import lz4.frame as lz4frame
except ImportError:
    lz4frame = None

MAGIC = b"\x89MCAP0\r\n"
FIXTURES = {
    # file: (lidar decoder, expected CSV or None, chunk compression or None = unchunked, has summary)
    "ros2_custom_lz4.mcap": ("custom", "custom.expected.csv", "lz4", True),
    "ros2_custom_zstd.mcap": ("custom", "custom.expected.csv", "zstd", True),
    "ros2_pc2_converter.mcap": ("pc2", "pc2_offset_u32.expected.csv", None, False),
    "ros2_pc2_ouster.mcap": ("pc2", "pc2_ouster.expected.csv", "", True),
    "ros2_pc2_velodyne.mcap": ("pc2", "pc2_velodyne.expected.csv", "lz4", True),
    "ros2_pc2_bigendian.mcap": ("pc2", "pc2_offset_u32.expected.csv", "zstd", True),
    "ros2_no_schema.mcap": ("custom", None, "", True),
}


def s32(b, o):
    n = struct.unpack_from("<I", b, o)[0]
    return b[o + 4:o + 4 + n].decode(), o + 4 + n


def records(b, o, end):
    while o < end:
        op = b[o]
        ln = struct.unpack_from("<Q", b, o + 1)[0]
        yield o, op, b[o + 9:o + 9 + ln]
        o += 9 + ln


def decompress(comp, data, usize):
    if comp == "":
        return data
    if comp == "lz4":
        if lz4frame is None:
            raise Mismatch("python3-lz4 missing")
        return lz4frame.decompress(data)
    if comp == "zstd":
        return subprocess.run(["zstd", "-d", "-c", "-q"], input=data, stdout=subprocess.PIPE, check=True).stdout
    raise Mismatch(f"compression {comp!r}")


def check(name, kind, csv, want_comp, want_summary):
    b = open(f"{HERE}/{name}", "rb").read()
    if b[:8] != MAGIC or b[-8:] != MAGIC:
        raise Mismatch("magic")
    schemas, channels, msgs, chunks, facts = {}, {}, [], [], []
    data_end = footer = None

    def handle(op, c, inside_chunk):
        nonlocal data_end
        if op == 0x01:
            profile, o = s32(c, 0)
            library, _ = s32(c, o)
            if profile != "ros2":
                raise Mismatch(f"profile {profile!r}")
            facts.append(f"library {library!r}")
        elif op == 0x03:
            sid = struct.unpack_from("<H", c, 0)[0]
            sname, o = s32(c, 2)
            enc, o = s32(c, o)
            schemas[sid] = (sname, enc)
        elif op == 0x04:
            cid, sid = struct.unpack_from("<HH", c, 0)
            topic, o = s32(c, 4)
            menc, o = s32(c, o)
            channels[cid] = (sid, topic, menc)
        elif op == 0x05:
            cid, seq, log_t, pub_t = struct.unpack_from("<HIQQ", c, 0)
            msgs.append((cid, log_t, c[22:]))
        elif op == 0x06:
            if inside_chunk:
                raise Mismatch("nested chunk")
            st, en, usize, crc = struct.unpack_from("<QQQI", c, 0)
            comp, o = s32(c, 28)
            rlen = struct.unpack_from("<Q", c, o)[0]
            raw = decompress(comp, c[o + 8:o + 8 + rlen], usize)
            if len(raw) != usize:
                raise Mismatch("chunk uncompressed_size")
            if crc != zlib.crc32(raw):
                raise Mismatch("chunk crc")
            chunks.append((comp, usize, rlen, crc != 0))
            for _, op2, c2 in records(raw, 0, len(raw)):
                handle(op2, c2, True)
        elif op == 0x0F:
            data_end = struct.unpack_from("<I", c, 0)[0]

    o = 8
    data_end_pos = None
    for pos, op, c in records(b, 8, len(b) - 8):
        if op == 0x0F:
            data_end_pos = pos
            handle(op, c, False)
            break
        handle(op, c, False)
    # DataEnd CRC covers everything from the file start up to the DataEnd record
    if data_end != zlib.crc32(b[:data_end_pos]):
        raise Mismatch("data_section_crc")
    # Footer: last record before the trailing magic (opcode 1 + length 8 + 20 bytes)
    fpos = len(b) - 8 - 29
    if b[fpos] != 0x02:
        raise Mismatch("footer position")
    summary_start, summary_offset_start, summary_crc = struct.unpack_from("<QQI", b, fpos + 9)
    summary_ops = []
    if summary_start:
        for _, op, c in records(b, summary_start, fpos):
            summary_ops.append(op)
        if summary_crc != zlib.crc32(b[summary_start:fpos + 9 + 16]):
            raise Mismatch("summary_crc")
    if bool(summary_start) != want_summary:
        raise Mismatch(f"summary_start {summary_start}")
    comps = {c[0] for c in chunks}
    if want_comp is None:
        if chunks:
            raise Mismatch("unexpected chunks")
    elif comps != {want_comp} or len(chunks) < 2:
        raise Mismatch(f"chunks {chunks}")
    lidar = [cid for cid, ch in channels.items() if ch[1] == "/livox/lidar"]
    if len(lidar) != 1 or channels[lidar[0]][2] != "cdr":
        raise Mismatch("channels")
    sid = channels[lidar[0]][0]
    if csv is None:  # the no-schema fixture
        if sid != 0:
            raise Mismatch("schema_id should be 0")
        facts.append("lidar channel schema_id 0")
    else:
        if schemas[sid][1] != "ros2msg":
            raise Mismatch("schema encoding")
        points = []
        for cid, log_t, data in msgs:
            if cid != lidar[0]:
                continue
            if kind == "custom":
                stamp, frame, _, pts, _ = cdr_custom(data)
            else:
                stamp, frame, pts, cloud, _ = cdr_pc2(data)
                facts.append(f"frame {frame!r} h{cloud['height']} w{cloud['width']} step {cloud['point_step']} "
                             f"be={int(cloud['is_bigendian'])} dense={int(cloud['is_dense'])}")
            if stamp != log_t:
                raise Mismatch("log_time != header stamp")
            points += pts
        compare(name, points, load_expected(csv))
    facts.append(f"{len(chunks)} chunks {sorted(comps)}" if chunks else "unchunked")
    facts.append(f"summary ops {sorted(set(summary_ops))}" if summary_start else "no summary (summary_start 0)")
    facts.append(f"summary_crc {'%#x' % summary_crc}, data_crc {'%#x' % data_end}")
    return sorted(set(facts), key=facts.index)


def main():
    ok = True
    for name, spec in FIXTURES.items():
        try:
            facts = check(name, *spec)
            print(f"ok   {name}: " + "; ".join(facts))
        except Exception as e:  # noqa: BLE001
            ok = False
            print(f"FAIL {name}: {type(e).__name__}: {e}")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
