#!/usr/bin/env bash
# Installs the Debian packages wavetrace builds with, and only those that are missing.
# Idempotent and silent when everything is already there.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libtbb-dev            # oneTBB: parallel_for / parallel_invoke / global_control
  libhwy-dev            # Google Highway: SIMD kernels for every x86/ARM target, chosen at run time
  libopenimageio-dev    # image textures in, PNG/JPEG/EXR/HDR/PFM out
  openimageio-tools     # Debian's OpenImageIO CMake config imports its tools (iconvert, idiff, ...) as targets
  libembree-dev         # Embree 3: the intersection reference in tests and benchmarks
  libassimp-dev         # meshes: OBJ+MTL, PLY (ASCII and binary), glTF 2.0
  zlib1g-dev            # assimp's CMake config links libz.so (libassimp-dev does not depend on it); tests
  nlohmann-json3-dev    # scene files
  libpugixml-dev        # Mitsuba 3 XML scene files
  libcli11-dev          # command line
  libfmt-dev            # formatting
  libgtest-dev libgmock-dev
  libbenchmark-dev
  clang libclang-rt-14-dev  # make sanitize / make fuzz: ASan, UBSan and libFuzzer runtimes
  slurm-wlm munge       # the `slurm` test: a one-node cluster runs an array render and its merge
  python3-dev pybind11-dev          # the Python module (python/)
  python3-numpy python3-pytest      # its arrays and its tests
  python3-matplotlib    # the Python example's plot (examples/python/)
)

# `install-deps.sh --bench` adds what `make bench` needs beyond the build: gnuplot for plots.
# `install-deps.sh --list` prints the packages instead of installing them (tools/check-deps.sh).
list=0
for arg in "$@"; do
  case "$arg" in
    --bench) packages+=(gnuplot-nox) ;;
    --list) list=1 ;;
    *) echo "usage: $0 [--bench] [--list]" >&2; exit 2 ;;
  esac
done
if [[ $list -eq 1 ]]; then
  printf '%s\n' "${packages[@]}"
  exit 0
fi

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

echo "install-deps: installing ${missing[*]}" >&2
sudo=""
if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq >/dev/null
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
