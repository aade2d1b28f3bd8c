#!/bin/sh
# Writes the expected outputs of cases.txt with the given strand binary (review the diff).
# Usage: tests/postprocess/inspect/check_stream/regenerate.sh build/cli/strand
set -e
strand=$(realpath "$1")
cd "$(dirname "$0")"
err=$(mktemp)
trap 'rm -f "$err"' EXIT
grep -v '^#' cases.txt | while read -r name input flags; do
  for mode in out json; do
    extra=""; [ "$mode" = json ] && extra="--json"
    set +e
    # shellcheck disable=SC2086
    "$strand" check "$input" $flags $extra >"$name.$mode" 2>"$err"
    code=$?
    set -e
    { echo "--- exit $code"; cat "$err"; } >>"$name.$mode"
  done
done
