# SPDX-License-Identifier: MIT
"""Keyword arguments -> the CLI's arguments, and the CLI's messages -> keywords.

Every policy keyword of :class:`streamclust.Clusterer` is a ``streamclust
cluster`` option (``window_time=0.1`` -> ``--window-time 0.1``); the module
parses them with the CLI's own parser, so presets, validation and messages are
the CLI's. A bad value raises ``ValueError`` whose message names the keyword.
"""

import numbers
import os
import re

from . import _streamclust

# keyword -> (CLI option, kind)
POLICY_KEYWORDS = {
    "window_time": ("--window-time", "number"),
    "window_count": ("--window-count", "number"),
    "linkage": ("--linkage", "choice"),
    "mask": ("--mask", "number"),
    "index": ("--index", "choice"),
    "connectivity": ("--connectivity", "choice"),
    "projection": ("--projection", "choice"),
    "mode": ("--mode", "choice"),
    "fov_azimuth": ("--fov-azimuth", "interval"),
    "fov_elevation": ("--fov-elevation", "interval"),
    "fov_z": ("--fov-z", "interval"),
    "min_range": ("--min-range", "number"),
    "grid": ("--grid", "grid"),
    "max_multiplicity": ("--max-multiplicity", "number"),
    "max_time_jump": ("--max-time-jump", "number"),
    # the whole seconds t counts from: read()'s time_origin; poses are read from it
    "time_origin": ("--time-origin", "number"),
    # motion and structure removal (the objects presets)
    "poses": ("--poses", "path"),
    "poses_topic": ("--poses-topic", "choice"),
    "mount": ("--mount", "angles"),
    "ground": ("--ground", "flag"),
    "sensor_height": ("--sensor-height", "number"),
    "ground_tolerance": ("--ground-tolerance", "number"),
    "ground_cell": ("--ground-cell", "number"),
    "max_slope": ("--max-slope", "number"),
    "ceiling": ("--ceiling", "flag"),
}

# Every option of the registered policies (theta, distance, cap, ... and a
# custom module's own): the registry's names, --min-ray-angle -> min_ray_angle.
for _keyword, _option in _streamclust.policy_options():
    POLICY_KEYWORDS.setdefault(_keyword, (_option, "number"))

READ_KEYWORDS = {
    "format": ("--format", "choice"),
    "topic": ("--topic", "choice"),
    "time_unit": ("--time-unit", "choice"),
    "point_rate": ("--point-rate", "number"),
    "time_origin": ("--time-origin", "number"),
}

SIMULATION_KEYWORDS = {
    "sensor": ("--sensor", "choice"),
    "scene": ("--scene", "choice"),
    "seconds": ("--seconds", "number"),
    "seed": ("--seed", "number"),
    "speed": ("--speed", "number"),
    "yaw_rate": ("--yaw-rate", "number"),
    "noise": ("--noise", "number"),
    "dropout": ("--dropout", "number"),
    "max_range": ("--max-range", "number"),
    "mount": ("--mount", "angles"),
    "burst": ("--burst", "interval"),
    "burst_speed": ("--burst-speed", "number"),
    "burst_yaw_rate": ("--burst-yaw-rate", "number"),
    "point_rate": ("--point-rate", "number"),
}

# CLI option -> keyword, for the messages (aliases included).
_OPTION_TO_KEYWORD = {"--preset": "preset", "--rate": "rate", "--multiplicity": "max_multiplicity",
                      "--no-ground": "ground", "--no-ceiling": "ceiling", "--duration": "seconds"}
for _table in (POLICY_KEYWORDS, READ_KEYWORDS, SIMULATION_KEYWORDS):
    for _kw, (_opt, _kind) in _table.items():
        _OPTION_TO_KEYWORD.setdefault(_opt, _kw)

# Convenience spellings of the CLI's choices (Python identifiers).
_CHOICE_ALIASES = {"range_adaptive": "range-adaptive", "scan_adaptive": "scan-adaptive", "lazy_bfs": "lazy-bfs", "spanning_forest": "forest"}


def _is_number(v):
    return isinstance(v, numbers.Real) and not isinstance(v, bool)


def _number(v):
    """A number as the CLI reads it: integers exactly, floats round-tripped."""
    if isinstance(v, numbers.Integral):
        return str(int(v))
    return repr(float(v))


def _format(keyword, kind, value):
    """The CLI argument(s) for one keyword, or ValueError naming it."""
    def bad(expected):
        return ValueError(f"{keyword}: expected {expected}, got {value!r}")

    if kind == "number":
        if not _is_number(value):
            raise bad("a number")
        return [_number(value)]
    if kind == "choice":
        if not isinstance(value, str):
            raise bad("a string")
        return [_CHOICE_ALIASES.get(value, value)]
    if kind == "path":
        if not isinstance(value, (str, os.PathLike)):
            raise bad("a file path")
        return [os.fspath(value)]
    if kind == "interval":
        try:
            lo, hi = value
        except (TypeError, ValueError):
            raise bad("a pair (min, max)") from None
        if not (_is_number(lo) and _is_number(hi)):
            raise bad("a pair of numbers (min, max)")
        return [f"{_number(lo)}:{_number(hi)}"]
    if kind == "angles":
        try:
            angles = list(value)
        except TypeError:
            raise bad("(roll, pitch, yaw) in degrees") from None
        if len(angles) != 3 or not all(_is_number(a) for a in angles):
            raise bad("(roll, pitch, yaw) in degrees")
        return [",".join(_number(a) for a in angles)]
    if kind == "grid":
        if value is None or value == "auto":
            return ["auto"]
        try:
            rows, cols = value
        except (TypeError, ValueError):
            raise bad("'auto' or (rows, cols)") from None
        if not all(isinstance(n, numbers.Integral) and not isinstance(n, bool) for n in (rows, cols)):
            raise bad("'auto' or (rows, cols) as whole numbers")
        return [f"{int(rows)}x{int(cols)}"]
    raise AssertionError(kind)


def to_arguments(table, keywords, what):
    """CLI arguments of `keywords` (a dict) looked up in `table`.

    Unknown keywords and values of the wrong type raise ValueError naming them.
    """
    args = []
    for keyword, value in keywords.items():
        if keyword not in table:
            known = ", ".join(sorted(table))
            raise ValueError(f"{keyword}: not a {what} keyword (known: {known})")
        option, kind = table[keyword]
        if kind == "flag":
            if not isinstance(value, bool):
                raise ValueError(f"{keyword}: expected True or False, got {value!r}")
            if keyword == "ground":
                args.append("--ground" if value else "--no-ground")
            elif not value:  # ceiling=False
                args.append("--no-ceiling")
            continue
        if value is None:
            raise ValueError(f"{keyword}: expected a value, got None")
        args.append(option)
        args.extend(_format(keyword, kind, value))
    return args


_OPTION = re.compile(r"--[a-z][a-z0-9-]*")


def keyword_message(message):
    """A CLI message with its option names replaced by the Python keywords."""
    return _OPTION.sub(lambda m: _OPTION_TO_KEYWORD.get(m.group(0), m.group(0)), message)


def reraise_with_keywords(error):
    """ValueError from the extension -> ValueError naming keywords."""
    return ValueError(keyword_message(str(error)))
