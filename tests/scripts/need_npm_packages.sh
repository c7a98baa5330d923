# SPDX-License-Identifier: MIT
# Sourced by the node tests: need_npm_packages PREFIX PACKAGE... exits 77
# (CTest's skip) naming what is missing unless node is on the PATH and every
# PACKAGE is under PREFIX/node_modules (scripts/install-npm-tools.sh installs
# them; STREAMCLUST_NPM_PREFIX points elsewhere).
need_npm_packages() {
  local prefix=$1 package
  shift
  for package in "$@"; do
    if ! command -v node >/dev/null || [[ ! -d "$prefix/node_modules/$package" ]]; then
      echo "skipped: needs node and $package in $prefix (scripts/install-npm-tools.sh)"
      exit 77
    fi
  done
}
