# SPDX-License-Identifier: MIT
"""fixture_check.py -- helpers shared by the Python verifiers (verify_ros1.py, verify_db3.py,
verify_mcap_bytes.py): expected-CSV loading, a PointField decoder and a small CDR decoder written
from the specifications (not from the writer code), and point comparison."""
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

# PointField datatype -> (struct code, size)
PF = {1: ("b", 1), 2: ("B", 1), 3: ("h", 2), 4: ("H", 2), 5: ("i", 4), 6: ("I", 4), 7: ("f", 4), 8: ("d", 8)}


class Mismatch(Exception):
    pass


def load_expected(name):
    rows = []
    with open(os.path.join(HERE, name)) as f:
        header = f.readline().strip()
        if header != "x,y,z,intensity,t":
            raise Mismatch("%s: bad header %r" % (name, header))
        for line in f:
            x, y, z, inten, t = line.strip().split(",")
            rows.append((float(x), float(y), float(z), float(inten), int(t)))
    return rows


def f32(v):
    """bit pattern of v rounded to float32 (NaN -> canonical marker)"""
    if math.isnan(v):
        return "nan"
    return struct.pack("<f", v)


def compare(label, got, expected):
    """got/expected: lists of (x, y, z, intensity, t_ns); x,y,z compared as float32 bit patterns
    (the CSV text is parsed with float() = strtod, then rounded to float32), intensity exactly,
    t exactly."""
    if len(got) != len(expected):
        raise Mismatch("%s: %d points, expected %d" % (label, len(got), len(expected)))
    for n, (g, e) in enumerate(zip(got, expected)):
        for a in range(3):
            if f32(g[a]) != f32(e[a]):
                raise Mismatch("%s: point %d coord %d: %r != %r" % (label, n, a, g[a], e[a]))
        if float(g[3]) != e[3]:
            raise Mismatch("%s: point %d intensity %r != %r" % (label, n, g[3], e[3]))
        if int(g[4]) != e[4]:
            raise Mismatch("%s: point %d t %r != %r" % (label, n, g[4], e[4]))


def decode_cloud(stamp_ns, height, width, fields, is_bigendian, point_step, row_step, data):
    """Generic PointCloud2 point decoder -> [(x, y, z, intensity, t_ns)].
    Time: 'timestamp' FLOAT64 absolute ns; 't' UINT32 ns since stamp; 'time' FLOAT32 s since stamp
    (rounded half away from zero, values are never ties)."""
    end = ">" if is_bigendian else "<"
    fmap = {f[0]: (f[1], f[2]) for f in fields}  # name -> (offset, datatype)

    def get(rec, name):
        off, dt = fmap[name]
        code, size = PF[dt]
        return struct.unpack_from(end + code, rec, off)[0]

    if len(data) != row_step * height or row_step != point_step * width:
        raise Mismatch("cloud size: data %d, row_step %d, height %d, width %d, point_step %d"
                       % (len(data), row_step, height, width, point_step))
    out = []
    for r in range(height):
        for c in range(width):
            o = r * row_step + c * point_step
            rec = data[o:o + point_step]
            if "timestamp" in fmap:
                t = int(get(rec, "timestamp"))
            elif "t" in fmap:
                t = stamp_ns + get(rec, "t")
            elif "time" in fmap:
                t = stamp_ns + int(math.floor(get(rec, "time") * 1e9 + 0.5))
            else:
                raise Mismatch("no time field")
            out.append((get(rec, "x"), get(rec, "y"), get(rec, "z"), get(rec, "intensity"), t))
    return out


class Cdr:
    """Minimal XCDR1 reader: 4-byte encapsulation header, then primitives aligned to their size
    relative to the first byte after the encapsulation header."""

    def __init__(self, buf):
        self.b = bytes(buf)
        kind = self.b[1]
        if self.b[0] != 0 or kind not in (0, 1):
            raise Mismatch("bad CDR encapsulation %r" % self.b[:4])
        self.e = "<" if kind == 1 else ">"
        self.o = 4
        self.pads = []  # (offset, n) of every padding gap, for reporting

    def align(self, n):
        rel = self.o - 4
        pad = (-rel) % n
        if pad:
            self.pads.append((self.o, pad))
        self.o += pad

    def prim(self, code, size):
        self.align(size)
        v = struct.unpack_from(self.e + code, self.b, self.o)[0]
        self.o += size
        return v

    def u8(self): return self.prim("B", 1)
    def u16(self): return self.prim("H", 2)
    def u32(self): return self.prim("I", 4)
    def i32(self): return self.prim("i", 4)
    def u64(self): return self.prim("Q", 8)
    def f32(self): return self.prim("f", 4)
    def f64(self): return self.prim("d", 8)

    def string(self):
        n = self.u32()
        s = self.b[self.o:self.o + n]
        if n == 0 or s[-1] != 0:
            raise Mismatch("CDR string without NUL")
        self.o += n
        return s[:-1].decode()

    def raw(self, n):
        s = self.b[self.o:self.o + n]
        self.o += n
        return s

    def header(self):
        sec = self.i32()
        nsec = self.u32()
        return sec * 1000000000 + nsec, self.string()


def cdr_custom(buf):
    """livox_ros_driver2/msg/CustomMsg -> (stamp_ns, frame_id, timebase, points, cdr)"""
    c = Cdr(buf)
    stamp, frame = c.header()
    timebase = c.u64()
    point_num = c.u32()
    c.u8()            # lidar_id
    c.raw(3)          # rsvd: uint8[3], fixed array, no length prefix
    n = c.u32()
    if n != point_num:
        raise Mismatch("point_num %d != sequence length %d" % (point_num, n))
    pts = []
    for _ in range(n):
        off = c.u32()
        x, y, z = c.f32(), c.f32(), c.f32()
        refl, tag, line = c.u8(), c.u8(), c.u8()
        pts.append((x, y, z, refl, timebase + off))
    if c.o != len(c.b):
        raise Mismatch("CustomMsg: %d trailing bytes" % (len(c.b) - c.o))
    return stamp, frame, timebase, pts, c


def cdr_pc2(buf):
    """sensor_msgs/msg/PointCloud2 -> (stamp_ns, frame_id, decoded points, cloud dict, cdr)"""
    c = Cdr(buf)
    stamp, frame = c.header()
    height, width = c.u32(), c.u32()
    fields = []
    for _ in range(c.u32()):
        name = c.string()
        offset = c.u32()
        dt = c.u8()
        count = c.u32()
        fields.append((name, offset, dt, count))
    is_be = c.u8() != 0
    point_step, row_step = c.u32(), c.u32()
    data = c.raw(c.u32())
    is_dense = c.u8() != 0
    if c.o != len(c.b):
        raise Mismatch("PointCloud2: %d trailing bytes" % (len(c.b) - c.o))
    cloud = dict(height=height, width=width, fields=fields, is_bigendian=is_be, point_step=point_step,
                 row_step=row_step, is_dense=is_dense, data_len=len(data))
    return stamp, frame, decode_cloud(stamp, height, width, fields, is_be, point_step, row_step, data), cloud, c
