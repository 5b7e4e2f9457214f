#!/usr/bin/env bash
# store::* (shell) — issue 34, "Trust": the results store as the command line
# meets it.
#   rerun_once     a config run twice without --resume, and twice more with
#                  --jobs 2 (plain, then --resume): each cell key stored once
#   link_lock      a writer holding the store's lock refuses a second writer
#                  that reaches the same file through a symbolic link
#   verify         an untouched store verifies (exit 0); one flipped bit in a
#                  figure row's text, or one changed digit of a count: verify,
#                  check, table exit 2 naming the cell (scene/viewpoint/WxH/map/label)
#   readonly       a store on a read-only mount: table, check, verify and merge
#                  (as a shard) read it
#   merge_refused  a damaged shard, a folder, /dev/zero, an empty file: exit 2
#                  naming it, nothing written
#   merge_mixed    shards of two git SHAs: exit 2 naming both; --allow-mixed
#                  merges and keeps both runs' provenance
#   lock_cleanup   no .lock file is left after a run, a --jobs run or a merge
#                  (issue 37); a writer running still refuses a second one;
#                  writers started together: each one done or refused 'in use',
#                  one cell per key, no lock left, the store verifies
set -u
bin=${1:?usage: cli_store.sh path/to/shadowlab CASE}
case_=${2:?case}
tmp=$(mktemp -d)
cleanup() { [ -n "${holder:-}" ] && kill "$holder" 2>/dev/null; mountpoint -q "$tmp/ro" 2>/dev/null && umount "$tmp/ro";
            chattr -i "$tmp/ro" 2>/dev/null; rm -rf "$tmp"; }
trap cleanup EXIT
fail() { echo "FAIL $*"; exit 1; }
cells() { sqlite3 "$1" 'SELECT count(*) FROM cells'; }
keys() { sqlite3 "$1" 'SELECT count(*) FROM (SELECT DISTINCT config_hash, scene, viewpoint, vw, vh, map_size, label FROM cells)'; }

# 2 views x 2 map sizes x 2 labels = 8 cells, seconds to run
cat >"$tmp/tiny.yaml" <<'YAML'
name: tiny
scenes: [{scene: primitives, viewpoints: [side, with]}]
viewports: [{width: 64, height: 64}]
map_sizes: [64, 128]
methods:
  - {label: nsm, method: nsm}
  - {label: csm, method: csm}
outputs: {overlays: false}
YAML
run() { "$bin" run "$tmp/tiny.yaml" -q "$@" >"$tmp/run.out" 2>&1 || { cat "$tmp/run.out"; fail "run $*"; }; }

# Flip bit 0 of the second byte of the last `text` in file: "wrong_image" is
# a percent_of value and, once, in the schema's text, which comes first; the
# last one is a figure row's value inside a page (SQLite's page checks do not
# see it). The callers check that exactly one row changed.
flip() {
  python3 - "$1" "$2" <<'PY' || fail "flip"
import sys
p, text = sys.argv[1], sys.argv[2].encode()
b = bytearray(open(p, 'rb').read())
i = b.rfind(text)
if i < 0:
    sys.exit("no %r in %s" % (text, p))
b[i + 1] ^= 1
open(p, 'wb').write(b)
PY
}

case $case_ in
rerun_once)
  run -o "$tmp/r"
  run -o "$tmp/r"
  [ "$(cells "$tmp/r/shadowlab.db")" -eq 8 ] || fail "two plain runs: $(cells "$tmp/r/shadowlab.db") cells, want 8 (one per key)"
  run -o "$tmp/j" --jobs 2
  run -o "$tmp/j" --jobs 2 --resume
  n=$(cells "$tmp/j/shadowlab.db") k=$(keys "$tmp/j/shadowlab.db")
  [ "$n" -eq 8 ] && [ "$k" -eq 8 ] || fail "--jobs 2 then --jobs 2 --resume: $n cells for $k keys, want 8 for 8"
  run -o "$tmp/j" --jobs 2
  [ "$(cells "$tmp/j/shadowlab.db")" -eq 8 ] || fail "--jobs 2 again: $(cells "$tmp/j/shadowlab.db") cells, want 8"
  "$bin" verify "$tmp/j/shadowlab.db" >/dev/null || fail "the store after --jobs does not verify"
  ;;
link_lock)
  mkdir -p "$tmp/r" "$tmp/elsewhere"
  run -o "$tmp/r"
  ln -s "$tmp/r/shadowlab.db" "$tmp/elsewhere/alias.db"
  ( exec 9>>"$tmp/r/shadowlab.db.lock"; flock 9; exec sleep 30 ) &   # a writer holds the store
  holder=$!
  sleep 0.5
  timeout 60 "$bin" run "$tmp/tiny.yaml" -o "$tmp/r2" --db "$tmp/elsewhere/alias.db" --resume >"$tmp/o" 2>"$tmp/e"; rc=$?
  [ $rc -eq 2 ] && grep -q "in use by another run" "$tmp/e" || fail "a writer through a link: exit $rc, want 2 'in use': $(cat "$tmp/e")"
  kill $holder; wait $holder 2>/dev/null; holder=
  [ "$(cells "$tmp/r/shadowlab.db")" -eq 8 ] || fail "cells after the refused writer: $(cells "$tmp/r/shadowlab.db")"
  ;;
verify)
  run -o "$tmp/r"
  db=$tmp/r/shadowlab.db
  "$bin" verify "$db" >"$tmp/v.out" 2>&1; rc=$?
  [ $rc -eq 0 ] || { cat "$tmp/v.out"; fail "an untouched store: exit $rc"; }
  grep -q ": 8 cell(s), .* 0 damaged" "$tmp/v.out" || { cat "$tmp/v.out"; fail "verify summary"; }
  "$bin" check "$db" --baseline "$tmp/b.yaml" --update 2>/dev/null || fail "baseline --update"
  # one bit of one figure row's percent_of ("wrong_image" -> "wrong_imagd"), in the file itself
  sqlite3 "$db" 'PRAGMA wal_checkpoint(TRUNCATE)' >/dev/null
  cp "$db" "$tmp/flip.db"
  flip "$tmp/flip.db" "wrong_image"
  [ "$(sqlite3 "$tmp/flip.db" "SELECT count(*) FROM figures WHERE percent_of = 'wsong_image'")" -eq 1 ] ||
    fail "the flip did not change one figure row"
  [ "$(sqlite3 "$tmp/flip.db" 'PRAGMA quick_check')" = ok ] || fail "the flip is not silent to SQLite (the case is moot)"
  # one digit of one count, through SQL
  cp "$db" "$tmp/digit.db"
  sqlite3 "$tmp/digit.db" "UPDATE figures SET count = count + 1 WHERE rowid = (SELECT min(f.rowid) FROM figures f
    JOIN cells c USING (cell_id) WHERE c.viewpoint = 'with' AND c.map_size = 128 AND c.label = 'csm' AND f.figure = 'wrong')"
  for f in flip digit; do
    "$bin" verify "$tmp/$f.db" >"$tmp/o" 2>"$tmp/e"; rc=$?
    [ $rc -eq 2 ] || fail "$f: verify exit $rc, want 2: $(cat "$tmp/e")"
    [ "$(grep -c 'damaged cell' "$tmp/e")" -eq 1 ] || fail "$f: want one damaged cell named: $(cat "$tmp/e")"
    grep -q "1 damaged" "$tmp/o" || fail "$f: verify summary: $(cat "$tmp/o")"
    "$bin" check "$tmp/$f.db" --baseline "$tmp/b.yaml" >"$tmp/o" 2>"$tmp/ce"; rc=$?
    [ $rc -eq 2 ] || fail "$f: check exit $rc on a damaged store, want 2: $(cat "$tmp/ce")"
    "$bin" table "$tmp/$f.db" >"$tmp/o" 2>"$tmp/te"; rc=$?
    [ $rc -eq 2 ] || fail "$f: table exit $rc on a damaged store, want 2"
    for out in e ce te; do grep -q "$tmp/$f.db" "$tmp/$out" || fail "$f: $out does not name the store: $(cat "$tmp/$out")"; done
  done
  grep -q "damaged cell primitives/with/64x64/128/csm" "$tmp/e" || fail "digit: the cell is not named: $(cat "$tmp/e")"
  grep -q "primitives/with/64x64/128/csm.*damaged" "$tmp/ce" || fail "digit: check does not name the cell: $(cat "$tmp/ce")"
  ;;
readonly)
  run -o "$tmp/r"
  sqlite3 "$tmp/r/shadowlab.db" 'PRAGMA wal_checkpoint(TRUNCATE)' >/dev/null
  "$bin" check "$tmp/r/shadowlab.db" --baseline "$tmp/b.yaml" --update 2>/dev/null || fail "baseline --update"
  mkdir -p "$tmp/ro"
  # a read-only mount (root in CI): a tmpfs remounted ro; else an immutable
  # folder (chattr +i: no -shm or -journal can be made in it, root or not)
  how=
  if mount -t tmpfs -o size=16m none "$tmp/ro" 2>/dev/null; then
    cp "$tmp/r/shadowlab.db" "$tmp/ro/" && mount -o remount,ro "$tmp/ro" 2>/dev/null && how="read-only tmpfs mount"
  fi
  if [ -z "$how" ]; then
    mountpoint -q "$tmp/ro" && umount "$tmp/ro"
    cp "$tmp/r/shadowlab.db" "$tmp/ro/" && chattr +i "$tmp/ro" 2>/dev/null && how="immutable folder (chattr +i)"
  fi
  [ -n "$how" ] || { echo "SKIP: neither a read-only mount nor chattr +i available"; exit 77; }
  touch "$tmp/ro/probe" 2>/dev/null && fail "$how: still writable"
  ro=$tmp/ro/shadowlab.db
  "$bin" table "$ro" >"$tmp/o" 2>"$tmp/e" || fail "table on a $how: $(cat "$tmp/e")"
  "$bin" check "$ro" --baseline "$tmp/b.yaml" >"$tmp/o" 2>"$tmp/e" || fail "check on a $how: $(cat "$tmp/e") $(cat "$tmp/o")"
  "$bin" verify "$ro" >"$tmp/o" 2>"$tmp/e" || fail "verify on a $how: $(cat "$tmp/e")"
  "$bin" merge "$ro" -o "$tmp/m/shadowlab.db" >"$tmp/o" 2>"$tmp/e" || fail "merge of a shard on a $how: $(cat "$tmp/e")"
  [ "$(cells "$tmp/m/shadowlab.db")" -eq 8 ] || fail "merged from a $how: $(cells "$tmp/m/shadowlab.db") cells"
  echo "read through a $how"
  ;;
merge_refused)
  run -o "$tmp/a" --cells 0:4
  run -o "$tmp/b" --cells 4:
  sqlite3 "$tmp/b/shadowlab.db" 'PRAGMA wal_checkpoint(TRUNCATE)' >/dev/null
  cp "$tmp/b/shadowlab.db" "$tmp/damaged.db"
  flip "$tmp/damaged.db" "wrong_image"
  [ "$(sqlite3 "$tmp/damaged.db" "SELECT count(*) FROM figures WHERE percent_of = 'wsong_image'")" -eq 1 ] ||
    fail "the flip did not change one figure row"
  mkdir "$tmp/folder.db"
  : >"$tmp/empty.db"
  for bad in "$tmp/damaged.db" "$tmp/folder.db" /dev/zero "$tmp/empty.db"; do
    rm -rf "$tmp/m"
    timeout 60 "$bin" merge "$tmp/a/shadowlab.db" "$bad" -o "$tmp/m/shadowlab.db" >"$tmp/o" 2>"$tmp/e"; rc=$?
    [ $rc -eq 2 ] || fail "shard $bad: exit $rc, want 2: $(cat "$tmp/e")"
    grep -q "$bad" "$tmp/e" || fail "shard $bad is not named: $(cat "$tmp/e")"
    grep -qi "readonly\|not there" "$tmp/e" && fail "shard $bad: $(cat "$tmp/e")"
    [ -e "$tmp/m/shadowlab.db" ] && fail "shard $bad: the refused merge wrote the store"
    echo "refused: $(head -1 "$tmp/e")"
  done
  grep -q "damaged" <(timeout 60 "$bin" merge "$tmp/damaged.db" -o "$tmp/m/x.db" 2>&1) || fail "a damaged shard is not called damaged"
  ;;
merge_mixed)
  run -o "$tmp/a" --cells 0:4
  run -o "$tmp/b" --cells 4:
  sqlite3 "$tmp/b/shadowlab.db" "UPDATE runs SET git_sha = 'feedbee'"
  "$bin" merge "$tmp/a/shadowlab.db" "$tmp/b/shadowlab.db" -o "$tmp/m/shadowlab.db" >"$tmp/o" 2>"$tmp/e"; rc=$?
  [ $rc -eq 2 ] || fail "shards of two git SHAs: exit $rc, want 2: $(cat "$tmp/e")"
  grep -q "$tmp/b/shadowlab.db.*feedbee.*--allow-mixed" "$tmp/e" || fail "the message: $(cat "$tmp/e")"
  [ -e "$tmp/m/shadowlab.db" ] && fail "the refused merge wrote the store"
  "$bin" merge "$tmp/a/shadowlab.db" "$tmp/b/shadowlab.db" -o "$tmp/m/shadowlab.db" --allow-mixed >"$tmp/o" 2>"$tmp/e" ||
    fail "--allow-mixed: $(cat "$tmp/e")"
  [ "$(sqlite3 "$tmp/m/shadowlab.db" 'SELECT count(DISTINCT git_sha) FROM runs')" -eq 2 ] || fail "the merged runs lost a provenance"
  "$bin" verify "$tmp/m/shadowlab.db" >/dev/null || fail "the merged store does not verify"
  ;;
lock_cleanup)
  nolock() { local l; l=$(find "$tmp" -name '*.lock' | head -n 3); [ -z "$l" ] || fail "$1 left $l"; }
  run -o "$tmp/r"
  nolock "a run"
  run -o "$tmp/j" --jobs 2
  nolock "run --jobs 2"
  "$bin" merge "$tmp/r/shadowlab.db" -o "$tmp/m/shadowlab.db" >/dev/null 2>&1 || fail "merge"
  nolock "a merge"
  # a writer at work (the lock held) refuses a second; then neither leaves a lock
  sed 's/viewports: .*/viewports: [{width: 256, height: 256}]/' "$tmp/tiny.yaml" >"$tmp/slow.yaml"
  "$bin" run "$tmp/slow.yaml" -q -o "$tmp/w" --no-cache >"$tmp/a.out" 2>&1 &
  a=$!
  for _ in $(seq 200); do [ -e "$tmp/w/shadowlab.db.lock" ] && break; sleep 0.05; done
  [ -e "$tmp/w/shadowlab.db.lock" ] || fail "no lock while the first writer runs"
  "$bin" run "$tmp/tiny.yaml" -q -o "$tmp/w" >"$tmp/b.out" 2>&1; rc=$?
  wait $a || { cat "$tmp/a.out"; fail "the first writer"; }
  [ $rc -eq 2 ] && grep -q "in use by another run" "$tmp/b.out" || fail "a second writer while one runs: exit $rc: $(cat "$tmp/b.out")"
  nolock "two writers, one refused"
  # writers started together, each done (0) or refused (2, 'in use'), three times over
  for round in 1 2 3; do
    pids=()
    for i in 1 2 3 4; do
      "$bin" run "$tmp/tiny.yaml" -q -o "$tmp/c" --no-cache >"$tmp/c$i.out" 2>&1 & pids+=($!)
    done
    done_=0
    for i in 1 2 3 4; do
      wait "${pids[$((i - 1))]}"; rc=$?
      if [ $rc -eq 0 ]; then done_=$((done_ + 1))
      elif [ $rc -ne 2 ] || ! grep -q "in use by another run" "$tmp/c$i.out"; then
        cat "$tmp/c$i.out"; fail "round $round, writer $i: exit $rc"
      fi
    done
    [ $done_ -ge 1 ] || fail "round $round: no writer got the store"
    nolock "round $round of writers started together"
  done
  n=$(cells "$tmp/c/shadowlab.db") k=$(keys "$tmp/c/shadowlab.db")
  [ "$n" -eq 8 ] && [ "$k" -eq 8 ] || fail "writers started together: $n cells for $k keys, want 8 for 8"
  "$bin" verify "$tmp/c/shadowlab.db" >/dev/null || fail "the store after writers started together does not verify"
  ;;
*) echo "unknown case $case_"; exit 2 ;;
esac
echo "1 passed, 0 failed"
