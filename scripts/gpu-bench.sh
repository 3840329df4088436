#!/usr/bin/env bash
# Builds and runs the GPU crowd-skinning benchmarks and prints one Markdown report: cga-gl-bench (OpenGL 4.5
# through EGL: vertex shader + transform feedback and compute, every method), cga-draw-bench (characters
# drawn with the skinning vertex shader) and, when the build has it (CMake found nvcc), cga-cuda-bench. The
# report names the machine (nvidia-smi's GPU name and driver when present, the GL renderer, the CPU) and is
# also written to $REPORT. Exit status: 0 when every benchmark ran and passed its check against the CPU
# SkinningJob, else the first failing status.
#
#   scripts/gpu-bench.sh [--no-build] [options for cga-gl-bench and cga-cuda-bench...]
#   scripts/gpu-bench.sh --bundle DIR
#   --no-build    run the binaries already in $BUILD_DIR (e.g. a bundle carried from another machine)
#   --bundle DIR  build, then copy the benchmarks and the shared libraries they need that a bare machine may
#                 lack (everything but glibc, libstdc++/libgcc and the GL/EGL loaders) into DIR, laid out so
#                 that `BUILD_DIR=DIR scripts/gpu-bench.sh --no-build` runs them there; runs nothing
#   other options go to cga-gl-bench and cga-cuda-bench: --vertices N --instances I --bones B --iterations K
#   --normals --mesh coherent|random|both (cga-draw-bench takes only DRAW_ARGS: its options differ)
# Environment: BUILD_DIR (default build), JOBS (build parallelism, default 2), REPORT (default
#              $BUILD_DIR/gpu-bench.md), GL_ARGS / CUDA_ARGS / DRAW_ARGS (options for one benchmark only,
#              e.g. GL_ARGS="--inputs shared", DRAW_ARGS="--characters 256"), GL_DEBS (a folder of Debian GL
#              loader packages, libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2, unpacked into / first:
#              for a machine with the NVIDIA driver but no GL loaders, as the device machines; needs root).
# On a device machine (see docs/gpu.md): here `BUILD_DIR=build-gl scripts/gpu-bench.sh --bundle build-gpubench`,
# there (carrying .gl and build-gpubench)
#   GL_DEBS=.gl BUILD_DIR=build-gpubench REPORT=$OUT/gpu-bench.md scripts/gpu-bench.sh --no-build
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD_DIR=${BUILD_DIR:-build}
JOBS=${JOBS:-2}
build=1
bundle=""
args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --no-build) build=0 ;;
    --bundle)
      [ $# -ge 2 ] || { echo "gpu-bench.sh: --bundle needs a folder" >&2; exit 2; }
      bundle=$2
      shift ;;
    *) args+=("$1") ;;
  esac
  shift
done
REPORT=${REPORT:-$BUILD_DIR/gpu-bench.md}
read -r -a gl_args <<<"${GL_ARGS:-}"
read -r -a cuda_args <<<"${CUDA_ARGS:-}"
read -r -a draw_args <<<"${DRAW_ARGS:-}"

if [ -n "${GL_DEBS:-}" ]; then
  for f in "$GL_DEBS"/*.deb; do dpkg -x "$f" /; done
  ldconfig
fi
# The NVIDIA driver's EGL vendor file where glvnd does not look by default (containers with the driver mounted).
nvidia_egl=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
if [ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" ] && [ -f "$nvidia_egl" ] &&
   ! ls /usr/share/glvnd/egl_vendor.d/*nvidia*.json >/dev/null 2>&1; then
  export __EGL_VENDOR_LIBRARY_FILENAMES=$nvidia_egl
fi

gl_bench=$BUILD_DIR/runtime/gpu/cga-gl-bench
draw_bench=$BUILD_DIR/runtime/gpu/cga-draw-bench
cuda_bench=$BUILD_DIR/runtime/cuda/cga-cuda-bench
if [ "$build" = 1 ]; then
  cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
  targets=(cga-gl-bench cga-draw-bench)
  # cga-cuda-bench exists only when CMake found nvcc.
  if cmake --build "$BUILD_DIR" --target help 2>/dev/null | grep -q '^cga-cuda-bench:'; then targets+=(cga-cuda-bench); fi
  cmake --build "$BUILD_DIR" --target "${targets[@]}" -j "$JOBS" >&2
fi
if [ ! -x "$gl_bench" ]; then
  echo "gpu-bench.sh: no $gl_bench (build it, or drop --no-build)" >&2
  exit 2
fi

if [ -n "$bundle" ]; then
  mkdir -p "$bundle/runtime/gpu" "$bundle/lib"
  bins=("$gl_bench" "$draw_bench")
  cp "$gl_bench" "$draw_bench" "$bundle/runtime/gpu/"
  if [ -x "$cuda_bench" ]; then
    mkdir -p "$bundle/runtime/cuda"
    cp "$cuda_bench" "$bundle/runtime/cuda/"
    bins+=("$cuda_bench")
  fi
  skip='^(linux-vdso|ld-linux|libc|libm|libdl|libpthread|librt|libstdc\+\+|libgcc_s|libEGL|libOpenGL|libGL|libGLX|libGLdispatch)\.'
  for lib in $(ldd "${bins[@]}" | awk '$2 == "=>" && $3 ~ /^\// {print $3}' | sort -u); do
    if ! basename "$lib" | grep -Eq "$skip"; then cp -L "$lib" "$bundle/lib/"; fi
  done
  echo "gpu-bench.sh: bundled into $bundle: $(cd "$bundle" && find . -type f | sort | tr '\n' ' ')" >&2
  exit 0
fi
if [ -d "$BUILD_DIR/lib" ]; then export LD_LIBRARY_PATH="$BUILD_DIR/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"; fi

status=0
gl_out=$("$gl_bench" "${args[@]}" "${gl_args[@]}" 2>&1) || status=$?
draw_out=""
draw_status=0
if [ -x "$draw_bench" ]; then
  draw_out=$("$draw_bench" "${draw_args[@]}" 2>&1) || draw_status=$?
  if [ "$status" = 0 ]; then status=$draw_status; fi
fi
cuda_out=""
cuda_status=0
if [ -x "$cuda_bench" ]; then
  cuda_out=$("$cuda_bench" "${args[@]}" "${cuda_args[@]}" 2>&1) || cuda_status=$?
  if [ "$status" = 0 ]; then status=$cuda_status; fi
fi

gpu="none found (no nvidia-smi)"
if command -v nvidia-smi >/dev/null 2>&1; then
  gpu=$(nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2>/dev/null | head -1 || true)
  gpu=${gpu:-"nvidia-smi gave no answer"}
fi
renderer=$(sed -n 's/^device: \(.*\)), [0-9]* vertices per instance.*/\1)/p' <<<"$gl_out" | head -1)
cpu=$(lscpu 2>/dev/null | sed -n 's/^Model name:[[:space:]]*//p' | head -1)
{
  echo "## GPU crowd-skinning benchmarks"
  echo
  echo "- GPU (nvidia-smi): ${gpu}"
  echo "- GL renderer: ${renderer:-unknown (cga-gl-bench failed before printing it)}"
  echo "- CPU: ${cpu:-unknown}, $(nproc --all) cores"
  echo "- Date: $(date -u '+%Y-%m-%d %H:%M UTC'). Reproduce: \`scripts/gpu-bench.sh ${args[*]}\`"
  echo
  echo "### OpenGL: cga-gl-bench ${args[*]} ${gl_args[*]}"
  echo
  echo "$gl_out"
  echo
  echo "### OpenGL draw path: cga-draw-bench ${draw_args[*]}"
  echo
  echo "${draw_out:-(no $draw_bench)}"
  [ "$draw_status" = 0 ] || echo "(cga-draw-bench exited with status $draw_status)"
  if [ -x "$cuda_bench" ]; then
    echo
    echo "### CUDA: cga-cuda-bench ${args[*]} ${cuda_args[*]}"
    echo
    echo "$cuda_out"
    [ "$cuda_status" = 0 ] || echo "(cga-cuda-bench exited with status $cuda_status)"
  else
    echo
    echo "(no $cuda_bench: this build found no CUDA compiler)"
  fi
} | tee "$REPORT"
exit "$status"
