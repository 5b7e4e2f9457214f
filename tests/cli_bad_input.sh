#!/usr/bin/env bash
# cli::bad_input — every bad input gets one line on stderr naming what and
# where, exit code 2, and nothing written under the output directory.
set -u
bin=${1:?usage: cli_bad_input.sh path/to/shadowlab}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0

check() { # name expected_rc stderr_pattern -- command...
  local name=$1 want=$2 pat=$3; shift 4
  "$@" >"$tmp/out" 2>"$tmp/err"
  local rc=$? lines
  lines=$(wc -l <"$tmp/err")
  if [ "$rc" -ne "$want" ]; then
    echo "FAIL $name: exit $rc, want $want"; cat "$tmp/err"; fail=$((fail + 1)); return
  fi
  if [ "$want" -eq 2 ] && ! { [ "$lines" -ge 1 ] && grep -Eq -- "$pat" <(head -n 1 "$tmp/err"); }; then
    echo "FAIL $name: first stderr line does not match /$pat/:"; cat "$tmp/err"; fail=$((fail + 1)); return
  fi
  if [ -d "$tmp/results" ] && [ -n "$(ls -A "$tmp/results")" ]; then
    echo "FAIL $name: wrote into results/:"; ls -la "$tmp/results"; fail=$((fail + 1)); return
  fi
  echo "ok   $name: $(head -n 1 "$tmp/err")"
  pass=$((pass + 1))
}

# each bad config: file and line named, exit 2, nothing written
for f in tests/bad/*.yaml; do
  case $(basename "$f") in
    syntax.yaml|missing_methods.yaml) pat="^shadowlab: $f:" ;;
    *) pat="^shadowlab: $f:[0-9]+: '" ;;
  esac
  check "run $(basename "$f")" 2 "$pat" -- "$bin" run "$f" --out "$tmp/results"
  check "validate $(basename "$f")" 2 "$pat" -- "$bin" validate "$f"
done
check "missing config" 2 "no_such\.yaml: cannot read: No such file" -- "$bin" run tests/bad/no_such.yaml --out "$tmp/results"
check "unknown command" 2 "unknown command" -- "$bin" frobnicate
check "run without config" 2 "missing CONFIG" -- "$bin" run
check "list nonsense" 2 "list: methods or scenes" -- "$bin" list trees

# an output directory that cannot be made: under a regular file, and in /proc
touch "$tmp/plainfile"
check "output under a file" 2 "plainfile.*(cannot create directory|not a directory)" -- \
  "$bin" run configs/default.yaml --out "$tmp/plainfile/results"
check "output in /proc" 2 "/proc/shadowlab-results.*cannot create directory" -- \
  "$bin" run configs/default.yaml --out /proc/shadowlab-results

# and the good config validates
check "validate default" 0 "" -- "$bin" validate configs/default.yaml

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
