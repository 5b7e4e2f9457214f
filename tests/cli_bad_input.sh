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
  # a hang fails the case instead of blocking the suite (a model reader that
  # loops is stopped by shadowlab itself after a few seconds)
  timeout 60 "$@" >"$tmp/out" 2>"$tmp/err"
  local rc=$? lines
  lines=$(wc -l <"$tmp/err")
  if [ "$rc" -ne "$want" ]; then
    echo "FAIL $name: exit $rc, want $want"; cat "$tmp/err"; fail=$((fail + 1)); return
  fi
  if [ "$want" -ge 2 ] && ! { [ "$lines" -ge 1 ] && grep -Eq -- "$pat" <(head -n 1 "$tmp/err"); }; then
    echo "FAIL $name: first stderr line does not match /$pat/:"; cat "$tmp/err"; fail=$((fail + 1)); return
  fi
  if [ -d "$tmp/results" ] && [ -n "$(ls -A "$tmp/results")" ]; then
    echo "FAIL $name: wrote into results/:"; ls -la "$tmp/results"; fail=$((fail + 1)); return
  fi
  echo "ok   $name: $(head -n 1 "$tmp/err")"
  pass=$((pass + 1))
}

# every bad input in the corpus: its expected first line, exit 2, nothing written
listed=$(grep -v '^#' tests/bad/expect.tsv | cut -f1 | sort)
present=$(find tests/bad -name '*.yaml' | sort)
if [ "$listed" != "$present" ]; then
  echo "FAIL corpus: tests/bad/expect.tsv and the files under tests/bad/ differ:"
  diff <(echo "$listed") <(echo "$present")
  fail=$((fail + 1))
fi
while IFS=$'\t' read -r f pat; do
  case $f in '#'*|'') continue ;; esac
  check "validate $f" 2 "^shadowlab: $pat" -- "$bin" validate "$f"
  case $f in
    tests/bad/scenes/*) ;;
    *) check "run $f" 2 "^shadowlab: $pat" -- "$bin" run "$f" --out "$tmp/results" ;;
  esac
done < tests/bad/expect.tsv
# huge files are refused before they are read (made here, not committed):
# a config over 4 MiB and a scene file over 16 MiB, both padded with comments
{ printf 'scenes: [{scene: primitives}]\nmap_sizes: [1024]\nmethods: [{method: nsm}]\n'
  head -c $((4 * 1024 * 1024)) /dev/zero | tr '\0' '#'; } >"$tmp/huge.yaml"
check "config over 4 MiB" 2 "^shadowlab: $tmp/huge\.yaml: file of 4194[0-9]+ bytes: at most 4 MiB" -- \
  "$bin" validate "$tmp/huge.yaml"
{ cat tests/bad/scenes/degenerate_depth.yaml; head -c $((16 * 1024 * 1024)) /dev/zero | tr '\0' '#'; } \
  >"$tmp/huge_scene.yaml"
check "scene over 16 MiB" 2 "^shadowlab: $tmp/huge_scene\.yaml: file of 16777[0-9]+ bytes: at most 16 MiB" -- \
  "$bin" validate "$tmp/huge_scene.yaml"
check "missing config" 2 "no_such\.yaml: cannot read: No such file" -- "$bin" run tests/bad/no_such.yaml --out "$tmp/results"
check "unknown command" 2 "unknown command" -- "$bin" frobnicate
check "run without config" 2 "missing CONFIG" -- "$bin" run
check "list nonsense" 2 "list: methods, scenes or techniques" -- "$bin" list trees
check "a folder as config" 2 "tests/bad.*(cannot read|Is a directory|invalid config)" -- "$bin" validate tests/bad
check "bad --cells" 2 "--cells wants A:B" -- "$bin" run configs/default.yaml --cells 5:2 --out "$tmp/results"
check "--cells beyond the sweep" 2 "outside the sweep of 6 cells" -- "$bin" run configs/default.yaml --cells 10:20 --out "$tmp/results"
check "table of a missing store" 2 "no_such\.db: cannot read the results store" -- "$bin" table "$tmp/no_such.db"
check "table of a non-database" 2 "expect\.tsv" -- "$bin" table tests/bad/expect.tsv
for verb in run validate table bench list; do
  check "$verb --help" 0 "" -- "$bin" "$verb" --help
  grep -q "^usage: shadowlab $verb" "$tmp/out" || { echo "FAIL $verb --help prints no usage"; fail=$((fail + 1)); }
done

# an output directory that cannot be made: under a regular file, and in /proc
touch "$tmp/plainfile"
check "output under a file" 3 "plainfile.*(cannot create directory|not a directory)" -- \
  "$bin" run configs/default.yaml --out "$tmp/plainfile/results"
check "output in /proc" 3 "/proc/shadowlab-results.*cannot create directory" -- \
  "$bin" run configs/default.yaml --out /proc/shadowlab-results

# and the good config validates
check "validate default" 0 "" -- "$bin" validate configs/default.yaml

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
