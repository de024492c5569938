#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan, build-fuzz/) and runs each for a bounded time,
# as many at once as there are cores (each libFuzzer process uses one).
#   bash scripts/fuzz.sh                 # every target, 60 s each
#   FUZZ_SECONDS=1800 bash scripts/fuzz.sh config png16
# Each target starts from tests/fuzz/corpus/<target> (read-only) and keeps what it finds in
# build-fuzz/corpus/<target>. A crash fails with exit 1 and leaves the input in
# build-fuzz/crashes/<target>/: copy it to tests/fuzz/regressions/<target>/ (ctest replays it as
# fuzz_replay_<target>) and fix the parser. Prints executions and coverage per target.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-60}
build=${FUZZ_BUILD_DIR:-build-fuzz}
jobs=${FUZZ_JOBS:-$(nproc)}
targets=("$@")
[[ ${#targets[@]} -gt 0 ]] || targets=(config camera_path hgt png16 r16 r32f)
bash scripts/install-deps.sh
bash scripts/apt-install.sh clang libclang-rt-14-dev  # Debian 12's clang 14 and its libFuzzer runtime
start=$(date +%s)
# -O1 -g1, as the sanitizer pass of scripts/test.sh: compiles in about half the time of -O2 -g and
# keeps file:line in a crash's stack.
CC=clang CXX=clang++ cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLODBENCH_FUZZ=ON \
  -DLODBENCH_TESTS=OFF -DLODBENCH_BENCH=OFF "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" >/dev/null
cmake --build "$build" -j "$(nproc)" --target "${targets[@]/#/fuzz_}"
echo "fuzz: build $(( $(date +%s) - start )) s"

run() {  # target -> exit status of libFuzzer
  local t=$1
  mkdir -p "$build/corpus/$t" "$build/crashes/$t"
  # -rss_limit_mb: ASan's shadow memory on top of the inputs' decoding. Leak checks are off:
  # nothing leaks by design, but libFuzzer would report the loaders' cached statics.
  ASAN_OPTIONS=detect_leaks=0 "$build/fuzz_$t" "$build/corpus/$t" "tests/fuzz/corpus/$t" \
    -max_total_time="$seconds" -timeout=30 -rss_limit_mb=4096 -max_len=65536 -print_final_stats=1 \
    -artifact_prefix="$build/crashes/$t/" >"$build/fuzz_$t.log" 2>&1
}
declare -A pid
for t in "${targets[@]}"; do
  while (( $(jobs -rp | wc -l) >= jobs )); do wait -n || true; done
  run "$t" &
  pid[$t]=$!
done
status=0
for t in "${targets[@]}"; do
  log="$build/fuzz_$t.log"
  if wait "${pid[$t]}"; then
    result=ok
  else
    result="FAILED (see $log and $build/crashes/$t/)"
    status=1
  fi
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo ?)
  cov=$(grep -o 'cov: [0-9]* ft: [0-9]*' "$log" | tail -1 || echo "cov: ?")
  echo "fuzz $t: $result, ${seconds} s, $execs executions, $cov, corpus $(ls "$build/corpus/$t" | wc -l) files"
done
echo "fuzz: done in $(( $(date +%s) - start )) s"
exit $status
