#!/usr/bin/env bash
# The first command on a fresh Debian 12 machine (reads scenes/, writes build/ and out/): installs
# what is missing, builds the montecl target only, and renders two images, printing their paths:
#   out/materials-path.png  the materials Cornell box (smooth and rough glass, a mirror, rough gold)
#                           path traced with next-event estimation and MIS, 256x256, 128 spp,
#                           denoised where Open Image Denoise is installed (setup.sh --oidn)
#   out/demo-ao.png         the lecture's ambient-occlusion scene (scenes/demo), 640x480, 64 spp
# Compiler output and the OpenCL runtime's kernel-build messages go to out/demo.log, which is
# printed when a step fails. Prints the build and render times apart.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
mkdir -p out
log=out/demo.log
: >"$log"
# A fresh clone has no compiler cache: batched compiles take about half the CPU time.
export MONTECL_UNITY_BUILD=${MONTECL_UNITY_BUILD:-ON}
step() {  # step WHAT COMMAND...: runs the command with its output in the log; on failure shows it
  local what=$1
  shift
  echo "== $what: $*" >>"$log"
  if ! "$@" >>"$log" 2>&1; then
    tail -40 "$log" >&2
    echo "demo: $what failed; the whole log: $(pwd)/$log" >&2
    exit 1
  fi
}
start=$SECONDS
echo "demo: building montecl (build/; compiler output in $log)" >&2
step build bash scripts/build.sh montecl
built=$SECONDS
echo "demo: rendering" >&2
path=(build/montecl render scenes/materials/scene.json --integrator path -o out/materials-path.png)
echo "== path render, denoised: ${path[*]} --denoise" >>"$log"
if ! "${path[@]}" --denoise >>"$log" 2>&1; then  # exit 2 at once without the library
  echo "demo: not denoised (Open Image Denoise is not installed: bash scripts/setup.sh --oidn)" >&2
  step "path render" "${path[@]}"
fi
step "AO render" build/montecl render scenes/demo/scene.json -o out/demo-ao.png
echo "demo: build $((built - start)) s, renders $((SECONDS - built)) s" >&2
echo "$(pwd)/out/materials-path.png"
echo "$(pwd)/out/demo-ao.png"
