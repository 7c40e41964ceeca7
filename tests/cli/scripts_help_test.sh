#!/usr/bin/env bash
# Every script under scripts/ (and scripts/figures/) answers --help: exit 0,
# a description on stdout, and nothing run or written (`figures/run
# --help` used to create a folder named --help and draw into it).
# Usage: scripts_help_test.sh SOURCE_DIR
set -uo pipefail
src=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
status=0
for script in "$src"/scripts/* "$src"/scripts/figures/*; do
  [[ -f "$script" ]] || continue
  case $script in
    *.py) cmd=(/usr/bin/python3 "$script") ;;
    *)
      # A script without .py runs by itself: not executable, it could not
      # answer --help (and would be skipped unnoticed).
      if [[ ! -x "$script" ]]; then
        echo "FAIL ${script#"$src"/}: not executable"
        status=1
        continue
      fi
      cmd=("$script")
      ;;
  esac
  for flag in --help -h; do
    out=$(cd "$work" && "${cmd[@]}" "$flag" 2>&1)
    rc=$?
    lines=$(printf '%s\n' "$out" | grep -c .)
    if ((rc != 0 || lines < 2)); then
      echo "FAIL ${script#"$src"/} $flag: exit $rc, $lines line(s) of help"
      printf '%s\n' "$out" | head -5
      status=1
    fi
  done
done
for made in "$work"/* "$src/--help" "$src/-h" "$src/scripts/--help" "$src/results/--help"; do
  if [[ -e "$made" ]]; then
    echo "FAIL --help wrote $made"
    status=1
  fi
done
((status == 0)) && echo "every script answers --help"
exit $status
