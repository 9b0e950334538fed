#!/usr/bin/env bash
# Makes sure the lavapipe Vulkan driver (Mesa's CPU rasterizer) is installed, installing
# it with apt when we are root (or have sudo). Everything rgraph runs headless needs it.
set -euo pipefail

icd_present() {
  ls /usr/share/vulkan/icd.d/lvp_icd.*.json >/dev/null 2>&1 && ldconfig -p 2>/dev/null | grep -q libvulkan.so.1
}

if icd_present; then
  exit 0
fi

packages="mesa-vulkan-drivers libvulkan1"
echo "rgraph: the lavapipe Vulkan driver is missing; installing: $packages" >&2
if [ "$(id -u)" = 0 ]; then
  sudo=""
elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
  sudo="sudo"
else
  echo "rgraph: cannot install packages (not root, no passwordless sudo)." >&2
  echo "rgraph: please run: sudo apt-get install -y $packages" >&2
  exit 1
fi
if ! command -v apt-get >/dev/null 2>&1; then
  echo "rgraph: apt-get not found; install Mesa's lavapipe Vulkan driver and the Vulkan loader with your package manager." >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq >&2
$sudo apt-get install -y -qq $packages >&2
if ! icd_present; then
  echo "rgraph: installed $packages but the lavapipe ICD is still missing under /usr/share/vulkan/icd.d" >&2
  exit 1
fi
echo "rgraph: lavapipe installed" >&2
