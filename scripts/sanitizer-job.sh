#!/usr/bin/env bash
# The sanitizer job of CI (.ci/run runs it after the README's test command): a clang build with
# AddressSanitizer (LeakSanitizer on) and UndefinedBehaviorSanitizer, every report fatal, in its
# own build folder; then the core unit tests, the filter tests, the command-line tests and the
# fuzzers' corpora under it (ctest labels unit, filter, cli, fuzz), and each fuzzer for a fixed
# short time. ParaView GUI, pvpython, install-tree and shared-data tests are left out: they run
# Debian's uninstrumented ParaView and Python, which ASan cannot run under.
#
# Environment: CBC3D_SANITIZE_BUILD (build folder, default build-sanitize), CBC3D_FUZZ_SECONDS
# (per fuzzer, default 60), CBC3D_FUZZ_SEED (libFuzzer's -seed, default 1: CI runs the same
# mutations every time, so a failure is repeatable).
set -euo pipefail
cd "$(dirname "$0")/.."
source_dir=$PWD
build=${CBC3D_SANITIZE_BUILD:-build-sanitize}
fuzz_seconds=${CBC3D_FUZZ_SECONDS:-60}
fuzz_seed=${CBC3D_FUZZ_SEED:-1}

suppressions="$source_dir/Testing/Fuzz/sanitizer-suppressions.txt"
export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$suppressions:print_suppressions=0"

job_start=$SECONDS
part_start=$SECONDS
timings=()
part_done() {
  timings+=("$(printf '%-34s %5d s' "$1" $((SECONDS - part_start)))")
  part_start=$SECONDS
}

echo "sanitizer job: configure and build ($build)"
cmake -S . -B "$build" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCBC3D_SANITIZE=ON -DCBC3D_FUZZERS=ON >/dev/null
# Only what the job runs: neither the ParaView plugin nor the benchmarks.
cmake --build "$build" -j2 --target CBC3DCoreUnitTests CBC3DFiltersCxxTests cbc3d \
  CBC3DFuzzPipeline CBC3DFuzzNIfTIReader
part_done "build (clang, ASan + UBSan)"

echo "sanitizer job: unit, filter, command-line tests and fuzz corpora"
# Two command-line tests set process limits that a sanitized build cannot meet, so they run in
# the README's (gcc) test command only: an address-space limit (TestCliOutOfMemory) leaves no
# room for ASan's shadow memory, and a file-size limit of a byte (TestCliWriteFaults) stops
# clang's OpenMP runtime, which registers itself in a shared-memory file before main.
ctest --test-dir "$build" -j2 --output-on-failure -L '^(unit|filter|cli|fuzz)$' -LE '^data$' \
  -E '^(TestCliOutOfMemory|TestCliWriteFaults)$'
part_done "ctest unit|filter|cli|fuzz"

# Each fuzzer mutates a scratch copy of its committed corpus (its first folder, where new
# inputs go), so the committed seeds never change; a crash lands in $build/fuzz-artifacts.
run_fuzzer() {
  local name=$1 corpus=$2 runs=$3
  local scratch="$build/fuzz-corpus/$corpus" artifacts="$build/fuzz-artifacts"
  rm -rf "$scratch"
  mkdir -p "$scratch" "$artifacts"
  echo "sanitizer job: fuzzing $name for $fuzz_seconds s"
  # -timeout=300: only a hang fails the job. Noisy label images can keep the pipeline's
  # manifold repair busy for over 20 s under ASan on a loaded machine (a known slow spot).
  # A fixed seed, a clean scratch folder and at most `runs` inputs keep CI's run short and
  # close to the last one here (libFuzzer's timing still varies it); longer runs by hand
  # explore more.
  "$build/bin/$name" -max_total_time="$fuzz_seconds" -runs="$runs" -timeout=300 -rss_limit_mb=2048 \
    -seed="$fuzz_seed" -print_final_stats=1 -artifact_prefix="$artifacts/$corpus-" \
    "$scratch" "$source_dir/Testing/Fuzz/corpus/$corpus" 2>"$build/fuzz-$corpus.log" || {
    tail -n 60 "$build/fuzz-$corpus.log"
    echo "sanitizer job: $name failed; the input is in $artifacts" >&2
    return 1
  }
  echo "  $(grep -m1 'stat::number_of_executed_units' "$build/fuzz-$corpus.log")"
  part_done "fuzz $name"
}
run_fuzzer CBC3DFuzzPipeline pipeline 100
run_fuzzer CBC3DFuzzNIfTIReader nifti 10000

echo "sanitizer job: passed in $((SECONDS - job_start)) s"
printf '  %s\n' "${timings[@]}"
