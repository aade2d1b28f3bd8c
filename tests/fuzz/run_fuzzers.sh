#!/usr/bin/env bash
# Runs every libFuzzer target of a STRAND_FUZZ build for SECONDS each: first on the
# regression inputs (each must pass), then fuzzing from a corpus seeded with samples/ and the
# regressions. Prints executions per target; exits non-zero on the first crash, hang or leak.
# Usage: tests/fuzz/run_fuzzers.sh BUILD_DIR SECONDS
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
for target in svg_fuzz gcode_fuzz json_fuzz where_fuzz curved_fuzz mesh_fuzz image_fuzz send_fuzz serve_fuzz; do
  exe="$build/tests/fuzz/$target"
  regressions="$src/tests/fuzz/regressions/$target"
  corpus="$build/fuzz-corpus/$target"
  repeat=()
  if [[ -n "${FUZZ_SEED:-}" ]]; then  # a repeatable run: fixed seed, fresh corpus, run count
    corpus="$build/fuzz-corpus-seeded/$target"
    rm -rf "$corpus"
    repeat=(-seed="$FUZZ_SEED" -runs="${FUZZ_RUNS:-20000}")
  fi
  mkdir -p "$corpus"
  for f in $(seeds "$target"); do cp -f "$f" "$corpus/"; done
  if compgen -G "$regressions/*" >/dev/null; then
    "$exe" -rss_limit_mb=2048 -timeout=$HANG_SECONDS "$regressions"/* >/dev/null 2>"$build/$target.regressions.log" ||
      { cat "$build/$target.regressions.log"; echo "$target: a regression input fails"; exit 1; }
  fi
  log="$build/$target.log"
  dict=()
  if [[ -f "$src/tests/fuzz/$target.dict" ]]; then dict=(-dict="$src/tests/fuzz/$target.dict"); fi
  inputs=("$corpus")
  if [[ -d "$regressions" ]]; then inputs+=("$regressions"); fi  # a new target may have none yet
  if ! "$exe" "${inputs[@]}" "${dict[@]}" "${repeat[@]}" -max_total_time="$seconds" -timeout=$HANG_SECONDS -rss_limit_mb=2048 \
       -max_len=65536 -print_final_stats=1 -artifact_prefix="$build/$target-" >"$log" 2>&1; then
    tail -n 60 "$log"
    echo "$target: FAILED (artifact in $build/$target-*)"
    exit 1
  fi
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  echo "$target: ${execs} executions (at most ${seconds} s), no crash"
done
