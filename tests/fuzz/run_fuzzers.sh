#!/usr/bin/env bash
# Runs every libFuzzer target of a STRAND_FUZZ build for SECONDS each: first on the
# regression inputs (each must pass), then fuzzing from a corpus seeded with samples/ and the
# regressions. Prints executions per target; exits non-zero on the first crash, hang or leak.
# Usage: tests/fuzz/run_fuzzers.sh BUILD_DIR SECONDS
# FUZZ_SEED=N: a repeatable run (fixed seed, fresh corpus) of FUZZ_RUNS inputs per target, or
# with FUZZ_RUNS=ci the counts of ci_runs below. FUZZ_JOBS targets run at once (default: the
# cores; each is one process).
set -euo pipefail
# An input counts as a hang past HANG_SECONDS: ASan + UBSan run 3-10x slower than the release
# build, and up to 70x on byte-by-byte parsing, so 60 s here is the release build's second (e.g.
# the <use>-doubling regression: 0.5 s release, 5-7 s here on a loaded 2-core machine; an
# O-word loop that never changes its counter, seed 1's unit 18,807 of gcode_fuzz, runs into
# the 1,000,000-line repeat bound in 0.36 s release and 26-41 s here).
HANG_SECONDS=60
build="$1"
seconds="$2"
src="$(cd "$(dirname "$0")/../.." && pwd)"
seeds() {  # target -> seed files
  case "$1" in
    svg_fuzz) ls "$src"/samples/plot/*.svg ;;
    gcode_fuzz) ls "$src"/tests/golden/*.gcode "$src"/tests/fuzz/seeds/gcode_fuzz/* ;;
    json_fuzz) ls "$src"/samples/*.json "$src"/samples/sweeps/*.json "$src"/machines/profiles/*.json ;;
    where_fuzz) ;;
    curved_fuzz) ls "$src"/tests/fuzz/seeds/curved_fuzz/* ;;
    mesh_fuzz) ls "$src"/tests/fuzz/seeds/mesh_fuzz/* ;;
    image_fuzz) ls "$src"/samples/plot/*.png ;;
    send_fuzz) ls "$src"/tests/fuzz/seeds/send_fuzz/* ;;
    serve_fuzz) ls "$src"/tests/fuzz/seeds/serve_fuzz/* ;;
  esac
}
# fuzz-ci's inputs per target: about 30 s each under ASan + UBSan on a 2-core machine
# (executions per second measured there: gcode 45, svg 170, curved 190, mesh 590, the others
# over 1,000), so the nine take about 1.5 min on two cores; `make fuzz` is the long run.
ci_runs() {
  case "$1" in
    gcode_fuzz) echo 1500 ;;
    svg_fuzz | curved_fuzz) echo 5000 ;;
    *) echo 20000 ;;
  esac
}
# One target: its regression inputs (each must pass), then the fuzzing run. Prints one line;
# on a failure the log's tail and the artifact's place, and returns non-zero.
run_target() {
  local target="$1"
  local exe="$build/tests/fuzz/$target"
  local regressions="$src/tests/fuzz/regressions/$target"
  local corpus="$build/fuzz-corpus/$target"
  local repeat=()
  if [[ -n "${FUZZ_SEED:-}" ]]; then  # a repeatable run: fixed seed, fresh corpus, run count
    local runs="${FUZZ_RUNS:-20000}"
    if [[ "$runs" == ci ]]; then runs="$(ci_runs "$target")"; fi
    corpus="$build/fuzz-corpus-seeded/$target"
    rm -rf "$corpus"
    repeat=(-seed="$FUZZ_SEED" -runs="$runs")
  fi
  mkdir -p "$corpus"
  for f in $(seeds "$target"); do cp -f "$f" "$corpus/"; done
  if compgen -G "$regressions/*" >/dev/null; then
    "$exe" -rss_limit_mb=2048 -timeout=$HANG_SECONDS "$regressions"/* >/dev/null 2>"$build/$target.regressions.log" ||
      { cat "$build/$target.regressions.log"; echo "$target: a regression input fails"; return 1; }
  fi
  local log="$build/$target.log"
  local dict=()
  if [[ -f "$src/tests/fuzz/$target.dict" ]]; then dict=(-dict="$src/tests/fuzz/$target.dict"); fi
  local inputs=("$corpus")
  if [[ -d "$regressions" ]]; then inputs+=("$regressions"); fi  # a new target may have none yet
  local start=$SECONDS
  if ! "$exe" "${inputs[@]}" "${dict[@]}" "${repeat[@]}" -max_total_time="$seconds" -timeout=$HANG_SECONDS -rss_limit_mb=2048 \
       -max_len=65536 -print_final_stats=1 -artifact_prefix="$build/$target-" >"$log" 2>&1; then
    tail -n 60 "$log"
    echo "$target: FAILED (artifact in $build/$target-*)"
    return 1
  fi
  local execs
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  echo "$target: ${execs} executions in $((SECONDS - start)) s (at most ${seconds} s), no crash"
}
jobs_at_once="${FUZZ_JOBS:-$(nproc)}"
failed=0
running=0
for target in gcode_fuzz svg_fuzz curved_fuzz mesh_fuzz image_fuzz serve_fuzz json_fuzz send_fuzz where_fuzz; do
  if ((running >= jobs_at_once)); then
    wait -n || failed=1
    running=$((running - 1))
  fi
  if ((failed)); then break; fi
  run_target "$target" &
  running=$((running + 1))
done
while ((running > 0)); do
  wait -n || failed=1
  running=$((running - 1))
done
exit $failed
