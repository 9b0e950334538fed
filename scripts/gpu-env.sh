# Sourced by the scripts that run rgraph on an NVIDIA server (no network, no display):
# the Vulkan loader unpacked from .gl/*.deb where ldconfig finds none (../shared/notes/gpu.md
# names the packages), the loader pointed at the NVIDIA driver, nvidia-smi on the PATH where
# the driver's folder has it (the bench samples the GPU's clocks with it), the GPU adapter
# picked, and the commit the binary was built from taken from git where the server has a
# checkout (else set RGRAPH_GIT_COMMIT). Run from the repository root; `tool` names the
# caller in messages.

if ! ldconfig -p | grep -q libvulkan; then
  debs=(.gl/*.deb)
  if [ ! -e "${debs[0]}" ]; then
    echo "$tool: no Vulkan loader (libvulkan) and no .debs in .gl/ to unpack;" \
         "see ../shared/notes/gpu.md" >&2
    exit 2
  fi
  for deb in "${debs[@]}"; do dpkg -x "$deb" /; done
  ldconfig
fi
nvidia_icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
if [ -z "${VK_DRIVER_FILES:-}" ] && [ -f "$nvidia_icd" ]; then
  export VK_DRIVER_FILES="$nvidia_icd"
fi
if ! command -v nvidia-smi >/dev/null 2>&1 && [ -x /usr/local/nvidia/bin/nvidia-smi ]; then
  export PATH="$PATH:/usr/local/nvidia/bin"
fi
command -v nvidia-smi >/dev/null 2>&1 \
  || echo "$tool: no nvidia-smi: the results will say the GPU clocks are not reported" >&2
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
export RGRAPH_ADAPTER="${RGRAPH_ADAPTER:-gpu}"
if [ -z "${RGRAPH_GIT_COMMIT:-}" ] && git rev-parse HEAD >/dev/null 2>&1; then
  export RGRAPH_GIT_COMMIT="$(git rev-parse HEAD)"
fi
