#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes the LVX / LVX2 test fixtures and, for each, the points a reader must
return (`<name>.expected.csv`, or `<name>.index<N>.expected.csv` per LiDAR of a
multi-LiDAR file).

Written from the format descriptions, not from the library's reader:
- LVX 1.1 / 1.0: the Livox SDK's LVX writer and the Livox ROS driver's reader
  (public header, private header, device info, frames, packages) and the SDK 1
  point structs (livox_def.h);
- LVX2: "LVX2 Specifications" v1.0 (Livox, 2023).

Expected values:
- x, y, z in metres as exact decimals: millimetres / 1000 and centimetres / 100
  written digit for digit; float points (LVX 1.0) as the float32 value; spherical
  points as the float32 nearest to the double of r sin(theta) cos(phi),
  r sin(theta) sin(phi), r cos(theta) (theta zenith, phi azimuth), which a reader
  computing in another order (or another libm) can match only to a unit in the
  last place (float values are written in the fewest digits that read back);
- intensity = reflectivity;
- t = package timestamp [ns] + firing index x firing interval [ns]: 10,000 ns
  for Mid-40, Mid-70 and Hub, 4,167 ns for Tele-15, Horizon and Avia (the Livox
  ROS driver's table), 5,000 ns for Mid-360 (200 kHz), 2,212 ns for HAP
  (452 kHz); the returns of one firing share its time. Timestamp type 3 (SDK 1)
  is UTC: year - 2000, month, day, hour, then uint32 microseconds in the hour.

Deterministic (fixed seeds): run it again after changing it.
Usage: python3 tests/data/lvx/make_lvx.py tests/data/lvx
"""

import calendar
import math
import os
import random
import struct
import sys
from decimal import Decimal

SIGNATURE = b"livox_tech" + bytes(6)
MAGIC = 0xAC0EA767

# Firing interval [ns] per device type.
FIRING_NS = {0: 10000, 1: 10000, 2: 4167, 3: 4167, 6: 10000, 7: 4167, 9: 5000, 10: 2212}


def metres(value, per_metre):
    """The exact decimal of an integer count of mm (per_metre 1000) or cm (100)."""
    d = Decimal(value) / Decimal(per_metre)
    s = format(d, "f")
    if "." in s:
        s = s.rstrip("0").rstrip(".")
    return s if s not in ("-0", "") else "0"


def f32(value):
    """The float32 nearest to value, as a Python float."""
    return struct.unpack("<f", struct.pack("<f", value))[0]


def f32_text(value):
    """The shortest decimal that reads back as the float32 nearest to value."""
    f = f32(value)
    for digits in range(1, 10):
        s = "%.*g" % (digits, f)
        if f32(float(s)) == f:
            return s
    return repr(f)


class Expected:
    """Rows of an expected CSV: x, y, z, intensity, t [ns]."""

    def __init__(self):
        self.rows = []

    def add(self, x, y, z, reflectivity, t_ns):
        self.rows.append("%s,%s,%s,%d,%d" % (x, y, z, reflectivity, t_ns))

    def text(self):
        return "x,y,z,intensity,t\n" + "".join(r + "\n" for r in self.rows)


# ----------------------------------------------------------------- timestamps
def ns_stamp(ns):
    return struct.pack("<Q", ns)


def utc_stamp(year, month, day, hour, microseconds):
    """SDK 1 timestamp type 3 and the time it stands for [ns since 1970]."""
    raw = struct.pack("<BBBBI", year - 2000, month, day, hour, microseconds)
    ns = calendar.timegm((year, month, day, hour, 0, 0)) * 1000000000 + microseconds * 1000
    return raw, ns


# ------------------------------------------------------------ point structs
def cartesian_mm(rng, tag=True):
    """int32 x, y, z [mm], reflectivity[, tag]; returns (bytes, (x, y, z, refl))."""
    if rng.random() < 0.08:
        x = y = z = 0  # a firing without a return: the origin
    else:
        x, y, z = rng.randint(-60000, 60000), rng.randint(-60000, 60000), rng.randint(-5000, 9000)
    refl = rng.randint(0, 255)
    raw = struct.pack("<iiiB", x, y, z, refl) + (struct.pack("<B", rng.randint(0, 63)) if tag else b"")
    return raw, (metres(x, 1000), metres(y, 1000), metres(z, 1000), refl)


def cartesian_cm(rng):
    x, y, z = rng.randint(-32768, 32767), rng.randint(-32768, 32767), rng.randint(-2000, 2000)
    refl = rng.randint(0, 255)
    raw = struct.pack("<hhhBB", x, y, z, refl, rng.randint(0, 63))
    return raw, (metres(x, 100), metres(y, 100), metres(z, 100), refl)


def spherical_xyz(depth_mm, theta, phi):
    r = depth_mm / 1000.0
    th = math.radians(theta / 100.0)
    ph = math.radians(phi / 100.0)
    return (f32_text(r * math.sin(th) * math.cos(ph)), f32_text(r * math.sin(th) * math.sin(ph)),
            f32_text(r * math.cos(th)))


def angles(rng):
    return rng.randint(0, 18000), rng.randint(0, 36000)


def spherical_single(rng, tag):
    """uint32 depth [mm], uint16 theta, uint16 phi [0.01 deg], reflectivity[, tag]."""
    depth = rng.randint(0, 200000)
    theta, phi = angles(rng)
    refl = rng.randint(0, 255)
    raw = struct.pack("<IHHB", depth, theta, phi, refl) + (struct.pack("<B", rng.randint(0, 63)) if tag else b"")
    return raw, [spherical_xyz(depth, theta, phi) + (refl,)]


def spherical_multi(rng, returns):
    """uint16 theta, uint16 phi, then per return uint32 depth, reflectivity, tag."""
    theta, phi = angles(rng)
    raw = struct.pack("<HH", theta, phi)
    points = []
    for _ in range(returns):
        depth, refl = rng.randint(0, 200000), rng.randint(0, 255)
        raw += struct.pack("<IBB", depth, refl, rng.randint(0, 63))
        points.append(spherical_xyz(depth, theta, phi) + (refl,))
    return raw, points


def float_point(rng):
    """LVX 1.0: float32 x, y, z [m], reflectivity."""
    x, y, z = (f32(rng.uniform(-40.0, 40.0)) for _ in range(3))
    refl = rng.randint(0, 255)
    return struct.pack("<fffB", x, y, z, refl), (f32_text(x), f32_text(y), f32_text(z), refl)


# SDK 1 data type -> (firings per package, function rng -> (bytes, [points]))
def sdk1_firing(data_type, rng):
    if data_type == 0:
        raw, p = cartesian_mm(rng, tag=False)
        return raw, [p]
    if data_type == 1:
        return spherical_single(rng, tag=False)
    if data_type == 2:
        raw, p = cartesian_mm(rng)
        return raw, [p]
    if data_type == 3:
        return spherical_single(rng, tag=True)
    if data_type in (4, 7):
        raws, points = b"", []
        for _ in range(2 if data_type == 4 else 3):
            raw, p = cartesian_mm(rng)
            raws += raw
            points.append(p)
        return raws, points
    if data_type in (5, 8):
        return spherical_multi(rng, 2 if data_type == 5 else 3)
    raise ValueError(data_type)


SDK1_FIRINGS = {0: 100, 1: 100, 2: 96, 3: 96, 4: 48, 5: 48, 7: 30, 8: 30}


# --------------------------------------------------------------------- LVX 1
class Lvx1Device:
    def __init__(self, serial, index, device_type, hub=b"", extrinsic=(0.0,) * 6, enabled=0):
        self.serial, self.index, self.device_type = serial, index, device_type
        self.hub, self.extrinsic, self.enabled = hub, extrinsic, enabled


def lvx1_package(device, data_type, ts_type, stamp, ts_ns, rng, expected, minor):
    """A package header (19 bytes) and its points; appends the points to expected[device.index]."""
    head = struct.pack("<BBBBBIBB", device.index, 5, 1, 1, 0, 0, ts_type, data_type) + stamp
    body = b""
    if minor == 0:  # LVX 1.0: 100 float points whatever the data type
        for k in range(100):
            raw, (x, y, z, refl) = float_point(rng)
            body += raw
            expected[device.index].add(x, y, z, refl, ts_ns + k * FIRING_NS[device.device_type])
    elif data_type == 6:  # IMU: gyro rad/s, acc g
        body = struct.pack("<6f", 0.01, -0.02, 0.003, 0.0, 0.0, 1.0)
    else:
        for k in range(SDK1_FIRINGS[data_type]):
            raw, points = sdk1_firing(data_type, rng)
            body += raw
            for (x, y, z, refl) in points:
                expected[device.index].add(x, y, z, refl, ts_ns + k * FIRING_NS[device.device_type])
    return head + body


def lvx1_file(minor, devices, frames):
    """frames: a list of lists of package bytes."""
    out = bytearray(SIGNATURE + bytes([1, minor, 0, 0]) + struct.pack("<I", MAGIC))
    out += struct.pack("<IB", 50, len(devices)) if minor == 1 else struct.pack("<B", len(devices))
    for d in devices:
        out += d.serial.ljust(16, b"\0") + d.hub.ljust(16, b"\0") + struct.pack("<BB", d.index, d.device_type)
        if minor == 1:
            out += struct.pack("<B", d.enabled)
        out += struct.pack("<6f", *d.extrinsic)
    for index, packages in enumerate(frames):
        body = b"".join(packages)
        header = 24 if minor == 1 else 32
        current = len(out)
        out += struct.pack("<QQQ", current, current + header + len(body), index)
        if minor == 0:
            out += struct.pack("<Q", len(packages))
        out += body
    return bytes(out)


# ---------------------------------------------------------------------- LVX2
class Lvx2Device:
    def __init__(self, serial, ip, device_type, extrinsic=(0.0,) * 6, enabled=0):
        self.serial, self.device_type = serial, device_type
        self.lidar_id = struct.unpack("<I", bytes(int(b) for b in ip.split(".")))[0]
        self.extrinsic, self.enabled = extrinsic, enabled


def lvx2_package(device, position, data_type, ts_type, ts_ns, points, rng, expected):
    body = b""
    for k in range(points):
        raw, (x, y, z, refl) = cartesian_mm(rng) if data_type == 1 else cartesian_cm(rng)
        body += raw
        expected[position].add(x, y, z, refl, ts_ns + k * FIRING_NS[device.device_type])
    head = struct.pack("<BIBBQHBIB4s", 0, device.lidar_id, 8, ts_type, ts_ns, rng.randint(0, 65535), data_type,
                       len(body), 0, bytes(4))
    assert len(head) == 27
    return head + body


def lvx2_file(devices, frames):
    out = bytearray(SIGNATURE + bytes([2, 0, 0, 0]) + struct.pack("<I", MAGIC))
    out += struct.pack("<IB", 50, len(devices))
    for d in devices:
        out += d.serial.ljust(16, b"\0") + bytes(16) + struct.pack("<IBBB", d.lidar_id, 247, d.device_type, d.enabled)
        out += struct.pack("<6f", *d.extrinsic)
    for index, packages in enumerate(frames):
        body = b"".join(packages)
        current = len(out)
        out += struct.pack("<QQQ", current, current + 24 + len(body), index)
        out += body
    return bytes(out)


# ------------------------------------------------------------------ fixtures
def write(directory, name, data, expected):
    with open(os.path.join(directory, name), "wb") as f:
        f.write(data)
    keys = sorted(expected)
    for key in keys:
        suffix = ".expected.csv" if len(keys) == 1 else ".index%d.expected.csv" % key
        with open(os.path.join(directory, name + suffix), "w", newline="\n") as f:
            f.write(expected[key].text())


def main(directory):
    os.makedirs(directory, exist_ok=True)

    # LVX 1.1, Avia, extended cartesian (2), two frames, an IMU package, PTP epoch times.
    rng = random.Random(11)
    avia = Lvx1Device(b"1PQDH5B00100041", 0, 7, extrinsic=(0.5, -1.0, 90.0, 0.1, 0.0, 1.2), enabled=1)
    exp = {0: Expected()}
    t0 = 1700000000123456789
    frames = [
        [lvx1_package(avia, 2, 1, ns_stamp(t0), t0, rng, exp, 1),
         lvx1_package(avia, 6, 1, ns_stamp(t0 + 300000), 0, rng, exp, 1)],
        [lvx1_package(avia, 2, 1, ns_stamp(t0 + 50000000), t0 + 50000000, rng, exp, 1)],
    ]
    write(directory, "avia_v11.lvx", lvx1_file(1, [avia], frames), exp)

    # LVX 1.0, Mid-40: 100 float points per package, UTC (type 3) times, two frames.
    rng = random.Random(10)
    mid40 = Lvx1Device(b"0TFDFCE00502151", 0, 1)
    exp = {0: Expected()}
    raw_a, ns_a = utc_stamp(2024, 2, 29, 13, 1234567890)
    raw_b, ns_b = utc_stamp(2024, 2, 29, 13, 1234567890 + 50000)
    frames = [[lvx1_package(mid40, 0, 3, raw_a, ns_a, rng, exp, 0)], [lvx1_package(mid40, 0, 3, raw_b, ns_b, rng, exp, 0)]]
    write(directory, "mid40_v10.lvx", lvx1_file(0, [mid40], frames), exp)

    # LVX 1.1, Horizon: cartesian (0), dual (4) and triple (7) returns, no sync (type 0).
    rng = random.Random(4)
    horizon = Lvx1Device(b"0TFDG3U00100321", 0, 3)
    exp = {0: Expected()}
    t0 = 8123456789
    frames = [[lvx1_package(horizon, 0, 0, ns_stamp(t0), t0, rng, exp, 1),
               lvx1_package(horizon, 4, 0, ns_stamp(t0 + 416700), t0 + 416700, rng, exp, 1)],
              [lvx1_package(horizon, 7, 0, ns_stamp(t0 + 616716), t0 + 616716, rng, exp, 1)]]
    write(directory, "horizon_v11_returns.lvx", lvx1_file(1, [horizon], frames), exp)

    # LVX 1.1, Tele-15: every spherical type (1, 3, 5, 8), PPS (type 4).
    rng = random.Random(3)
    tele = Lvx1Device(b"0TFDH7600100111", 0, 2)
    exp = {0: Expected()}
    t0 = 42000000000
    frames = [[lvx1_package(tele, 1, 4, ns_stamp(t0), t0, rng, exp, 1),
               lvx1_package(tele, 3, 4, ns_stamp(t0 + 416700), t0 + 416700, rng, exp, 1),
               lvx1_package(tele, 5, 4, ns_stamp(t0 + 816732), t0 + 816732, rng, exp, 1),
               lvx1_package(tele, 8, 4, ns_stamp(t0 + 1016748), t0 + 1016748, rng, exp, 1)]]
    write(directory, "tele15_v11_spherical.lvx", lvx1_file(1, [tele], frames), exp)

    # LVX 1.1, two LiDARs on a hub, device indices 1 (Mid-70) and 3 (Avia), interleaved.
    rng = random.Random(2)
    mid70 = Lvx1Device(b"3WEDH7600103381", 1, 6, hub=b"13UUG1R00400170")
    avia2 = Lvx1Device(b"3JEDHB300100591", 3, 7, hub=b"13UUG1R00400170")
    exp = {1: Expected(), 3: Expected()}
    t0 = 1700000100000000000
    frames = [[lvx1_package(mid70, 2, 1, ns_stamp(t0), t0, rng, exp, 1),
               lvx1_package(avia2, 2, 1, ns_stamp(t0 + 1000), t0 + 1000, rng, exp, 1),
               lvx1_package(avia2, 6, 1, ns_stamp(t0 + 2000), 0, rng, exp, 1)],
              [lvx1_package(avia2, 2, 1, ns_stamp(t0 + 401032), t0 + 401032, rng, exp, 1)]]
    write(directory, "two_lidars_v11.lvx", lvx1_file(1, [mid70, avia2], frames), exp)

    # LVX2, Mid-360, data type 1 (mm), 96 points per package, two frames, no sync.
    rng = random.Random(9)
    m360 = Lvx2Device(b"47MDK9DF710030", "192.168.1.44", 9)
    exp = {0: Expected()}
    t0 = 3000000001
    frames = [[lvx2_package(m360, 0, 1, 0, t0, 96, rng, exp)], [lvx2_package(m360, 0, 1, 0, t0 + 50000000, 96, rng, exp)]]
    write(directory, "mid360_type1.lvx2", lvx2_file([m360], frames), exp)

    # LVX2, Mid-360, data type 2 (cm), PTP epoch times.
    rng = random.Random(8)
    m360b = Lvx2Device(b"47MDK9DF710195", "192.168.1.195", 9, extrinsic=(0.84, -1.2, -92.1, 0.036, 0.028, 0.08), enabled=1)
    exp = {0: Expected()}
    t0 = 1700000200999999000
    frames = [[lvx2_package(m360b, 0, 2, 1, t0 + k * 480000, 96, rng, exp) for k in range(2)]]
    write(directory, "mid360_type2.lvx2", lvx2_file([m360b], frames), exp)

    # LVX2, a Mid-360 and a HAP interleaved (small packages), GPS (type 2) epoch times.
    rng = random.Random(7)
    a = Lvx2Device(b"47MDK9DF710124", "192.168.1.124", 9)
    hap = Lvx2Device(b"HAP2301TX000731", "192.168.1.100", 10)
    exp = {0: Expected(), 1: Expected()}
    t0 = 1700000300500000000
    frames = [[lvx2_package(a, 0, 1, 2, t0, 32, rng, exp), lvx2_package(hap, 1, 1, 2, t0 + 12345, 32, rng, exp),
               lvx2_package(hap, 1, 2, 2, t0 + 12345 + 70784, 24, rng, exp)],
              [lvx2_package(hap, 1, 1, 2, t0 + 50000000, 32, rng, exp),
               lvx2_package(a, 0, 1, 2, t0 + 50000100, 32, rng, exp)]]
    write(directory, "two_lidars.lvx2", lvx2_file([a, hap], frames), exp)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: make_lvx.py OUTPUT_DIR")
    main(sys.argv[1])
