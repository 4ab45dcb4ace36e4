#!/usr/bin/env bash
# with_intel_opencl.sh CMD [ARGS...]: runs CMD with Intel's CPU OpenCL runtime visible beside the
# system's OpenCL drivers (PoCL), e.g. `scripts/with_intel_opencl.sh build/montecl devices`.
# The runtime is the venv that `scripts/setup.sh --intel-opencl` installs
# ($MONTECL_INTEL_OPENCL_VENV, default ~/.cache/montecl/intel-opencl-venv). It is registered through
# OCL_ICD_FILENAMES (Intel's libintelocl.so, then every library named in /etc/OpenCL/vendors/*.icd)
# and LD_LIBRARY_PATH=<venv>/lib: the venv's own ICD loader (Khronos) is the one that honours the
# list; Debian's ocl-icd does not load libintelocl.so. Exit 3 when the runtime is not installed.
set -euo pipefail
venv=${MONTECL_INTEL_OPENCL_VENV:-$HOME/.cache/montecl/intel-opencl-venv}
lib="$venv/lib/libintelocl.so"
if [ ! -e "$lib" ]; then
  echo "with_intel_opencl: $lib not found: run scripts/setup.sh --intel-opencl" >&2
  exit 3
fi
if [ $# -eq 0 ]; then
  echo "usage: with_intel_opencl.sh CMD [ARGS...]" >&2
  exit 2
fi
files="$lib"
for icd in /etc/OpenCL/vendors/*.icd; do
  [ -r "$icd" ] || continue
  entry=$(head -n1 "$icd" | tr -d '[:space:]')
  [ -n "$entry" ] && files="$files:$entry"
done
export OCL_ICD_FILENAMES="$files"
export LD_LIBRARY_PATH="$venv/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
exec "$@"
