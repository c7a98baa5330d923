# SPDX-License-Identifier: MIT
"""streamclust.live: a Livox LiDAR's stream, clustered as it arrives."""

from numbers import Integral, Real

from . import _streamclust
from ._options import POLICY_KEYWORDS, to_arguments
from ._retrieval import Retrieval


class LiveRetrieval(Retrieval):
    """One retrieval of a live source: a :class:`Retrieval` with the points.

    Attributes (besides cycle, time, index, labels, components, tracks)
    ----------------------------------------------------------
    xyz : numpy.ndarray, float32 (M, 3)
        Position of each row [m, the LiDAR's frame] (rows as ``index``).
    t : numpy.ndarray, float64 (M,)
        Time of each row [s] since :attr:`LiveStream.time_origin`.
    intensity : numpy.ndarray, float32 (M,)
        Reflectivity of each row (0-255).
    new_xyz, new_t, new_intensity : numpy.ndarray (N, 3), (N,), (N,)
        The points received since the previous retrieval, in stream order
        (stream indices ``index`` counts): concatenated over all retrievals
        they are the whole stream, which :func:`cluster_stream` clusters to
        the same cycles.
    counters : dict
        The connection's counters at this retrieval (see :attr:`LiveStream.counters`).
    """

    __slots__ = ("xyz", "t", "intensity", "new_xyz", "new_t", "new_intensity", "counters")

    def __init__(self, cycle, time, index, labels, components, xyz, t, intensity, new_xyz, new_t, new_intensity,
                 counters, tracks=None):
        super().__init__(cycle, time, index, labels, components, tracks)
        self.xyz = xyz
        self.t = t
        self.intensity = intensity
        self.new_xyz = new_xyz
        self.new_t = new_t
        self.new_intensity = new_intensity
        self.counters = counters


def _seconds(name, value, allow_none):
    if value is None and allow_none:
        return 0.0
    if isinstance(value, bool) or not isinstance(value, Real) or not value > 0:
        expected = "None or seconds > 0" if allow_none else "seconds > 0"
        raise ValueError(f"{name}: expected {expected}, got {value!r}")
    return float(value)


def _count(name, value, low, high):
    if isinstance(value, bool) or not isinstance(value, Integral) or not low <= value <= high:
        raise ValueError(f"{name}: expected a whole number from {low} to {high}, got {value!r}")
    return int(value)


class LiveStream:
    """The iterator :func:`live` returns: retrievals as they are due.

    The LiDAR was connected when the stream was made. ``close()`` (also:
    leaving a ``with`` block, by an exception too, or dropping the stream,
    as breaking out of ``for r in live(...)`` does) stops the receiver
    thread and the LiDAR (SDK1: stop sampling) within about 20 ms. One
    thread at a time.
    """

    def __init__(self, run):
        self._run = run

    def __iter__(self):
        return self

    def __next__(self):
        if self._run is None:
            raise StopIteration
        r = self._run.next()
        if r is None:
            raise StopIteration
        return LiveRetrieval(*r)

    def close(self):
        """Stops the receiver and the LiDAR; idempotent."""
        run, self._run = self._run, None
        if run is not None:
            run.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def __del__(self):
        self.close()

    @property
    def counters(self):
        """The connection's counters now, named as in the CLI's report:
        lidar ("MODEL SERIAL" or "LiDAR at ADDRESS"), datagrams, bytes,
        point_packets, imu_packets, returns, empty_slots, lost, late,
        duplicates, counter_jumps, malformed, foreign (from other addresses),
        oversize, queue_drops (the consumer fell behind), kernel_drops (None
        where the OS does not say), clock_epochs, time_sync, end ("running",
        "duration reached", "idle_exit: no packets", "closed")."""
        if self._run is None:
            raise ValueError("counters: the live stream is closed")
        return self._run.counters()

    @property
    def time_origin(self):
        """Whole seconds of the host clock (Unix time) that the times count
        from; None before the first packet."""
        if self._run is None:
            raise ValueError("time_origin: the live stream is closed")
        return self._run.time_origin


def live(source, preset="carc-mid360", *, lidar=None, configure=False, discovery_address=None, duration=None,
         idle_exit=None, wait=10.0, queue=4096, reorder=8, rate=20, tracks=False, **options):
    """Clusters a Livox LiDAR's stream as it arrives (``streamclust live``).

    source: ``"livox-sdk2://[HOST_IP][:PORT]"`` (Mid-360, HAP; points on
    PORT, default 56301, IMU on PORT + 100) or ``"livox-sdk1://[HOST_IP][:PORT]"``
    (Avia, Mid-40/70, Horizon, Tele-15; broadcasts on PORT, default 55000,
    commands from PORT + 500, data on PORT + 1000), as the CLI reads them.
    lidar: a serial number or an address, or a list of one (default: the
    first LiDAR heard). configure: SDK2: discovery, then point the LiDAR's
    streams at this host (else the LiDAR's stored destination is used);
    discovery_address: where discovery requests go (default broadcast).
    duration: seconds of wall time, then the stream ends; idle_exit: seconds
    without packets end it; wait: seconds for discovery, the handshake and
    the first packet (then ConnectionError or TimeoutError). queue: packets
    between the receiver thread and the engine (when full, whole packets
    are dropped and counted); reorder: packets held to undo reordering.
    rate: retrievals per second of stream time. preset, tracks and
    options: as :class:`Clusterer` (with ``ground=True`` the mount and
    sensor height not given are estimated from the first window, as
    :func:`cluster_stream` does; with ``tracks=True`` each retrieval's
    ``tracks`` are the tracked objects, the rows of ``streamclust live
    --tracks`` for its cycle).

    Returns a :class:`LiveStream` yielding :class:`LiveRetrieval` objects on
    the schedule of :func:`cluster_stream`; when the stream ends (duration,
    idle_exit) the last retrieval comes and iteration stops. The GIL is
    released while waiting; Ctrl-C raises KeyboardInterrupt within 50 ms.
    A bad source or option raises ValueError before anything is sent.
    """
    if not isinstance(source, str):
        raise ValueError(f"source: expected livox-sdk2://[HOST_IP][:PORT] or livox-sdk1://[HOST_IP][:PORT], "
                         f"got {source!r}")
    if not isinstance(preset, str):
        raise ValueError(f"preset: expected a preset name, got {preset!r}")
    if "time_origin" in options:
        raise ValueError("time_origin: a live source counts from its first packet's whole second")
    lidars = [] if lidar is None else [lidar] if isinstance(lidar, str) else list(lidar)
    if not all(isinstance(x, str) for x in lidars):
        raise ValueError(f"lidar: expected a serial number or an IPv4 address (str), got {lidar!r}")
    if len(lidars) > 1:
        raise ValueError("lidar: one LiDAR per live source (make one per LiDAR)")
    if not isinstance(configure, bool):
        raise ValueError(f"configure: expected True or False, got {configure!r}")
    if not isinstance(tracks, bool):
        raise ValueError(f"tracks: expected True or False, got {tracks!r}")
    if discovery_address is not None and not isinstance(discovery_address, str):
        raise ValueError(f"discovery_address: expected a dotted IPv4 address, got {discovery_address!r}")
    args = (["--preset", preset] + to_arguments(POLICY_KEYWORDS, options, "live")
            + to_arguments({"rate": ("--rate", "number")}, {"rate": rate}, "rate"))
    from . import _call  # the package's error translation (CLI option names -> keywords)
    try:
        run = _call(_streamclust.LiveRun, args, source, lidars, configure, discovery_address,
                    _seconds("wait", wait, False), _seconds("duration", duration, True),
                    _seconds("idle_exit", idle_exit, True), _count("queue", queue, 2, 1 << 20),
                    _count("reorder", reorder, 0, 1024), tracks)
    except ValueError as e:
        message = str(e)
        if message.startswith("SOURCE: "):
            raise ValueError("source: " + message[len("SOURCE: "):]) from None
        raise
    return LiveStream(run)
