#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Merges the results of several bench_latency runs (e.g. one per sensor run
side by side with --filter mid360 / --filter avia) into one directory:
summary.json (scenarios concatenated, run settings of the first), summary.md
(each table's rows concatenated), cycles.csv (rows concatenated, one header),
and the cdf/ and pct/ files copied. bench/run.sh runs every scenario as its
own process (`--scenario NAME`) and merges them in --list order with this.

    python3 bench/latency/merge_summaries.py OUT_DIR RUN_DIR [RUN_DIR ...]

The runs must use the same --cycles / --peer-every / --pcl-every /
--timed-cycles (checked) so that the merged record is one experiment.
"""
import json
import os
import shutil
import sys

SETTINGS = ("cycles", "peer_every", "pcl_every", "timed_cycles")


def merge_md(paths):
    """First file's text, with every table extended by the others' rows."""
    def tables(text):
        out, current = {}, None
        for line in text.splitlines():
            if line.startswith("## "):
                current = line
                out[current] = []
            elif current is not None and line.startswith("| ") and not line.startswith("| scenario"):
                out[current].append(line)
        return out

    texts = [open(p).read() for p in paths]
    extra = {}
    for t in texts[1:]:
        for head, rows in tables(t).items():
            extra.setdefault(head, []).extend(rows)
    lines, current, out = texts[0].splitlines(), None, []
    for i, line in enumerate(lines):
        if line.startswith("## "):
            current = line
        out.append(line)
        last_row = line.startswith("|") and (i + 1 == len(lines) or not lines[i + 1].startswith("|"))
        if current is not None and last_row:
            out.extend(extra.pop(current, []))
    return "\n".join(out) + "\n"


def main(out_dir, runs):
    data = [json.load(open(os.path.join(r, "summary.json"))) for r in runs]
    for d, r in zip(data[1:], runs[1:]):
        for k in SETTINGS:
            if d[k] != data[0][k]:
                sys.exit(f"{r}: {k} = {d[k]} differs from {runs[0]}'s {data[0][k]}")
    merged = dict(data[0])
    merged["scenarios"] = [s for d in data for s in d["scenarios"]]
    os.makedirs(out_dir, exist_ok=True)
    json.dump(merged, open(os.path.join(out_dir, "summary.json"), "w"), indent=1)
    open(os.path.join(out_dir, "summary.md"), "w").write(merge_md([os.path.join(r, "summary.md") for r in runs]))
    with open(os.path.join(out_dir, "cycles.csv"), "w") as csv:
        for r in runs:
            path = os.path.join(r, "cycles.csv")
            if not os.path.isfile(path):
                continue
            lines = open(path).read().splitlines(keepends=True)
            csv.writelines(lines if csv.tell() == 0 else lines[1:])
    for r in runs:
        for sub in ("cdf", "pct"):
            src = os.path.join(r, sub)
            if os.path.isdir(src):
                shutil.copytree(src, os.path.join(out_dir, sub), dirs_exist_ok=True)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit("usage: merge_summaries.py OUT_DIR RUN_DIR [RUN_DIR ...]")
    main(sys.argv[1], sys.argv[2:])
