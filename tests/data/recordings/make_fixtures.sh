#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# make_fixtures.sh -- regenerate every recording fixture in this folder from scratch.
#
#   bash tests/data/recordings/make_fixtures.sh
#
# Needs: node >= 20 + npm (npm registry reachable), Debian's /usr/bin/python3 with
# python3-rosbag, python3-genpy, python3-genmsg, python3-roslz4 (sqlite3 is in the standard library):
#   apt-get install python3-rosbag python3-genpy python3-roslz4
# The pinned npm packages are installed into a temporary directory that is deleted afterwards;
# nothing from npm is kept in the repository.  Output is deterministic (run twice, compare with
# sha256sum); afterwards run verify_fixtures.sh.
set -euo pipefail
export PYTHONDONTWRITEBYTECODE=1

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
PY=/usr/bin/python3   # Debian's python: the pyenv python on PATH lacks the ROS modules

# Writer packages (exact versions).  lz4js and zstd-codec compress MCAP chunks (LZ4 frame / zstd
# frame format); the fixtures' decompression is checked by verify_fixtures.sh with other codecs.
NPM_PKGS=(
  "@mcap/core@2.2.2"
  "@foxglove/rosmsg2-serialization@3.1.0"
  "@foxglove/rosmsg@5.0.5"
  "lz4js@0.2.0"
  "zstd-codec@0.1.5"
)

TMP="$(mktemp -d "${TMPDIR:-/tmp}/recordings-fixtures.XXXXXX")"
trap 'rm -rf "$TMP"' EXIT
mkdir -p "$TMP/npm" "$TMP/work"

"$PY" -c 'import rosbag, genpy, genmsg, roslz4, sqlite3' || {
  echo "make_fixtures.sh: $PY lacks rosbag/genpy/genmsg/roslz4 (apt-get install python3-rosbag python3-genpy python3-roslz4)" >&2
  exit 1
}

echo "== npm install (into $TMP/npm)"
(cd "$TMP/npm" && echo '{"name":"fixture-writer","private":true}' > package.json &&
  npm install --no-audit --no-fund --ignore-scripts --save-exact --prefix "$TMP/npm" "${NPM_PKGS[@]}" >/dev/null)

# Remove previous outputs (only files this script creates).
rm -rf "$HERE/ros2_custom_db3"
rm -f "$HERE"/*.expected.csv "$HERE"/ros1_*.bag "$HERE"/ros2_*.mcap "$HERE"/ros2_*.db3

echo "== node gen_fixtures.mjs (expected CSVs, MCAP files, CDR payloads)"
node "$HERE/gen_fixtures.mjs" "$TMP/npm" "$HERE" "$TMP/work"

echo "== python write_ros1_bags.py (ROS 1 bags)"
"$PY" "$HERE/write_ros1_bags.py" "$TMP/work/ros1_input.json" "$HERE"

echo "== python write_db3.py (rosbag2 SQLite)"
"$PY" "$HERE/write_db3.py" "$TMP/work" "$HERE"

echo "== done"
cd "$HERE" && ls -l *.expected.csv ros1_*.bag ros2_*.mcap ros2_*.db3 ros2_custom_db3/*
