#!/usr/bin/env bash
# cli::limits_* — a technique package whose shader runs for minutes
# (tests/techniques/slow: a loop of 50,000 turns of 256 written-out steps
# per pixel, bounded, so llvmpipe's loop limit does not cut it):
#   pass_seconds  `limits: {pass_seconds: 2}` ends the run within a few
#                 seconds, exit 2, naming the package's file and the pass
#                 (the lookup's, then the map's with `pass: 1`); nothing
#                 stored for the cell
#   sigterm       SIGTERM during the lookup pass stops the run within 5 s,
#                 exit 143, the usual --resume message, nothing stored, no
#                 staging folder left
set -u
bin=${1:?usage: cli_limits.sh path/to/shadowlab CASE}
case_=${2:?case}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL $*"; exit 1; }
config() {   # $1 the slow package's pass (0 lookup, 1 map), $2 extra top-level line
  cat >"$tmp/c.yaml" <<YAML
name: slow
techniques: [$PWD/tests/techniques]
scenes: [{scene: primitives, viewpoints: [side]}]
viewports: [{width: 256, height: 256}]
map_sizes: [512]
methods:
  - {label: slow, method: slow, pass: $1}
outputs: {overlays: false}
$2
YAML
}
stored() { sqlite3 "$1/shadowlab.db" "SELECT count(*) FROM cells" 2>/dev/null || echo 0; }

case $case_ in
pass_seconds)
  for pass in 0 1; do
    name=$([ $pass = 0 ] && echo lookup || echo map); file=$([ $pass = 0 ] && echo lookup.glsl || echo map.glsl)
    config $pass "limits: {pass_seconds: 2}"
    t0=$(date +%s.%N)
    "$bin" run "$tmp/c.yaml" --no-cache -o "$tmp/o$pass" >"$tmp/out" 2>"$tmp/err"; rc=$?
    s=$(echo "$(date +%s.%N) - $t0" | bc)
    echo "$name pass: exit $rc after $s s"
    [ $rc -eq 2 ] || { cat "$tmp/err"; fail "$name pass over limits.pass_seconds: exit $rc, want 2"; }
    grep -q "tests/techniques/slow/$file: technique slow: the $name pass ran .* over limits.pass_seconds (2 s)" "$tmp/err" ||
      { cat "$tmp/err"; fail "the message does not name the package's file and the $name pass"; }
    [ "$(echo "$s < 10" | bc)" = 1 ] || fail "the run took $s s under pass_seconds 2"
    [ "$(stored "$tmp/o$pass")" = 0 ] || fail "a cell stored after its $name pass was ended"
    ls -a "$tmp/o$pass" | grep -q partial && fail "staging folder left: $(ls -a "$tmp/o$pass")"
  done
  ;;
sigterm)
  config 0 ""
  "$bin" run "$tmp/c.yaml" --no-cache -o "$tmp/o" >"$tmp/out" 2>"$tmp/err" &
  pid=$!
  sleep 3   # the truth traced, the lookup pass under way
  kill -0 "$pid" 2>/dev/null || { cat "$tmp/err"; fail "the run ended before the signal"; }
  t0=$(date +%s.%N)
  kill -TERM "$pid"
  for _ in $(seq 1 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  s=$(echo "$(date +%s.%N) - $t0" | bc)
  kill -0 "$pid" 2>/dev/null && { kill -KILL "$pid"; fail "still running 10 s after SIGTERM"; }
  wait "$pid"; rc=$?
  echo "stopped $s s after SIGTERM, exit $rc"
  [ "$(echo "$s <= 5" | bc)" = 1 ] || fail "stopped $s s after SIGTERM, want <= 5"
  [ $rc -eq 143 ] || { cat "$tmp/err"; fail "exit $rc, want 143"; }
  grep -q "^shadowlab: interrupted (SIGTERM): 0 of 1 cell(s) of this config are stored in $tmp/o/shadowlab.db; to go on:" "$tmp/err" ||
    { cat "$tmp/err"; fail "no interrupt message"; }
  grep -A1 "to go on:" "$tmp/err" | tail -1 | grep -q -- " --resume$" || fail "no --resume command"
  [ "$(stored "$tmp/o")" = 0 ] || fail "the interrupted cell was stored"
  ls -a "$tmp/o" | grep -q partial && fail "staging folder left: $(ls -a "$tmp/o")"
  ;;
*) fail "unknown case $case_" ;;
esac
echo "1 passed, 0 failed"
