#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs the npm packages the optional tests mcap_foxglove and
# foxglove_live use (the reference MCAP reader, the ROS 2 message decoder, and
# the reference Foxglove WebSocket client with its WebSocket) into build/npm. Needs node,
# npm and the npm registry; nothing is installed outside build/npm.
# Usage: scripts/install-npm-tools.sh [PREFIX]
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
PREFIX=${1:-$ROOT/build/npm}
mkdir -p "$PREFIX"
cd "$PREFIX"
[[ -f package.json ]] || echo '{"name":"streamclust-test-tools","private":true}' > package.json
npm install --no-audit --no-fund --ignore-scripts --save-exact \
  @mcap/core@2.2.2 @mcap/support@1.1.0 @foxglove/rosmsg@5.0.5 @foxglove/rosmsg2-serialization@3.1.0 \
  @foxglove/ws-protocol@0.8.0 ws@8.18.0
echo "install-npm-tools: packages in $PREFIX/node_modules"
