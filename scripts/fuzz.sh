#!/usr/bin/env bash
# Fuzzes the problem loader with libFuzzer for SECONDS (default 60), starting from the shipped
# problems and the malformed test files. Exits non-zero if the fuzzer finds a crash, a
# sanitizer error or an exception other than InputError; the input that did it is saved in
# build-fuzz/artifacts/.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
./scripts/install-deps.sh
if [ ! -f build-fuzz/CMakeCache.txt ]; then
  CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DKAUTHAM_BUILD_FUZZERS=ON >/dev/null
fi
cmake --build build-fuzz --parallel "$(nproc)"
corpus=build-fuzz/corpus
mkdir -p "$corpus" build-fuzz/artifacts
cp problems/*.xml tests/data/*.xml tests/data/malformed/*.xml "$corpus/"
./build-fuzz/tests/fuzz/problem_loader_fuzzer "$corpus" -max_total_time="$seconds" \
  -max_len=16384 -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
  -artifact_prefix=build-fuzz/artifacts/ 2>&1 | grep -v '^#[0-9]*.*\(NEW\|REDUCE\|pulse\)' || {
  echo "fuzz: the problem loader failed; see build-fuzz/artifacts/" >&2
  exit 1
}
