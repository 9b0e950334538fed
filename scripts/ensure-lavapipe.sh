#!/usr/bin/env bash
# Makes sure the lavapipe Vulkan driver (Mesa's CPU rasterizer) is installed, and a C++
# compiler (the nv-flip crate behind `rgraph bench` builds NVIDIA's FLIP from C++); with
# --tests also Xvfb and xwininfo (the virtual X display the `rgraph view` tests open their
# windows on, and what reads their titles) and Chromium (the browser the plan page's tests
# open it in). Installs what is missing with apt when we are root (or have sudo).
set -euo pipefail

icd_present() {
  ls /usr/share/vulkan/icd.d/lvp_icd.*.json >/dev/null 2>&1 && ldconfig -p 2>/dev/null | grep -q libvulkan.so.1
}

packages=""
icd_present || packages="mesa-vulkan-drivers libvulkan1"
command -v c++ >/dev/null 2>&1 || packages="$packages g++"
tests=false
[ "${1:-}" = --tests ] && tests=true
chromium_present() {
  [ -n "${RGRAPH_CHROMIUM:-}" ] || command -v chromium >/dev/null 2>&1 || command -v chromium-browser >/dev/null 2>&1
}
test_tools_present() {
  ! $tests || { [ -x /usr/bin/Xvfb ] && [ -x /usr/bin/xwininfo ] && chromium_present; }
}
if $tests; then
  [ -x /usr/bin/Xvfb ] || packages="$packages xvfb"
  [ -x /usr/bin/xwininfo ] || packages="$packages x11-utils"
  chromium_present || packages="$packages chromium"
fi
if [ -z "$packages" ]; then
  exit 0
fi
echo "rgraph: missing what the build or the GPU tests need; installing:$packages" >&2
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
  echo "rgraph: apt-get not found; install with your package manager:$packages (Mesa's lavapipe Vulkan driver, the Vulkan loader, a C++ compiler, Xvfb, xwininfo, Chromium)" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq >&2
$sudo apt-get install -y -qq $packages >&2
if ! icd_present || ! command -v c++ >/dev/null 2>&1 || ! test_tools_present; then
  echo "rgraph: installed ${packages# } but the lavapipe ICD (/usr/share/vulkan/icd.d), c++, /usr/bin/Xvfb, /usr/bin/xwininfo or chromium is still missing" >&2
  exit 1
fi
echo "rgraph: installed ${packages# }" >&2
