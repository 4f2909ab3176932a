#!/usr/bin/env bash
# Installs alignset's dependencies from Debian 12 packages. Idempotent: packages
# already present are skipped.
#
#   scripts/install-deps.sh          what building and running alignset needs (the
#                                    quickstart, the container image's build stage)
#   scripts/install-deps.sh --test   that, plus what the test suite, the benchmarks,
#                                    the plots, the container test, the pbrt-v4
#                                    build and the fuzzers need (scripts/test.sh)
#   scripts/install-deps.sh --pbrt   the build's, plus pbrt-v4's (integrations/pbrt-v4)
set -euo pipefail

# Compilers and the libraries the CLI, the server and the client library link
# (and Boost's headers: Boost.Random's table of Sobol direction numbers).
BUILD_PACKAGES=(
  build-essential cmake ninja-build pkg-config git ca-certificates
  libeigen3-dev libfftw3-dev
  libsqlite3-dev
  libgrpc++-dev libprotobuf-dev protobuf-compiler protobuf-compiler-grpc
  libspdlog-dev libfmt-dev libcli11-dev libboost-dev
  libssl-dev libmicrohttpd-dev
)
# GoogleTest and Google Benchmark, the tools the tests drive (sqlite3, openssl for the TLS
# test), Python with the packages of the Python client (pybind11 for its sampler module), its test, the plots and the
# manifest check, and the daemon-less container build of deploy/test-container.sh.
TEST_PACKAGES=(
  libgtest-dev libgmock-dev libbenchmark-dev
  sqlite3 openssl
  python3 python3-numpy python3-matplotlib python3-yaml python3-grpcio python3-protobuf
  python3-grpc-tools python3-dev pybind11-dev
  yamllint buildah podman debootstrap
)

# What pbrt-v4 (integrations/pbrt-v4/build.sh) builds against: its git
# submodules' Debian packages (Ptex and wjakob/filesystem have stand-ins), and
# ccache, which makes a rebuild after a patch to pbrt's headers take seconds.
PBRT_PACKAGES=(
  libopenexr-dev libdouble-conversion-dev libstb-dev libdeflate-dev libutf8proc-dev
  libglfw3-dev libnanovdb-dev liblodepng-dev libqoi-dev zlib1g-dev libgl-dev ccache
)

# Debian's clang with libFuzzer's runtime: the fuzzers of fuzz/ (scripts/fuzz.sh,
# and their short run in the test command).
FUZZ_PACKAGES=(clang libclang-rt-14-dev)

case "${1:-}" in
  "") PACKAGES=("${BUILD_PACKAGES[@]}") ;;
  --test) PACKAGES=("${BUILD_PACKAGES[@]}" "${TEST_PACKAGES[@]}" "${PBRT_PACKAGES[@]}" "${FUZZ_PACKAGES[@]}") ;;
  --pbrt) PACKAGES=("${BUILD_PACKAGES[@]}" "${PBRT_PACKAGES[@]}") ;;
  *) echo "usage: $0 [--test | --pbrt]" >&2; exit 2 ;;
esac

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
