#!/usr/bin/env bash
# Installs what catena's build needs from Debian's packages, only if it is missing:
#   libhdf5-dev (HDF5 results, via the hdf5-metno crate) and pkg-config.
# Safe to run again; does nothing when everything is there. Needs root (or sudo) the first time.
set -euo pipefail
need=()
for pkg in libhdf5-dev pkg-config; do
  dpkg -s "$pkg" >/dev/null 2>&1 || need+=("$pkg")
done
if [ ${#need[@]} -gt 0 ]; then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "setup: installing ${need[*]}" >&2
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${need[@]}" >/dev/null
fi
