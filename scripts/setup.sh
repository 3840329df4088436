#!/usr/bin/env bash
# Installs the Debian packages cgagen needs, and only those that are missing.
# Safe to run again: when everything is present it touches nothing and takes a second.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libginac-dev libcln-dev libfmt-dev libglm-dev
  glslang-dev glslang-tools spirv-tools
  libhwy-dev                                 # targets: simd (Google Highway), the runtime's batch kernels
  g++-aarch64-linux-gnu qemu-user            # targets: simd-aarch64 (NEON, run under qemu)
  catch2 libassimp-dev assimp-testmodels libbenchmark-dev
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libstb-dev
  clang libclang-rt-14-dev
  dpkg-dev
  python3-numpy                              # targets: python (Debian's /usr/bin/python3)
  python3-pyflakes                           # targets/warnings: the Python output's lint
  nodejs                                     # targets: javascript (node)
  rustc                                      # targets: rust (no cargo, no crates)
  pocl-opencl-icd ocl-icd-opencl-dev opencl-c-headers   # targets: opencl on the CPU
  spirv-cross                                # targets: hlsl (SPIR-V -> GLSL for the GL 4.5 run)
  texlive-latex-base graphviz                # targets: latex (pdflatex), dot
  chromium-headless-shell                    # targets: wgsl (WebGPU), glsl-es (WebGL 2), on SwiftShader
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: not root and no sudo; install: ${missing[*]}" >&2; exit 1; }
  SUDO=sudo
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y --no-install-recommends "${missing[@]}"
