#!/usr/bin/env bash
# Installs what the HTML report viewer needs: three.js (and, for the browser tests,
# playwright-core) from the npm registry at the versions pinned in viewer/package-lock.json.
#   scripts/setup_viewer.sh [--with-chromium]
# --with-chromium also installs Debian's chromium for scripts/run_browser_tests.sh.
# Node.js and npm come from Debian's nodejs and npm packages when they are missing (as root).
# Configure the build folder again afterwards: the viewer is inlined at configure time.
set -euo pipefail
cd "$(dirname "$0")/.."

with_chromium=false
for argument in "$@"; do
  case "$argument" in
    --with-chromium) with_chromium=true ;;
    *) echo "setup_viewer.sh: unknown argument '$argument'" >&2; exit 2 ;;
  esac
done

apt_install() {
  if [ "$(id -u)" -ne 0 ]; then
    echo "setup_viewer.sh: $* missing; install them (apt-get install -y $*) as root" >&2
    return 1
  fi
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q "$@" > /dev/null ||
    { apt-get update -q > /dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -q "$@" > /dev/null; }
}

if ! command -v node > /dev/null || ! command -v npm > /dev/null; then
  apt_install nodejs npm
fi
if $with_chromium && [ ! -x /usr/bin/chromium ]; then
  apt_install chromium
fi

# npm ci only when the installed tree is older than the lock file.
if [ ! -f viewer/node_modules/.package-lock.json ] || [ viewer/package-lock.json -nt viewer/node_modules/.package-lock.json ]; then
  (cd viewer && npm ci --no-audit --no-fund --loglevel=error)
fi
echo "viewer: three $(node -p "require('./viewer/node_modules/three/package.json').version") installed in viewer/node_modules"
