#!/usr/bin/env bash
# A run on several processes that fails ends every process with the message,
# a non-zero exit status and no output file: bad input (seen by every
# process), a failure on one process only (the first process cannot write),
# and --edges (written by a single process only).
# usage: failure.sh ATTENUVIS MPIEXEC WORKDIR
set -uo pipefail
attenuvis=$1 mpiexec=$2 dir=$3
rm -rf "$dir" && mkdir -p "$dir" && cd "$dir" || exit 2
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
failed=0

# expect_failure NAME MESSAGE ARGS...: non-zero exit, MESSAGE on stderr, no scores.csv.
expect_failure() {
  local name=$1 message=$2
  shift 2
  rm -f scores.csv
  timeout 120 "$mpiexec" --oversubscribe -np 3 "$attenuvis" vg "$@" --quiet --out scores.csv 2>"$name.err"
  local status=$?
  if [ "$status" -eq 0 ] || [ "$status" -eq 124 ]; then
    echo "$name: exit status $status, expected a failure" >&2
    failed=1
  fi
  if ! grep -qF -- "$message" "$name.err"; then
    echo "$name: stderr lacks '$message':" >&2
    cat "$name.err" >&2
    failed=1
  fi
  if [ -e scores.csv ] || compgen -G "*.tmp*" >/dev/null || compgen -G ".*tmp*" >/dev/null; then
    echo "$name: an output file was left behind:" >&2
    ls -a >&2
    failed=1
  fi
}

printf 'x,y,z\n1,2,1.7\n4,5\n' >bad_nodes.csv
expect_failure bad_input "bad_nodes.csv:3" layout:2 --nodes bad_nodes.csv --conditions clear
expect_failure first_process_cannot_write "missing_dir/scores.ply" layout:2 --conditions clear \
  --ply missing_dir/scores.ply
expect_failure edges "--edges is written by a single process" layout:2 --conditions clear --edges edges.csv
exit $failed
