#!/usr/bin/env bash
# Installs Radiant's build and test dependencies from Debian 12 packages.
# Idempotent: packages already present are left alone. Needs root (or sudo).
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  libembree-dev libtbb-dev libopenexr-dev libstb-dev libpng-dev libtinyobjloader-dev
  nlohmann-json3-dev libcli11-dev libfmt-dev libtinygltf-dev libcpp-httplib-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libjemalloc-dev
  libopenmpi-dev openmpi-bin
  clang-format-14
  clang-14 libclang-rt-14-dev
  python3
  chromium
)
# The browser viewer (viewer/) and its tests run on Node.js: Debian's, unless
# the machine already has a node and npm of its own (e.g. NodeSource's, whose
# nodejs package conflicts with Debian's npm).
command -v node >/dev/null || packages+=(nodejs)
command -v npm >/dev/null || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
else
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "install-deps: run as root or install sudo" >&2; exit 1; }
    sudo="sudo"
  fi
  echo "install-deps: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -q
  $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# The viewer's npm packages (three.js; the browser tests' puppeteer-core and
# gltf-validator), exactly as viewer/package-lock.json pins them, into
# viewer/node_modules; skipped when that lock file is what was installed last.
viewer="$(dirname "$0")/../viewer"
if [ -f "$viewer/package-lock.json" ] &&
  ! cmp -s "$viewer/package-lock.json" "$viewer/node_modules/.package-lock.json.installed"; then
  echo "install-deps: npm ci in viewer/"
  # Only the viewer and its tests need them: without the npm registry (offline, or a proxy whose
  # certificate Node does not trust) the build and the renderer still install, and the browser
  # tests report themselves skipped. NODE_EXTRA_CA_CERTS, if set, is how Node trusts such a proxy.
  if (cd "$viewer" && npm ci --no-audit --no-fund --loglevel=error); then
    cp "$viewer/package-lock.json" "$viewer/node_modules/.package-lock.json.installed"
  else
    echo "install-deps: WARNING: npm ci in viewer/ failed (no access to the npm registry?): the browser" \
      "viewer and its tests need it; run scripts/install-deps.sh again where the registry is reachable" >&2
  fi
fi
