#!/usr/bin/env bash
# Installs the Debian 12 packages the build needs (idempotent). Run as root (or with sudo).
# Arguments name extra sets, installed in the same apt-get run as the build packages, so that a
# fresh machine reads the package lists once:
#   fuzz     clang and libFuzzer (scripts/run_fuzz.sh)
#   browser  Chromium and Node.js with npm (the browser tests; Node.js only where `node` is missing)
#   mpi      Open MPI (soup_topology_mpi and its tests under mpirun)
# e.g. `bash scripts/setup.sh fuzz browser`.
set -euo pipefail
packages=(g++ cmake make xz-utils libcgal-dev libgmp-dev libmpfr-dev libboost-graph-dev libeigen3-dev
          libtbb-dev libgtest-dev libgmock-dev libbenchmark-dev)
for extra in "$@"; do
  case $extra in
    fuzz) packages+=(clang libclang-rt-14-dev libfuzzer-14-dev) ;;
    browser)
      packages+=(chromium)
      command -v node > /dev/null || packages+=(nodejs npm) ;;
    mpi) packages+=(libopenmpi-dev openmpi-bin) ;;
    *) echo "setup.sh: unknown set '$extra' (known: fuzz, browser, mpi)" >&2; exit 2 ;;
  esac
done
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
fi
