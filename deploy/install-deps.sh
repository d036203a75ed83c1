#!/usr/bin/env bash
# Installs every Debian 12 package reenact needs to build, test and run.
# Idempotent: packages already present are skipped, so a second run is fast.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config git ca-certificates curl
  libeigen3-dev libboost-dev libboost-system-dev libssl-dev libsqlite3-dev sqlite3
  nlohmann-json3-dev libopencv-dev libopencv-contrib-dev libdraco-dev libopenni2-dev
  libtinygltf-dev libstb-dev
  libglfw3-dev libepoxy-dev libegl-dev libgl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri
  ffmpeg libgtest-dev libgmock-dev libbenchmark-dev
  postgresql postgis postgresql-15-postgis-3 libpq-dev
  nginx-light
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q '^install ok installed$' || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps: missing packages: ${missing[*]}" >&2
  echo "install-deps: run as root (or: sudo $0) to install them" >&2
  exit 1
fi
echo "install-deps: installing ${#missing[@]} packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${PACKAGES[@]}" >/dev/null
echo "install-deps: done"
