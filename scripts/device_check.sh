#!/usr/bin/env bash
# device_check.sh: the one prepared check for a lent GPU machine, whose time is short (about 15
# minutes in all, its start included): installs what that machine lacks, builds the montecl target
# only, then `montecl devices`, `montecl conformance` (the device against the host backend, bit for
# bit) and the speed rows (`montecl bench` on Sponza; Cornell box and Sponza path renders with
# --profile), each step under its own time limit so the whole stays under 8 minutes. Reads the
# tree and the shared scenes; writes a build folder and one summary file (Markdown: a table of
# the steps' times and results, then each step's output).
#
# Usage: scripts/device_check.sh [--device SPEC] [--out FILE] [--scenes DIR] [--build DIR]
#                                [--binary EXE] [--small] [--pack DIR]
#   --device SPEC  the OpenCL device (`montecl devices`: P:D or part of its name); default: every
#                  device for conformance, montecl's own pick for the speed rows
#   --out FILE     the summary; default $OUT/device_check.md where OUT is set (the device tool's
#                  folder that comes back), else device_check.md here
#   --scenes DIR   the shared scenes; default ../shared/scenes, else shared/scenes (a folder inside
#                  the checkout travels to the device machine; ../shared does not). Rows whose scene
#                  is absent are reported as skipped.
#   --build DIR    the build folder (default build-device); configured only when it has no cache
#   --binary EXE   a montecl built elsewhere (no install, no build); with --pack's folder: its montecl
#   --small        tiny sizes and one repetition: the dry run on the CPU that CI runs (CMakeLists.txt,
#                  test device_check:dry_run, `--device portable`: PoCL), so the script does not rot
#   --pack DIR     instead of checking: builds montecl here and copies it with the shared libraries
#                  it loads (glibc's aside) into DIR, for a machine that cannot install packages (the
#                  lent ones reach no registry): carry DIR, then run with --binary DIR/montecl
# Exit status: 0 when every step that ran passed (skipped rows count as passed), else 1.
set -uo pipefail
cd "$(dirname "$0")/.."

device="" out="" scenes="" build=build-device binary="" small=0 pack=""
while [ $# -gt 0 ]; do
  case "$1" in
    --device) device=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --scenes) scenes=$2; shift 2 ;;
    --build) build=$2; shift 2 ;;
    --binary) binary=$2; shift 2 ;;
    --small) small=1; shift ;;
    --pack) pack=$2; shift 2 ;;
    -h|--help) sed -n '2,/^# Exit status/p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "device_check: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done

build_montecl() {  # build_montecl DIR: the montecl target only (DIR configured once)
  if [ ! -f "$1/CMakeCache.txt" ]; then
    bash scripts/configure.sh "$1" -DCMAKE_BUILD_TYPE=Release || return 1
  fi
  cmake --build "$1" -j"$(nproc)" --target montecl
}

if [ -n "$pack" ]; then
  build_montecl "$build" >/dev/null || { echo "device_check: the build failed" >&2; exit 1; }
  mkdir -p "$pack/lib"
  cp "$build/montecl" "$pack/"
  # Every library it loads but the C runtime's own (the machine's glibc is as new or newer).
  ldd "$build/montecl" | awk '$3 ~ /^\// { print $3 }' |
    grep -vE '/(libc|libm|libdl|libpthread|librt|ld-linux[^/]*)\.so' | xargs -r cp -L -t "$pack/lib"
  echo "device_check: packed $(du -sh "$pack" | cut -f1) into $pack; run: scripts/device_check.sh --binary $pack/montecl"
  exit 0
fi

if [ -z "$scenes" ]; then
  scenes=../shared/scenes
  [ -d "$scenes" ] || scenes=shared/scenes
fi
if [ -z "$out" ]; then out=${OUT:+$OUT/}device_check.md; fi
mkdir -p "$(dirname "$out")"
log=$(mktemp -d)
trap 'rm -rf "$log"' EXIT
dev=(${device:+--device "$device"})
start=$SECONDS
rows=() status=0

# step NAME LIMIT_S CMD...: runs CMD (a program or a function of this script) with its output in
# the log, under LIMIT_S seconds; one row. A CMD that exits 77 was skipped (its reason: the last
# line it printed).
step() {
  local name=$1 limit=$2 t0=$SECONDS rc result
  shift 2
  echo "device_check: $name" >&2
  if [ "$(type -t "$1")" = function ]; then  # (timeout runs programs: the function goes with a bash)
    timeout "$limit" bash -c "$(declare -f "$1"); \"\$@\"" step "$@" >"$log/$name.txt" 2>&1
  else
    timeout "$limit" "$@" >"$log/$name.txt" 2>&1
  fi
  rc=$?
  case $rc in
    0) result=pass ;;
    77) result="skipped: $(tail -n 1 "$log/$name.txt")" ;;
    124) result="timed out after ${limit} s"; status=1 ;;
    *) result="failed (exit $rc)"; status=1 ;;
  esac
  rows+=("| $name | $((SECONDS - t0)) | $result |")
  names+=("$name")
}
names=()

# --- what the machine lacks, and the build ----------------------------------------------------------
if [ -n "$binary" ]; then
  exe=$binary
  # A packed binary (--pack) brings its libraries beside it.
  [ -d "$(dirname "$exe")/lib" ] && export LD_LIBRARY_PATH="$(cd "$(dirname "$exe")/lib" && pwd)${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
else
  exe=$build/montecl
  install() {
    # Debian: scripts/setup.sh installs only the packages that are missing (nothing on a second run).
    if [ -f /etc/debian_version ] && command -v apt-get >/dev/null; then bash scripts/setup.sh; return; fi
    echo "not Debian: nothing installed (a build error below names what is missing; or use --pack)"
    return 77
  }
  step install 240 install
  step build 300 build_montecl "$build"
fi
# The vendor's ICD is there but may not be registered with the loader (no /etc/OpenCL/vendors entry).
if [ -z "${OCL_ICD_VENDORS:-}" ] && [ ! -d /etc/OpenCL/vendors ]; then
  nv=$(ldconfig -p 2>/dev/null | awk '/libnvidia-opencl\.so\.1/ { print $NF; exit }')
  if [ -n "$nv" ]; then
    mkdir -p "$log/vendors" && echo "$nv" >"$log/vendors/nvidia.icd" && export OCL_ICD_VENDORS=$log/vendors
  fi
fi

# --- devices, conformance, speed ----------------------------------------------------------------------
step devices 60 "$exe" devices
if [ "$small" = 1 ]; then
  conf=(--size 8 --spp 1 --cornell-size 8 --cornell-spp 1)
  bench=(--repeat 1 --warmup 0 --width 32 --height 18 --no-embree)
  cornell=(--width 32 --height 32 --spp 1) sponza=(--width 32 --height 18 --spp 1)
else
  conf=()
  bench=(--repeat 5 --width 1920 --height 1080)
  cornell=(--width 1024 --height 1024 --spp 256) sponza=(--width 1920 --height 1080 --spp 64)
fi
step conformance 240 "$exe" conformance "${dev[@]}" --cornell "$scenes/cornell-box/scene.json" "${conf[@]}"
scene_step() {  # scene_step NAME LIMIT SCENE CMD...: skipped when the scene is absent
  local name=$1 limit=$2 scene=$3
  shift 3
  if [ -f "$scene" ]; then
    step "$name" "$limit" "$@"
  else
    echo "no $scene" >"$log/$name.txt"
    rows+=("| $name | 0 | skipped: no $scene |")
    names+=("$name")
  fi
}
sponza_scene=$scenes/sponza/scene.json cornell_scene=$scenes/cornell-box/scene.json
scene_step bench-sponza 120 "$sponza_scene" "$exe" bench "$sponza_scene" "${dev[@]}" "${bench[@]}" -q
scene_step path-cornell 90 "$cornell_scene" "$exe" render "$cornell_scene" "${dev[@]}" --integrator path \
  "${cornell[@]}" --profile -q -o "$log/cornell.png"
scene_step path-sponza 120 "$sponza_scene" "$exe" render "$sponza_scene" "${dev[@]}" --integrator path \
  "${sponza[@]}" --profile -q -o "$log/sponza.png"

# --- the summary ---------------------------------------------------------------------------------------
total=$((SECONDS - start))
{
  echo "# montecl device check"
  echo
  echo "$(date -u '+%Y-%m-%d %H:%M UTC'), $(hostname), commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown)," \
       "device ${device:-(default)}$([ "$small" = 1 ] && echo ', --small (dry run)'), $total s in all" \
       "$([ "$total" -gt 480 ] && echo '(over the 8-minute budget)')"
  echo
  echo "| step | seconds | result |"
  echo "|---|---:|---|"
  printf '%s\n' "${rows[@]}"
  for name in "${names[@]}"; do
    echo
    echo "## $name"
    echo
    echo '```'
    tail -n 60 "$log/$name.txt"
    echo '```'
  done
} >"$out"
echo "device_check: $total s; summary in $out" >&2
printf '%s\n' "${rows[@]}" >&2
exit $status
