#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Writes the seed corpora fuzz/corpus/<target>/ (small files, a handful per
# target, each a few KB at most), deterministically: run it again after
# changing it and commit the result. Python 3 (standard library) packs the
# binary formats; the LZF blocks of binary_compressed PCD are made by a
# small greedy compressor below (the format of io/lzf.hpp).
#
# Usage: fuzz/make_seeds.sh
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
exec python3 - "$ROOT/corpus" <<'PY'
import os, random, struct, sys

out = sys.argv[1]

def put(target, name, data):
    d = os.path.join(out, target)
    os.makedirs(d, exist_ok=True)
    if isinstance(data, str):
        data = data.encode()
    with open(os.path.join(d, name), "wb") as f:
        f.write(data)

def lzf(data):
    """Greedy LZF: literal runs of <= 32 bytes, back references of 3-264 bytes within 8 KiB."""
    o, lit, i, n, last = bytearray(), bytearray(), 0, len(data), {}
    def flush():
        for k in range(0, len(lit), 32):
            chunk = lit[k:k + 32]
            o.append(len(chunk) - 1)
            o.extend(chunk)
        lit.clear()
    while i < n:
        key = data[i:i + 3]
        cand = last.get(key) if len(key) == 3 else None
        last[key] = i
        if cand is not None and i - cand <= 8192:
            length = 3
            while length < 264 and i + length < n and data[cand + length] == data[i + length]:
                length += 1
            flush()
            off, l = i - cand - 1, length - 2
            if l < 7:
                o.append((l << 5) | (off >> 8))
            else:
                o.append((7 << 5) | (off >> 8))
                o.append(l - 7)
            o.append(off & 0xFF)
            i += length
        else:
            lit.append(data[i])
            i += 1
    flush()
    return bytes(o)

# A few points of a small scene: (x, y, z, intensity, t, label)
pts = [(1.0 + 0.1 * k, -0.5 + 0.05 * k, 0.2, 10.0 * k, 0.0001 * k, k // 3) for k in range(8)]

# ---------------------------------------------------------------- CSV
put("fuzz_csv", "header.csv",
    "x,y,z,intensity,t,label\n" + "".join("%g,%g,%g,%g,%.6f,%d\n" % p for p in pts))
put("fuzz_csv", "headerless_blanks.csv", "".join("%g %g\t%g %g\n" % p[:4] for p in pts))
put("fuzz_csv", "livox_viewer.csv",
    "Version,Slot ID,LiDAR Index,Rsvd,Error Code,Timestamp Type,Data Type,Timestamp,X,Y,Z,Reflectivity,Tag,\n" +
    "".join("5,1,1,0,0x00000000,0,1,%d,%g,%g,%g,%d,0,\n" % (1700000000123456789 + 4166 * k, p[0], p[1], p[2], k)
            for k, p in enumerate(pts)))
put("fuzz_csv", "bom_quoted_epoch.csv",
    "\ufeff\"X\",\"Y\",\"Z\",\"time\",\"gt\"\r\n# a comment\r\n\r\n" +
    "1,2,nan,inf,3\r\n" +
    "".join("%g,%g,%g,1700000003.%09d,%d\r\n" % (p[0], p[1], p[2], 123456789 + k, p[5]) for k, p in enumerate(pts)))
put("fuzz_csv", "offset_time.csv",
    "x,y,z,reflectivity,offset_time,object\n" + "".join("%g,%g,%g,%d,%d,%d\n" % (p[0], p[1], p[2], k, 4166 * k, -1)
                                                         for k, p in enumerate(pts)))

# ---------------------------------------------------------------- PCD
def pcd_header(fields, sizes, types, counts, n, data, width=None, height=1, extra=""):
    return ("# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS %s\nSIZE %s\nTYPE %s\nCOUNT %s\n"
            "WIDTH %d\nHEIGHT %d\nVIEWPOINT 0 0 0 1 0 0 0\n%sPOINTS %d\nDATA %s\n" %
            (" ".join(fields), " ".join(map(str, sizes)), " ".join(types), " ".join(map(str, counts)),
             n if width is None else width, height, extra, n, data))

fields, sizes, types, counts = ["x", "y", "z", "intensity", "t", "label"], [4, 4, 4, 4, 8, 4], list("FFFFFI"), [1] * 6
fmt = "<ffffdi"
put("fuzz_pcd", "ascii.pcd", pcd_header(fields, sizes, types, counts, len(pts), "ascii") +
    "".join("%g %g %g %g %.6f %d\n" % p for p in pts))
put("fuzz_pcd", "binary.pcd", pcd_header(fields, sizes, types, counts, len(pts), "binary").encode() +
    b"".join(struct.pack(fmt, *p) for p in pts))
soa = b"".join(b"".join(struct.pack("<" + fmt[1 + f], p[f]) for p in pts) for f in range(6))
block = lzf(soa)
put("fuzz_pcd", "binary_compressed.pcd", pcd_header(fields, sizes, types, counts, len(pts), "binary_compressed").encode() +
    struct.pack("<II", len(block), len(soa)) + block)
zeros = bytes(16 * 40)  # 40 points at the origin: long back references
zblock = lzf(zeros)
put("fuzz_pcd", "binary_compressed_zeros.pcd",
    pcd_header(["x", "y", "z", "reflectivity"], [4, 4, 4, 4], list("FFFF"), [1] * 4, 40, "binary_compressed").encode() +
    struct.pack("<II", len(zblock), len(zeros)) + zblock)
# Livox-style: offset_time (U4, ns), padding `_`, a field with COUNT 3, WIDTH 0 HEIGHT 0.
put("fuzz_pcd", "livox_padding.pcd",
    pcd_header(["x", "y", "z", "_", "normal", "offset_time"], [4, 4, 4, 1, 4, 4], list("FFFUFU"), [1, 1, 1, 4, 3, 1],
               len(pts), "binary", width=0, height=0).encode() +
    b"".join(struct.pack("<fff4sfffI", p[0], p[1], p[2], b"\0" * 4, 0, 0, 1, 4166 * k) for k, p in enumerate(pts)))
put("fuzz_pcd", "ascii_types.pcd",
    "VERSION .7\nFIELDS x y z time gt\nSIZE 8 8 8 8 2\nTYPE F F F F I\nCOUNT 1 1 1 1 1\nWIDTH 4\nHEIGHT 2\nPOINTS 8\n"
    "DATA ascii\n" + "".join("%r %r %r 1700000000.%09d %d\n" % (p[0], p[1], p[2], k, -k) for k, p in enumerate(pts)) +
    "\n \t\n")

# ---------------------------------------------------------------- PLY
put("fuzz_ply", "ascii.ply",
    "ply\nformat ascii 1.0\ncomment made by make_seeds.sh\nobj_info none\nelement vertex %d\n"
    "property float x\nproperty float y\nproperty float z\nproperty uchar intensity\nproperty double time\n"
    "property list uchar int extra\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n" % len(pts) +
    "".join("%g %g %g %d %.6f 2 %d %d\n" % (p[0], p[1], p[2], k, p[4], k, k + 1) for k, p in enumerate(pts)) +
    "3 0 1 2\n")
put("fuzz_ply", "binary.ply",
    ("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float32 x\nproperty float32 y\n"
     "property float32 z\nproperty float64 t\nproperty int label\nproperty uint8 red\nproperty uchar green\n"
     "property uchar blue\nelement edge 1\nproperty int vertex1\nproperty int32 vertex2\nend_header\n" % len(pts)).encode() +
    b"".join(struct.pack("<fffdiBBB", p[0], p[1], p[2], p[4], p[5], 1, 2, 3) for p in pts) + struct.pack("<ii", 0, 1))
put("fuzz_ply", "binary_lists.ply",
    ("ply\nformat binary_little_endian 1.0\nelement camera 1\nproperty short view\nelement vertex 3\n"
     "property list ushort char tags\nproperty double x\nproperty double y\nproperty double z\n"
     "property uint offset_time\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n").encode() +
    struct.pack("<h", 7) +
    b"".join(struct.pack("<H", 2) + b"ab" + struct.pack("<dddI", 1.5 + k, 2.0, -0.5, 4166 * k) for k in range(3)) +
    struct.pack("<BIII", 3, 0, 1, 2))
put("fuzz_ply", "ascii_int_types.ply",
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty int8 x\nproperty int16 y\nproperty uint32 z\n"
    "property float scalar_intensity\nproperty int64 instance\nend_header\n1 -2 3 0.5 -1\n4 5 6 nan 9\n"
    "-7 8 9 inf 2\n0 0 0 0 0\n\n")

# ---------------------------------------------------------------- KITTI
kitti = lambda rows: b"".join(struct.pack("<ffff", *r) for r in rows)
put("fuzz_kitti", "four.bin", kitti([p[:4] for p in pts[:4]]))
put("fuzz_kitti", "special.bin", kitti([(float("nan"), 1, 2, 0), (float("inf"), 0, 0, 0), (1e30, -1e30, 0, 1e-40)]))
put("fuzz_kitti", "one.bin", kitti([(10.0, 0.0, -1.5, 0.25)]))

# ---------------------------------------------------------------- LVX / LVX2
# The reader's test fixtures (tests/data/lvx, written by make_lvx.py there;
# 1.7-4.3 KB each): every LVX version and data type, one and two LiDARs.
lvx_dir = os.path.join(out, "..", "..", "tests", "data", "lvx")
for name in sorted(os.listdir(lvx_dir)):
    if name.endswith((".lvx", ".lvx2")):
        with open(os.path.join(lvx_dir, name), "rb") as f:
            put("fuzz_lvx", name, f.read())

# ---------------------------------------------------------------- recordings
# The recording readers' test fixtures (tests/data/recordings, written by
# python3-rosbag, @mcap/core and sqlite3 there; 15-30 KB each). MCAP seeds get
# their CRCs zeroed ("not computed" in the specification), so that mutations
# reach the records instead of stopping at a CRC mismatch.
rec_dir = os.path.join(out, "..", "..", "tests", "data", "recordings")
def rec(name):
    with open(os.path.join(rec_dir, name), "rb") as f:
        return f.read()

def mcap_records(b, start, end):
    at = start
    while at + 9 <= end:
        op, length = b[at], struct.unpack_from("<Q", b, at + 1)[0]
        yield at, op, b[at + 9:at + 9 + length]
        at += 9 + length

def mcap_without_crcs(b):
    b = bytearray(b)
    summary_start = struct.unpack_from("<Q", b, len(b) - 8 - 20)[0]
    end = summary_start if summary_start else len(b) - 8 - 29
    for at, op, _ in mcap_records(bytes(b), 8, end):
        if op == 0x06:
            struct.pack_into("<I", b, at + 9 + 24, 0)   # chunk uncompressed_crc
        if op == 0x0F:
            struct.pack_into("<I", b, at + 9, 0)        # data_section_crc
    struct.pack_into("<I", b, len(b) - 8 - 4, 0)        # summary_crc
    return bytes(b)

for name in ["ros2_pc2_converter.mcap", "ros2_pc2_ouster.mcap", "ros2_custom_lz4.mcap", "ros2_custom_zstd.mcap"]:
    put("fuzz_mcap", name, mcap_without_crcs(rec(name)))
for name in ["ros1_custom.bag", "ros1_custom_lz4.bag", "ros1_custom_bz2.bag", "ros1_pc2_livox.bag"]:
    put("fuzz_bag", name, rec(name))
put("fuzz_db3", "ros2_pc2_old.db3", rec("ros2_pc2_old.db3"))
put("fuzz_db3", "ros2_custom.db3", rec("ros2_custom_db3/ros2_custom_db3_0.db3"))

def mcap_messages(b):
    """Payloads of the Message records, top level and in uncompressed chunks."""
    summary_start = struct.unpack_from("<Q", b, len(b) - 8 - 20)[0]
    end = summary_start if summary_start else len(b) - 8 - 29
    for _, op, content in mcap_records(b, 8, end):
        if op == 0x05:
            yield content[22:]
        if op == 0x06:
            clen = struct.unpack_from("<I", content, 28)[0]
            compression = content[32:32 + clen]
            records = content[32 + clen + 8:]
            if compression == b"":
                for _, op2, c2 in mcap_records(records, 0, len(records)):
                    if op2 == 0x05:
                        yield c2[22:]

def bag_messages(b):
    """Payloads of the message records in a bag's uncompressed chunks."""
    def records(buf, at, end):
        while at + 4 <= end:
            hl = struct.unpack_from("<I", buf, at)[0]
            header = buf[at + 4:at + 4 + hl]
            dl = struct.unpack_from("<I", buf, at + 4 + hl)[0]
            data = buf[at + 8 + hl:at + 8 + hl + dl]
            fields, i = {}, 0
            while i < len(header):
                fl = struct.unpack_from("<I", header, i)[0]
                k, _, v = header[i + 4:i + 4 + fl].partition(b"=")
                fields[k] = v
                i += 4 + fl
            yield fields, data
            at += 8 + hl + dl
    for fields, data in records(b, 13, len(b)):
        if fields.get(b"op") == b"\x05" and fields.get(b"compression") == b"none":
            for f2, d2 in records(data, 0, len(data)):
                if f2.get(b"op") == b"\x02":
                    yield d2

# One message per case; the first byte picks type and encoding (fuzz_ros_message.cpp).
largest = lambda payloads: max(payloads, key=len)
put("fuzz_ros_message", "ros1_custom", b"\x00" + largest(bag_messages(rec("ros1_custom.bag"))))
put("fuzz_ros_message", "ros1_cloud_livox", b"\x01" + largest(bag_messages(rec("ros1_pc2_livox.bag"))))
put("fuzz_ros_message", "cdr_custom", b"\x02" + largest(mcap_messages(rec("ros2_no_schema.mcap"))))
put("fuzz_ros_message", "cdr_cloud_converter", b"\x03" + largest(mcap_messages(rec("ros2_pc2_converter.mcap"))))
put("fuzz_ros_message", "cdr_cloud_ouster_rate", b"\x07" + largest(mcap_messages(rec("ros2_pc2_ouster.mcap"))))

# ---------------------------------------------------------------- LZF
# An input is a 2-byte little-endian declared size, then the compressed bytes.
for name, raw in [("text", b"streamclust streamclust streamclust: continuous clustering, continuous!"),
                  ("zeros", bytes(600)), ("points", soa)]:
    c = lzf(raw)
    put("fuzz_lzf", name, struct.pack("<H", len(raw)) + c)
put("fuzz_lzf", "bad_reference", struct.pack("<H", 64) + bytes([0x00, 0x41, 0xE0, 0x20, 0x05]))
put("fuzz_lzf", "truncated_literal", struct.pack("<H", 10) + bytes([0x09, 1, 2, 3]))

# ---------------------------------------------------------------- TUM
put("fuzz_tum", "simple.tum", "# t tx ty tz qx qy qz qw\n" +
    "".join("%.3f %.3f 0 0 0 0 %.6f %.6f\n" % (0.1 * k, 0.2 * k, 0.0998 * k, 1.0) for k in range(6)))
put("fuzz_tum", "epoch_tabs.tum",
    "".join("1700000000.%09d\t1.5\t-2\t0.25\t0\t0\t0\t1\r\n" % (5000000 * k + 1) for k in range(5)) + "\n# end\n")
put("fuzz_tum", "exponents.tum", "  1e-3 1E2 -0.0 +3 0.5 0.5 0.5 0.5\n\n2.5e0 0 0 0 1e-3 0 0 0\n")

# ---------------------------------------------------------------- CLI options (one argument per line)
put("fuzz_cli_options", "cluster_preset", "scan.csv\n--preset\ncarc-mid360\n--labels\nlabels.csv\n--cycles\n0,3,7\n")
put("fuzz_cli_options", "cluster_objects",
    "in.pcd\n--preset\nobjects-avia\n--mount\n0,15,0\n--sensor-height\n1.2\n--window-count\n1000\n--connectivity\n"
    "lazy-bfs\n--ground-cell\n0.5\n--max-slope\n20\n--no-ceiling\n--poses\nodom.tum\n")
put("fuzz_cli_options", "cluster_inputs",
    "in.bin\n--format\nkitti\n--point-rate\n1200000\n--time-origin\n1700000000\n--verify\n--grid\n32x1800\n"
    "--fov-azimuth\n-35:35\n--mask\n7\n--index\ncapped\n--cap\n3\n--time-unit\nns\n--max-time-jump\n0.5\n")
put("fuzz_cli_options", "simulate",
    "--sensor\navia\n--scene\nforest\n--duration\n2.5\n--burst\n1:0.3\n--burst-yaw-rate\n3\n--out\nx.csv\n"
    "--start-time\n1700000000\n--class-column\n")
put("fuzz_cli_options", "evaluate_objects",
    "--method\nobjects,carc\n--height\n2\n--poses\noff\n--sensor\nmid360\n--mount\n180,0,0\n--window-time\n0.5\n"
    "--rate\n20\n--ransac-iterations\n50\n")
put("fuzz_cli_options", "evaluate",
    "--sensor\nmid70\n--scene\nstreet\n--linkage\neuclidean\n--distance\n0.3\n--structure\ndrop\n--frames\ntumbling\n"
    "--multiplicity\n1.25\n--min-points\n5\n")

# ---------------------------------------------------------------- Livox SDK2 datagrams
# Data packets (36-byte header, live/sdk2_packets.hpp) of every data type and
# control frames (24-byte header, live/sdk2_control.hpp) of the messages both
# sides exchange. binascii.crc32 is CRC-32/ISO-HDLC; crc16 is CCITT-FALSE.
import binascii, math

def crc16_ccitt_false(b):
    c = 0xFFFF
    for byte in b:
        c ^= byte << 8
        for _ in range(8):
            c = ((c << 1) ^ 0x1021) & 0xFFFF if c & 0x8000 else (c << 1) & 0xFFFF
    return c

def sdk2_packet(data_type, slots, body, time_interval=4750, udp_cnt=1, time_type=0, crc=False, t0=1700000000123456789):
    length = 36 + len(body)
    head = struct.pack("<BHHHHBBB12sI", 0, length, time_interval, slots, udp_cnt, 0, data_type, time_type, bytes(12), 0)
    b = bytearray(head + struct.pack("<Q", t0) + body)
    if crc:
        struct.pack_into("<I", b, 24, binascii.crc32(bytes(b[28:])))
    return bytes(b)

ring = [(2.0 * math.cos(0.3 * k), 2.0 * math.sin(0.3 * k), 0.1 * (k % 5) - 0.2) for k in range(12)]
put("fuzz_livox_sdk2_packet", "type1_mm",
    sdk2_packet(1, 12, b"".join(struct.pack("<iiiBB", round(x * 1000), round(y * 1000), round(z * 1000), 20 + k, k % 3)
                                 if k != 4 else bytes(12) + bytes([60, 0]) for k, (x, y, z) in enumerate(ring))))
put("fuzz_livox_sdk2_packet", "type2_cm_crc",
    sdk2_packet(2, 12, b"".join(struct.pack("<hhhBB", round(x * 100), round(y * 100), round(z * 100), 7, 0x15)
                                 for x, y, z in ring), udp_cnt=65535, time_type=1, crc=True))
put("fuzz_livox_sdk2_packet", "type3_spherical",
    sdk2_packet(3, 12, b"".join(struct.pack("<IHHBB", 0 if k == 7 else 1500 + 250 * k, 6000 + 900 * k, (3000 * k) % 36000,
                                            k, 0) for k in range(12)), time_type=2))
put("fuzz_livox_sdk2_packet", "type17_dual",
    sdk2_packet(0x11, 6, b"".join(struct.pack("<iiiBB", round(x * 1000), round(y * 1000), round(z * 1000), 30, 1) +
                                   (bytes(14) if k % 2 else struct.pack("<iiiBB", round(x * 1100), round(y * 1100), 0, 9, 2))
                                   for k, (x, y, z) in enumerate(ring[:6]))))
put("fuzz_livox_sdk2_packet", "imu_crc",
    sdk2_packet(0, 1, struct.pack("<6f", 0.01, -0.02, 0.5, 0.0, -0.05, 0.998), time_interval=0, crc=True))

def sdk2_control(seq, cmd_id, cmd_type, sender, data=b""):
    head = bytearray(struct.pack("<BBHIHBB6s", 0xAA, 0, 24 + len(data), seq, cmd_id, cmd_type, sender, bytes(6)))
    head += struct.pack("<HI", crc16_ccitt_false(head), binascii.crc32(data))
    return bytes(head) + data

def kv(key, value):
    return struct.pack("<HH", key, len(value)) + value

host = bytes([192, 168, 1, 50])
put("fuzz_livox_sdk2_control", "discovery_req", sdk2_control(1, 0x0000, 0, 0))
put("fuzz_livox_sdk2_control", "discovery_ack",
    sdk2_control(1, 0x0000, 1, 1, struct.pack("<BB16s4sH", 0, 9, b"47MDL9A0020123", bytes([192, 168, 1, 123]), 56100)))
put("fuzz_livox_sdk2_control", "set_parameters",
    sdk2_control(2, 0x0100, 0, 0, struct.pack("<HH", 6, 0) +
                 kv(0x0005, host + struct.pack("<HH", 56201, 56200)) + kv(0x0006, host + struct.pack("<HH", 56301, 56300)) +
                 kv(0x0007, host + struct.pack("<HH", 56401, 56400)) + kv(0x001A, b"\x01") + kv(0x0000, b"\x01") +
                 kv(0x001C, b"\x01")))
put("fuzz_livox_sdk2_control", "set_parameters_ack", sdk2_control(2, 0x0100, 1, 1, struct.pack("<BH", 0x20, 0x001C)))
put("fuzz_livox_sdk2_control", "status_push", sdk2_control(3, 0x0102, 0, 1, b'{"cur_work_state":1,"core_temp":4500}'))
# ---------------------------------------------------------------- Livox SDK1 packets and control frames
def sdk1_packet(data_type, time_type, stamp, structs):
    head = struct.pack("<BBBBIBB", 5, 0, 1, 0, 0, time_type, data_type)
    return head + (stamp if isinstance(stamp, bytes) else struct.pack("<Q", stamp)) + b"".join(structs)

def sdk1_cart(k, tag=None):
    p = struct.pack("<iiiB", 1000 + 7 * k, -2000 + 3 * k, 150 - k, k % 256)
    return p if tag is None else p + bytes([tag])

def sdk1_sph(k, tag=None):
    p = struct.pack("<IHHB", 5000 + 11 * k, 4500 + 13 * k, (7 * k * 100) % 36000, k % 256)
    return p if tag is None else p + bytes([tag])

empty = lambda n: bytes(n)
gps = struct.pack("<BBBBI", 26, 11, 29, 13, 1234567890)
t = 1700000000123456789
put("fuzz_livox_sdk1_packet", "type0_cartesian", sdk1_packet(0, 0, t, [sdk1_cart(k) if k % 9 else empty(13) for k in range(100)]))
put("fuzz_livox_sdk1_packet", "type1_spherical", sdk1_packet(1, 1, t, [sdk1_sph(k) if k % 9 else empty(9) for k in range(100)]))
put("fuzz_livox_sdk1_packet", "type2_extended_gps", sdk1_packet(2, 3, gps, [sdk1_cart(k, k % 64) for k in range(96)]))
put("fuzz_livox_sdk1_packet", "type3_extended_spherical", sdk1_packet(3, 4, t, [sdk1_sph(k, 0x10) for k in range(96)]))
put("fuzz_livox_sdk1_packet", "type4_dual", sdk1_packet(4, 0, t, [sdk1_cart(k, 0x10) + (sdk1_cart(k + 50, 0x20) if k % 2 else empty(14)) for k in range(48)]))
put("fuzz_livox_sdk1_packet", "type5_dual_spherical", sdk1_packet(5, 1, t, [struct.pack("<HHIBBIBB", 9000, 100 * k, 3000 + k, 9, 0x10, 4000 + k, 8, 0x20) for k in range(48)]))
put("fuzz_livox_sdk1_packet", "type6_imu", sdk1_packet(6, 3, gps, [struct.pack("<6f", 0.01, -0.02, 0.03, 0.0, 0.05, -1.0)]))
put("fuzz_livox_sdk1_packet", "type7_triple", sdk1_packet(7, 0, t, [sdk1_cart(k, 0x10) + sdk1_cart(k + 1, 0x20) + sdk1_cart(k + 2, 0x30) for k in range(30)]))
put("fuzz_livox_sdk1_packet", "type8_triple_spherical", sdk1_packet(8, 0, t, [struct.pack("<HH", 6000, 4500) + b"".join(struct.pack("<IBB", 2000 * (r + 1) + k, r, r) for r in range(3)) for k in range(30)]))

def crc16_livox(data, crc=0x4C49):
    for b in data:
        crc ^= b
        for _ in range(8):
            crc = (crc >> 1) ^ 0x8408 if crc & 1 else crc >> 1
    return crc

def crc32_livox(data):
    crc = 0x564F580A ^ 0xFFFFFFFF
    for b in data:
        crc ^= b
        for _ in range(8):
            crc = (crc >> 1) ^ 0xEDB88320 if crc & 1 else crc >> 1
    return crc ^ 0xFFFFFFFF

def sdk1_frame(packet_type, seq, cmd_set, cmd_id, data=b""):
    pre = struct.pack("<BBHBH", 0xAA, 1, len(data) + 15, packet_type, seq)
    body = pre + struct.pack("<H", crc16_livox(pre)) + bytes([cmd_set, cmd_id]) + data
    return body + struct.pack("<I", crc32_livox(body))

put("fuzz_livox_sdk1_control", "broadcast_avia", sdk1_frame(2, 0, 0, 0x00, b"3GGDJ6K00200101\0" + bytes([7, 0, 0])))
put("fuzz_livox_sdk1_control", "handshake_as_ack", sdk1_frame(1, 1, 0, 0x01, bytes([192, 168, 1, 50]) + struct.pack("<HHH", 56000, 55500, 56000)))
put("fuzz_livox_sdk1_control", "handshake_ack", sdk1_frame(1, 1, 0, 0x01, b"\0"))
put("fuzz_livox_sdk1_control", "heartbeat", sdk1_frame(0, 0x0203, 0, 0x03))
put("fuzz_livox_sdk1_control", "heartbeat_ack", sdk1_frame(1, 0x0203, 0, 0x03, struct.pack("<BBBI", 0, 1, 0, 0)))
put("fuzz_livox_sdk1_control", "start_sampling", sdk1_frame(0, 0x0405, 0, 0x04, b"\x01"))
put("fuzz_livox_sdk1_control", "return_mode_dual", sdk1_frame(0, 0x0607, 1, 0x06, b"\x02"))
put("fuzz_livox_sdk1_control", "imu_200hz_ack", sdk1_frame(1, 0x0809, 1, 0x08, b"\0"))

# ---------------------------------------------------------------- engine scenarios (engine/scenario.hpp)
def engine_seed(config, preset, window, grid, mask, ground, linkage, stress, ops):
    return bytes([config, preset, window, grid, mask, ground, linkage, stress]) + bytes(ops)

def blob_ops(rng, n_points, retrieve_every, coords, time_byte):
    ops = []
    for k in range(n_points):
        if k % 24 == 0 and k:
            ops += [160, 11] + [b for _ in range(12) for b in (rng.choice(coords), rng.choice(coords),
                                                                rng.choice(coords), time_byte(rng))]
        else:
            ops += [rng.randrange(150), rng.choice(coords), rng.choice(coords), rng.choice(coords), time_byte(rng)]
        if k % retrieve_every == retrieve_every - 1:
            ops.append(200 if k % 3 else 220)
            if ops[-1] == 220:
                ops.append(4)
    return ops

rng = random.Random(7)
near = [3, 4, 5, 6, 7, 19, 20, 21, 131, 132, 133, 148]  # 1-5 m, a few jitters
wide = list(range(0, 224, 7))
forward = lambda r: r.choice([1, 2, 3, 4, 4, 5, 6, 160])
messy = lambda r: r.choice([1, 2, 4, 5, 6, 160, 170, 130, 200, 224, 226, 240])
put("fuzz_engine", "carc_blobs", engine_seed(0, 0, 0x01, 0, 0, 0, 0, 0, blob_ops(rng, 300, 40, near, forward)))
put("fuzz_engine", "carc_lazy_fixed_grid", engine_seed(1, 1, 0x02, 0x65, 0x02, 0, 0x11, 0, blob_ops(rng, 250, 25, wide, forward)))
put("fuzz_engine", "carc_count_messy_times", engine_seed(4, 2, 0x20, 0x66, 0x04, 0x80, 0x41, 0x01, blob_ops(rng, 300, 30, near + wide, messy)))
put("fuzz_engine", "objects_ground_mount", engine_seed(6, 1, 0x85, 0, 0x80, 0x19, 0x20, 0, blob_ops(rng, 350, 50, near + [99, 115], forward)))
put("fuzz_engine", "objects_lazy_estimate", engine_seed(7, 0, 0x80, 0, 0x80, 0x00, 0x00, 0, blob_ops(rng, 300, 60, near + [99, 115], forward)))
put("fuzz_engine", "overwrite_folds", engine_seed(3, 0, 0x03, 0x64, 0x05, 0x02, 0x02, 0x05, blob_ops(rng, 300, 20, near, forward)))
put("fuzz_engine", "cylindrical_count", engine_seed(9, 0, 0x28, 0, 0x03, 0x02, 0x30, 0, blob_ops(rng, 250, 35, wide, messy)))
PY
