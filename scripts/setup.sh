#!/usr/bin/env bash
# Installs the Debian 12 packages the build needs (idempotent). Run as root (or with sudo).
set -euo pipefail
packages=(g++ cmake make xz-utils libcgal-dev libgmp-dev libmpfr-dev libboost-graph-dev libeigen3-dev
          libtbb-dev libgtest-dev libgmock-dev libbenchmark-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
fi
