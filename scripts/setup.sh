#!/usr/bin/env bash
# Installs, only when missing, every Debian package montecl needs to build, test and benchmark.
# Idempotent: a second run installs nothing and does not touch the network.
set -euo pipefail

packages=(
  cmake g++ make ninja-build pkg-config
  clang-14 libclang-rt-14-dev
  ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers pocl-opencl-icd clinfo oclgrind
  libglm-dev libtinyobjloader-dev libtinygltf-dev libdraco-dev libpugixml-dev libopenimageio-dev libopenexr-dev openimageio-tools libpng-dev
  libjpeg62-turbo-dev libstb-dev
  doctest-dev nlohmann-json3-dev libcli11-dev
  libembree-dev jq bc
  openmpi-bin libopenmpi-dev
)

# clang-14 and its ASan/UBSan/libFuzzer runtimes (libclang-rt-14-dev) build the sanitized build
# (scripts/sanitize.sh: the suite and the libFuzzer harnesses in one). Only the plotting scripts
# need matplotlib: `setup.sh --plots` adds it.
# Only scripts/vs_mitsuba.py (and its test) needs Mitsuba 3: `setup.sh --mitsuba` adds python3-venv
# and libllvm19 (Mitsuba's llvm_ad_rgb variant needs an LLVM newer than Debian's default) and
# installs PyPI's mitsuba + numpy into a cached venv, $MONTECL_MITSUBA_VENV or
# ~/.cache/montecl/mitsuba-venv (about 100 MB; skipped when it already imports mitsuba), with
# NVlabs' FLIP metric (PyPI flip-evaluator, BSD-3) for scripts/convergence.py --vs-time.
# `setup.sh --intel-opencl` adds Intel's CPU OpenCL runtime (PyPI intel-opencl-rt +
# intel-cmplr-lib-rt, about 270 MB to download, 0.5 GB installed) into a cached venv,
# $MONTECL_INTEL_OPENCL_VENV or ~/.cache/montecl/intel-opencl-venv (skipped when its libintelocl.so
# is there); scripts/with_intel_opencl.sh runs a command with it visible beside PoCL.
# Only `montecl render --denoise` needs Open Image Denoise: `setup.sh --oidn` installs PyPI's pyoidn
# 2.5.1 wheel (it bundles OIDN 2.5.1's shared libraries with TBB; about 270 MB installed) into a
# cached venv, $MONTECL_OIDN_VENV or ~/.cache/montecl/oidn-venv (skipped when its
# libOpenImageDenoise.so.2 is there); montecl dlopens the library from there.
mitsuba=0
intel_opencl=0
oidn=0
for arg in "$@"; do
  case "$arg" in
    --plots) packages+=(python3-matplotlib) ;;
    --mitsuba) packages+=(python3-venv libllvm19); mitsuba=1 ;;
    --intel-opencl) packages+=(python3-venv); intel_opencl=1 ;;
    --oidn) packages+=(python3-venv); oidn=1 ;;
  esac
done

mitsuba_venv() {
  [ "$mitsuba" = 1 ] || return 0
  local venv=${MONTECL_MITSUBA_VENV:-$HOME/.cache/montecl/mitsuba-venv}
  if [ -x "$venv/bin/python" ] && "$venv/bin/python" -c 'import mitsuba, numpy, flip_evaluator' 2>/dev/null; then
    return 0
  fi
  echo "setup: installing Mitsuba 3 and FLIP (PyPI mitsuba, numpy, flip-evaluator) into $venv" >&2
  mkdir -p "$(dirname "$venv")"
  [ -x "$venv/bin/python" ] || python3 -m venv "$venv"
  "$venv/bin/pip" install -q --disable-pip-version-check mitsuba numpy flip-evaluator >&2
}

intel_opencl_venv() {
  [ "$intel_opencl" = 1 ] || return 0
  local venv=${MONTECL_INTEL_OPENCL_VENV:-$HOME/.cache/montecl/intel-opencl-venv}
  if [ -e "$venv/lib/libintelocl.so" ]; then
    return 0
  fi
  echo "setup: installing Intel's CPU OpenCL runtime (PyPI intel-opencl-rt, intel-cmplr-lib-rt) into $venv" >&2
  mkdir -p "$(dirname "$venv")"
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q --disable-pip-version-check intel-opencl-rt intel-cmplr-lib-rt >&2
  # The wheels hold the big libraries twice (libX.so and libX.so.<version>, no links): link them.
  local f v
  for f in "$venv"/lib/*.so; do
    for v in "$f".*; do
      if [ -f "$v" ] && [ ! -L "$v" ] && [ ! -L "$f" ] && cmp -s "$f" "$v"; then
        ln -sf "$(basename "$v")" "$f"
      fi
    done
  done
}

oidn_venv() {
  [ "$oidn" = 1 ] || return 0
  local venv=${MONTECL_OIDN_VENV:-$HOME/.cache/montecl/oidn-venv}
  if compgen -G "$venv/lib/python*/site-packages/pyoidn/oidn/lib/libOpenImageDenoise.so.2" >/dev/null; then
    return 0
  fi
  echo "setup: installing Open Image Denoise 2.5.1 (PyPI pyoidn) into $venv" >&2
  mkdir -p "$(dirname "$venv")"
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q --disable-pip-version-check pyoidn==2.5.1.0 >&2
}

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  mitsuba_venv
  intel_opencl_venv
  oidn_venv
  exit 0
fi

echo "setup: installing ${missing[*]}" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
mitsuba_venv
intel_opencl_venv
oidn_venv
