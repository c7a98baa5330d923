#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Install the Debian packages streamclust builds with. Idempotent: does nothing
# (not even `apt-get update`) when every package is already installed.
set -euo pipefail

PACKAGES=(
  build-essential cmake g++ clang-14
  libboost-graph-dev libeigen3-dev librange-v3-dev
  doctest-dev libbenchmark-dev
  nlohmann-json3-dev
  # the recording readers (ROS 1 bags, rosbag2, MCAP): chunk codecs and SQLite;
  # zlib for the PNG writer
  liblz4-dev libzstd-dev libbz2-dev libsqlite3-dev zlib1g-dev
  # the live view's Foxglove WebSocket server (tools/live): websocketpp on standalone asio
  libwebsocketpp-dev libasio-dev
  # the fuzz targets (-DSTREAMCLUST_FUZZ=ON, scripts/fuzz.sh): clang-14's libFuzzer runtime
  libclang-rt-14-dev
  # the Python module (-DSTREAMCLUST_PYTHON=ON, docs/python.md), its tests and example
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib python3-setuptools
  # the ROS 2 node over DDS (`streamclust ros2`, docs/ros2.md): Cyclone DDS
  cyclonedds-dev
)
# The reference implementations the tests check outputs against (the MCAP
# reader, the ROS 2 serializer, the Foxglove WebSocket client) run on node
# and install with npm (scripts/install-npm-tools.sh): Debian's, unless a
# node with npm is already on the PATH.
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  PACKAGES+=(nodejs npm)
fi

missing=()
for pkg in "${PACKAGES[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$pkg" 2>/dev/null || true)
  if [[ "$status" != "installed" ]]; then
    missing+=("$pkg")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install-deps: all ${#PACKAGES[@]} packages already installed"
  exit 0
fi

SUDO=()
if [[ $(id -u) -ne 0 ]]; then
  if command -v sudo >/dev/null 2>&1; then
    SUDO=(sudo)
  else
    echo "install-deps: not root and no sudo; install these by hand: ${missing[*]}" >&2
    exit 1
  fi
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
"${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
