#!/usr/bin/env bash
# The project speaks of itself only: no reference to a ticket number
# ("issue 17", "issues 9, 17", "issue #36", "#36", "the issue's") or to a
# file outside the repository ("DESIGN.md", "STYLE.md", "../shared/", a
# style guide) in the sources, scripts, configs, experiments, benchmarks,
# tests and docs, nor in what users read: `cnclab schema`, `cnclab
# --help-all` and every subcommand's --help, and the manifests' target
# sources that `--check` prints (configs/studies/). A source is a paper, a
# section, or a measurement in docs/.
# Not flagged: "issues" as a word, "Friedman #1" (the benchmark's name),
# STEP entity ids ("#12 = ..." in .step data), colours ("#444"), and
# citations of other projects' trackers ("GCC bug 105329").
# Usage: self_reference_test.sh SOURCE_DIR CNCLAB
set -uo pipefail
src=$1
cnclab=$2
# ERE, matched case-insensitively.
patterns=(
  '\bissues? *#?[0-9]+'             # issue 17, Issue 22 item 4, issues 9, 17, issue #36
  '(^|[[:space:](])#[0-9]{1,4}([[:space:].,:;)]|$)'  # #36 as a ticket
  "\\bthe issue's\\b"               # the issue's targets
  'DESIGN\.md|STYLE\.md'            # design and style files kept outside the repository
  '\.\./shared\b|/work/shared\b'    # the folder beside the repository
  '\bstyle guide\b'
)
joined=$(IFS='|'; echo "${patterns[*]}")
# Text that looks like a pattern but is not a reference: the benchmark's
# name, and STEP entity lines ("#3=PRODUCT(...,(#2))") inlined in tests.
strip='s/friedman #1//Ig; /^([^:]*:[0-9]+:)?#[0-9]+ *=/d'
status=0
hits=$(cd "$src" && grep -rnIiE "$joined" src scripts configs experiments bench docs tests \
  README.md CONTRIBUTING.md --exclude='*.step' --exclude='*.stp' --exclude='*.igs' \
  --exclude-dir=corpus --exclude=self_reference_test.sh 2>/dev/null |
  sed -E "$strip" | grep -iE "$joined")
if [[ -n $hits ]]; then
  echo "references to tickets or to files outside the repository:"
  echo "$hits"
  status=1
fi
check_output() {  # NAME, then the command
  local name=$1
  shift
  local out
  if ! out=$("$@" 2>&1); then
    echo "FAIL: $name exited non-zero"
    status=1
  fi
  local found
  found=$(printf '%s\n' "$out" | sed -E "$strip" | grep -niE "$joined")
  if [[ -n $found ]]; then
    echo "in the output of $name:"
    echo "$found"
    status=1
  fi
}
check_output "cnclab schema" "$cnclab" schema
check_output "cnclab --help-all" "$cnclab" --help-all
# Every subcommand (and sub-subcommand) by itself, as a user asks for it.
n=0
for sub in $("$cnclab" --help | sed -nE 's/^  ([a-z][a-z-]*) .*/\1/p'); do
  check_output "cnclab $sub --help" "$cnclab" "$sub" --help
  n=$((n + 1))
  for nested in $("$cnclab" "$sub" --help | sed -nE '/^Subcommands:/,/^$/s/^  ([a-z][a-z-]*) .*/\1/p'); do
    check_output "cnclab $sub $nested --help" "$cnclab" "$sub" "$nested" --help
    n=$((n + 1))
  done
done
for script in "$src"/scripts/* "$src"/scripts/figures/*; do
  [[ -f $script ]] || continue
  case $script in
    *.py) check_output "${script#"$src"/} --help" /usr/bin/python3 "$script" --help ;;
    *) check_output "${script#"$src"/} --help" "$script" --help ;;
  esac
done
if ((n < 10)); then
  echo "FAIL: only $n subcommands found in cnclab --help (the listing changed?)"
  status=1
fi
((status == 0)) && echo "no ticket or outside-file references (sources, schema, $n command helps, scripts)"
exit $status
