#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# verify_fixtures.sh -- read every recording fixture back with independent readers and compare the
# points with the expected CSVs.  Exit status 0 only if every check passes.
#
#   bash tests/data/recordings/verify_fixtures.sh
#
# Readers used (none of them is the code that wrote the files' containers):
#   ROS 1 bags   python3-rosbag (Bag.read_messages) + a raw record walk; lz4 chunks also through
#                python3-lz4 (liblz4 frame API), bz2 chunks through Python's bz2
#   rosbag2 db3  Python sqlite3 + a CDR decoder written from the spec (fixture_check.py), and
#                @foxglove/rosmsg2-serialization's MessageReader
#   MCAP         a spec-based record walk in Python (all CRCs recomputed, chunks through liblz4 /
#                the zstd CLI) and @mcap/core's McapStreamReader + McapIndexedReader with
#                @mcap/support's decompressors + MessageReader
# Needs /usr/bin/python3 with python3-rosbag (python3-lz4 and the zstd CLI for the cross-checks),
# node + npm (registry reachable; packages go to a temporary directory).
set -uo pipefail
export PYTHONDONTWRITEBYTECODE=1

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
PY=/usr/bin/python3
NPM_PKGS=(
  "@mcap/core@2.2.2"
  "@mcap/support@1.1.0"
  "@foxglove/rosmsg2-serialization@3.1.0"
  "@foxglove/rosmsg@5.0.5"
)

TMP="$(mktemp -d "${TMPDIR:-/tmp}/recordings-verify.XXXXXX")"
trap 'rm -rf "$TMP"' EXIT
mkdir -p "$TMP/npm"

status=0
run() {
  echo "== $*"
  "$@" || status=1
}

cd "$HERE"
run "$PY" verify_ros1.py
run "$PY" verify_db3.py "$TMP/db3_dump.json"
run "$PY" verify_mcap_bytes.py

echo "== npm install (into $TMP/npm)"
if (cd "$TMP/npm" && echo '{"name":"fixture-verify","private":true}' > package.json &&
    npm install --no-audit --no-fund --ignore-scripts --save-exact --prefix "$TMP/npm" "${NPM_PKGS[@]}" >/dev/null); then
  run node verify_mcap.mjs "$TMP/npm" "$TMP/db3_dump.json"
else
  echo "FAIL npm install"
  status=1
fi

if [ "$status" -eq 0 ]; then echo "verify_fixtures.sh: all fixtures OK"; else echo "verify_fixtures.sh: FAILURES"; fi
exit "$status"
