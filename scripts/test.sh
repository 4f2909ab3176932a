#!/usr/bin/env bash
# The test command: installs the build and test dependencies, builds everything, runs
# the whole test suite:
# the GoogleTest suites (core, storage, server, end-to-end over loopback), a
# short run of every fuzzer (fuzz/), the Kubernetes manifest checks, pbrt-v4 with the aligned sampler (given
# ALIGNSET_PBRT_SOURCE, a pbrt-v4 source folder), and, as root, the real container image build and
# run (deploy/test-container.sh). ALIGNSET_SKIP_CONTAINER=1 leaves the image
# test out (it needs root and takes minutes).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --test
# Tests and benchmarks on, also in a build directory the quickstart configured without them.
bash scripts/build.sh -DALIGNSET_BUILD_TESTS=ON -DALIGNSET_BUILD_BENCH=ON
BUILD_DIR="${BUILD_DIR:-build}"
# pbrt-v4 with the aligned sampler, from a pbrt-v4 source folder when one is
# given (its CTest, Pbrt.AlignedSamplerInPbrt, is skipped without one).
if [ -n "${ALIGNSET_PBRT_SOURCE:-}" ]; then
  BUILD_DIR="$BUILD_DIR" bash integrations/pbrt-v4/build.sh "$ALIGNSET_PBRT_SOURCE"
else
  echo "test.sh: no ALIGNSET_PBRT_SOURCE: pbrt-v4 is not built and its test is skipped"
fi
(cd "$BUILD_DIR" && ctest -j "${JOBS:-$(nproc)}" --output-on-failure --timeout 900)

# Every fuzzer of fuzz/ for a short run from its seed corpus (libFuzzer with
# AddressSanitizer and UndefinedBehaviorSanitizer; scripts/fuzz.sh runs them longer).
bash scripts/fuzz.sh "${ALIGNSET_FUZZ_SECONDS:-20}"

bash deploy/check-manifests.sh
if [ "${ALIGNSET_SKIP_CONTAINER:-0}" = 1 ]; then
  echo "test.sh: container image test skipped (ALIGNSET_SKIP_CONTAINER=1)"
elif [ "$(id -u)" -ne 0 ]; then
  echo "test.sh: container image test needs root; run 'sudo bash deploy/test-container.sh'"
else
  ALIGNSET_HOST_CLI="$BUILD_DIR/cli/alignset" bash deploy/test-container.sh
fi
