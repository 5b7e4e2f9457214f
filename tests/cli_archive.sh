#!/usr/bin/env bash
# store::* (shell) — issue 49, the store as an archive: what a .db alone
# holds when a run, a merge or a failure ends, and what the readers say.
#   seal           a run leaves no -wal and its .db alone holds every cell;
#                  the final checkpoint failing (SHADOWLAB_FAULT=checkpoint, a
#                  disk that fills at the last step) exits 3 naming the store,
#                  its -wal and what to free, with no "written to"; `run
#                  --resume` then leaves a .db that holds every cell alone
#   wal_readonly   a store and the -wal a failed checkpoint left, on a
#                  read-only mount: verify, table and check read all 8 cells
#                  (through a private copy, removed afterwards); with no
#                  writable TMPDIR, exit 2 saying why
#   merge_killed   a merge into an existing target killed (SIGKILL) at each
#                  of its moments (SHADOWLAB_FAULT=merge:N, 13 of them) and at
#                  the same 13 into a new target: the target is the old store,
#                  intact, or the complete new one (or, new, none), and a
#                  merge afterwards completes it
#   files          each overlay and table a run writes is recorded (path,
#                  size, CRC-32 equal to zlib's over the file); one flipped
#                  byte in an overlay: verify exit 2 naming it, report exit 2
#                  refusing to copy it; the .db alone: not checked unless
#                  --files (then each is missing); --resume recomputes the
#                  damaged and a deleted overlay's cells, after which verify
#                  and report pass; a merge keeps the records
#   complete       half a sweep stored (--cells 0:4): verify (exit 1), table,
#                  check (on stderr, only of an incomplete sweep) and report
#                  each say "4 of 8 cells", verify and the
#                  report name the 4 missing cells; merged with the other
#                  half: 8 of 8, exit 0
#   old_schemas    a store written by the build of each schema since 16
#                  (tests/stores/): verify, table, check and report read it
#                  through an upgraded private copy, the counts as stored,
#                  the file untouched, the copy removed; from 17 on, a count
#                  changed by hand is still a damaged cell; a writer (run
#                  --resume) refuses every older one (23 added the cost
#                  stages to the cells, and a cell's digest covers every
#                  column), the file untouched; merge refuses them as
#                  shards naming the schema
#   doc            verify --help and doc/store.md state the same checks and
#                  exit codes
set -u
bin=${1:?usage: cli_archive.sh path/to/shadowlab CASE}
case_=${2:?case}
tmp=$(mktemp -d)
cleanup() { mountpoint -q "$tmp/ro" 2>/dev/null && umount "$tmp/ro"; rm -rf "$tmp"; }
trap cleanup EXIT
fail() { echo "FAIL $*"; exit 1; }
cells() { sqlite3 "$1" 'SELECT count(*) FROM cells'; }
# the .db alone, as a copy without its -wal would read it
alone_cells() { cp "$1" "$tmp/alone.db" && sqlite3 "$tmp/alone.db" 'SELECT count(*) FROM cells' 2>&1; rm -f "$tmp/alone.db"*; }

# 2 views x 2 map sizes x 2 labels = 8 cells, seconds to run
cat >"$tmp/tiny.yaml" <<'YAML'
name: tiny
scenes: [{scene: primitives, viewpoints: [side, with]}]
viewports: [{width: 64, height: 64}]
map_sizes: [64, 128]
methods:
  - {label: nsm, method: nsm}
  - {label: csm, method: csm}
YAML
run() { "$bin" run "$tmp/tiny.yaml" -q "$@" >"$tmp/run.out" 2>&1 || { cat "$tmp/run.out"; fail "run $*"; }; }

case "$case_" in
seal)
  run --out "$tmp/r"
  [ -e "$tmp/r/shadowlab.db-wal" ] && fail "a run left a -wal of $(stat -c %s "$tmp/r/shadowlab.db-wal") bytes"
  [ "$(alone_cells "$tmp/r/shadowlab.db")" = 8 ] || fail "the .db alone: $(alone_cells "$tmp/r/shadowlab.db")"
  SHADOWLAB_FAULT=checkpoint "$bin" run "$tmp/tiny.yaml" -q --out "$tmp/f" >"$tmp/o" 2>"$tmp/e"; rc=$?
  [ $rc -eq 3 ] || fail "checkpoint failing: exit $rc, want 3: $(cat "$tmp/e")"
  grep -q "written to" "$tmp/o" && fail "checkpoint failing: says 'written to': $(cat "$tmp/o")"
  grep -q "$tmp/f/shadowlab.db: the final checkpoint failed" "$tmp/e" || fail "the store is not named: $(cat "$tmp/e")"
  grep -q "only in $tmp/f/shadowlab.db-wal" "$tmp/e" || fail "the -wal is not named: $(cat "$tmp/e")"
  grep -q "free at least [0-9]* bytes on the filesystem of $tmp/f" "$tmp/e" || fail "what to free: $(cat "$tmp/e")"
  grep -q -- "--resume" "$tmp/e" || fail "no --resume: $(cat "$tmp/e")"
  # what the issue found: the .db alone lacks the cells
  [ -s "$tmp/f/shadowlab.db-wal" ] || fail "the injected failure left no -wal"
  [ "$(alone_cells "$tmp/f/shadowlab.db")" = 8 ] && fail "the injected failure left a whole .db"
  "$bin" run "$tmp/tiny.yaml" -q --out "$tmp/f" --resume >"$tmp/o" 2>"$tmp/e" || fail "--resume: $(cat "$tmp/e")"
  grep -q "written to" "$tmp/o" || fail "--resume: no 'written to'"
  [ -e "$tmp/f/shadowlab.db-wal" ] && fail "--resume left a -wal"
  [ "$(alone_cells "$tmp/f/shadowlab.db")" = 8 ] || fail "after --resume, the .db alone: $(alone_cells "$tmp/f/shadowlab.db")"
  "$bin" verify "$tmp/f/shadowlab.db" >/dev/null 2>"$tmp/e" || fail "verify after --resume: $(cat "$tmp/e")"
  ;;
wal_readonly)
  SHADOWLAB_FAULT=checkpoint "$bin" run "$tmp/tiny.yaml" -q --out "$tmp/f" >/dev/null 2>&1
  [ -s "$tmp/f/shadowlab.db-wal" ] || fail "the injected failure left no -wal"
  "$bin" check "$tmp/f/shadowlab.db" --baseline "$tmp/b.yaml" --update >/dev/null 2>"$tmp/e" || fail "baseline: $(cat "$tmp/e")"
  mkdir -p "$tmp/ro" "$tmp/t"
  mount -t tmpfs -o size=16m none "$tmp/ro" 2>/dev/null || { echo "SKIP: no tmpfs mount here"; exit 77; }
  cp "$tmp/f/shadowlab.db" "$tmp/f/shadowlab.db-wal" "$tmp/ro/" && mount -o remount,ro "$tmp/ro" || fail "remount ro"
  touch "$tmp/ro/probe" 2>/dev/null && fail "the mount is still writable"
  ro=$tmp/ro/shadowlab.db
  TMPDIR=$tmp/t "$bin" verify "$ro" >"$tmp/o" 2>"$tmp/e" || fail "verify: $(cat "$tmp/e")"
  grep -q "8 cell(s)" "$tmp/o" || fail "verify read: $(cat "$tmp/o")"
  TMPDIR=$tmp/t "$bin" table "$ro" --format csv >"$tmp/o" 2>"$tmp/e" || fail "table: $(cat "$tmp/e")"
  [ "$(grep -c '^primitives,' "$tmp/o")" -ge 8 ] || fail "table read $(grep -c '^primitives,' "$tmp/o") cell rows"
  TMPDIR=$tmp/t "$bin" check "$ro" --baseline "$tmp/b.yaml" >"$tmp/o" 2>"$tmp/e" || fail "check: $(cat "$tmp/e")"
  [ -z "$(ls -A "$tmp/t")" ] || fail "the private copy was left: $(ls -A "$tmp/t")"
  TMPDIR=$tmp/none "$bin" verify "$ro" >"$tmp/o" 2>"$tmp/e"; rc=$?
  [ $rc -eq 2 ] || fail "no TMPDIR: exit $rc, want 2"
  grep -q "a -wal of [0-9]* bytes lies beside this store on read-only media" "$tmp/e" || fail "why not: $(cat "$tmp/e")"
  ;;
merge_killed)
  run --out "$tmp/a" --cells 0:3
  run --out "$tmp/b" --cells 3:6
  run --out "$tmp/c" --cells 6:
  shards=("$tmp/a/shadowlab.db" "$tmp/b/shadowlab.db" "$tmp/c/shadowlab.db")
  # an existing target holding shard a's cells, killed at each moment
  # (in a folder of its own: the overlays it gathered lie beside it)
  "$bin" merge "${shards[0]}" -o "$tmp/old/shadowlab.db" >/dev/null 2>&1
  [ "$(cells "$tmp/old/shadowlab.db")" = 3 ] || fail "the old target: $(cells "$tmp/old/shadowlab.db") cells"
  for n in $(seq 1 13); do
    rm -rf "$tmp/m" && cp -r "$tmp/old" "$tmp/m"
    SHADOWLAB_FAULT=merge:$n "$bin" merge "${shards[@]}" -o "$tmp/m/shadowlab.db" >"$tmp/o" 2>"$tmp/e"; rc=$?
    [ $rc -eq 137 ] || fail "moment $n: exit $rc, not killed: $(cat "$tmp/e")"
    got=$(alone_cells "$tmp/m/shadowlab.db")
    { [ "$got" = 3 ] || [ "$got" = 8 ]; } || fail "moment $n: the target holds $got cells (old 3, new 8)"
    "$bin" verify "$tmp/m/shadowlab.db" >/dev/null 2>"$tmp/e"; rc=$?   # 1: the old target's sweep is incomplete
    [ $rc -eq 0 ] || { [ $rc -eq 1 ] && [ "$got" = 3 ]; } || fail "moment $n: verify exit $rc: $(cat "$tmp/e")"
    "$bin" merge "${shards[@]}" -o "$tmp/m/shadowlab.db" >/dev/null 2>"$tmp/e" || fail "moment $n: merge again: $(cat "$tmp/e")"
    [ "$(cells "$tmp/m/shadowlab.db")" = 8 ] || fail "moment $n: merged again: $(cells "$tmp/m/shadowlab.db") cells"
    [ -z "$(ls "$tmp/m" | grep -v '^shadowlab.db$\|^tiny$')" ] || fail "moment $n: left $(ls "$tmp/m")"
    echo "moment $n: target held $got cells"
  done
  # a new target: none, or the whole merge
  for n in $(seq 1 13); do
    rm -rf "$tmp/n"
    SHADOWLAB_FAULT=merge:$n "$bin" merge "${shards[@]}" -o "$tmp/n/shadowlab.db" >"$tmp/o" 2>"$tmp/e"; rc=$?
    [ $rc -eq 137 ] || fail "new, moment $n: exit $rc, not killed: $(cat "$tmp/e")"
    if [ -e "$tmp/n/shadowlab.db" ]; then
      got=$(alone_cells "$tmp/n/shadowlab.db")
      [ "$got" = 8 ] || fail "new, moment $n: a target of $got cells"
    else
      got=none
    fi
    echo "new, moment $n: $got"
  done
  ;;
files)
  run --out "$tmp/r"
  db=$tmp/r/shadowlab.db
  [ "$(sqlite3 "$db" "SELECT count(*) FROM files WHERE cell_id IS NOT NULL AND path LIKE 'tiny/overlays/%.png'")" = 8 ] ||
    fail "overlays recorded: $(sqlite3 "$db" 'SELECT path FROM files')"
  [ "$(sqlite3 "$db" "SELECT count(*) FROM files WHERE cell_id IS NULL AND path = 'tiny/table.md'")" = 1 ] ||
    fail "table.md is not recorded"
  # the recorded CRC-32 and size are the file's (python's zlib: another reader of the same bytes)
  ov=tiny/overlays/primitives-side-64x64-64-csm.png
  want=$(python3 -c "import zlib,sys; b=open(sys.argv[1],'rb').read(); print(len(b), zlib.crc32(b))" "$tmp/r/$ov")
  [ "$(sqlite3 -separator ' ' "$db" "SELECT size, crc32 FROM files WHERE path = '$ov'")" = "$want" ] ||
    fail "recorded $(sqlite3 "$db" "SELECT size, crc32 FROM files WHERE path = '$ov'"), the file is $want"
  "$bin" verify "$db" >"$tmp/o" 2>"$tmp/e" || fail "an untouched store: $(cat "$tmp/e")"
  grep -q "16 recorded file(s) checked: 0 missing or damaged" "$tmp/o" || fail "verify's files: $(cat "$tmp/o")"
  # one flipped byte in the overlay's image data
  python3 -c "import sys; p=sys.argv[1]; b=bytearray(open(p,'rb').read()); b[len(b)//2]^=1; open(p,'wb').write(b)" "$tmp/r/$ov"
  "$bin" verify "$db" >"$tmp/o" 2>"$tmp/e"; rc=$?
  [ $rc -eq 2 ] || fail "a flipped overlay byte: verify exit $rc, want 2"
  grep -q "damaged file $ov: its CRC-32" "$tmp/e" || fail "verify does not name $ov: $(cat "$tmp/e")"
  "$bin" verify "$db" --no-files >/dev/null 2>&1 || fail "--no-files still checks the files"
  # the .db alone: no file beside it, not checked unless --files
  mkdir "$tmp/alone" && cp "$db" "$tmp/alone/"
  "$bin" verify "$tmp/alone/shadowlab.db" >"$tmp/o" 2>"$tmp/e" || fail "the .db alone: $(cat "$tmp/e")"
  grep -q "16 recorded file(s) not checked" "$tmp/o" || fail "the .db alone: $(cat "$tmp/o")"
  "$bin" verify "$tmp/alone/shadowlab.db" --files >"$tmp/o" 2>"$tmp/e"; rc=$?
  [ $rc -eq 2 ] && grep -q "missing file $ov" "$tmp/e" || fail "--files on the .db alone: exit $rc: $(cat "$tmp/e")"
  # report refuses to copy it, naming it
  "$bin" report "$db" -o "$tmp/rep" >"$tmp/o" 2>"$tmp/e"; rc=$?
  [ $rc -eq 2 ] || fail "report of a damaged overlay: exit $rc, want 2"
  grep -q "$ov: damaged overlay of cell primitives/side/64x64/64/csm" "$tmp/e" || fail "report: $(cat "$tmp/e")"
  # a missing one beside it; --resume computes both cells again and writes their files anew
  rm "$tmp/r/tiny/overlays/primitives-with-64x64-128-nsm.png"
  "$bin" run "$tmp/tiny.yaml" --out "$tmp/r" --resume >"$tmp/o" 2>"$tmp/e" || fail "--resume: $(cat "$tmp/e")"
  grep -q "2 cell(s) computed, 6 already stored" "$tmp/o" || fail "--resume recomputed: $(cat "$tmp/o")"
  "$bin" verify "$db" >"$tmp/o" 2>"$tmp/e" || fail "after --resume: $(cat "$tmp/e")"
  "$bin" report "$db" -o "$tmp/rep" >"$tmp/o" 2>"$tmp/e" || fail "report after --resume: $(cat "$tmp/e")"
  # a merge keeps the records, at the gathered paths
  "$bin" merge "$db" -o "$tmp/m/shadowlab.db" >/dev/null 2>"$tmp/e" || fail "merge: $(cat "$tmp/e")"
  "$bin" verify "$tmp/m/shadowlab.db" --files >"$tmp/o" 2>"$tmp/e" || fail "the merged store's files: $(cat "$tmp/e")"
  grep -q "8 recorded file(s) checked: 0 missing" "$tmp/o" || fail "merged: $(cat "$tmp/o")"
  ;;
complete)
  # a sweep split in two, one half stored: all four readers say 4 of 8
  run --out "$tmp/h" --cells 0:4
  db=$tmp/h/shadowlab.db
  [ "$(sqlite3 "$db" 'SELECT count(*) FROM plan')" = 8 ] || fail "the plan: $(sqlite3 "$db" 'SELECT count(*) FROM plan') keys"
  "$bin" check "$db" --baseline "$tmp/b.yaml" --update >/dev/null 2>"$tmp/e" || fail "baseline: $(cat "$tmp/e")"
  line="sweep 'tiny' (config [0-9a-f]*, run 1): 4 of 8 cells, incomplete"
  "$bin" verify "$db" >"$tmp/o" 2>"$tmp/e"; rc=$?
  [ $rc -eq 1 ] || fail "verify of an incomplete sweep: exit $rc, want 1: $(cat "$tmp/e")"
  grep -q "verify: $db: $line" "$tmp/e" || fail "verify: $(cat "$tmp/e")"
  [ "$(grep -c 'verify: .*missing cell' "$tmp/e")" = 4 ] || fail "verify names not 4 missing cells: $(cat "$tmp/e")"
  grep -q "missing cell 7: primitives/with/64x64/128/csm" "$tmp/e" || fail "verify: cell 7 not named"
  "$bin" table "$db" --format csv >"$tmp/o" 2>"$tmp/e" || fail "table: $(cat "$tmp/e")"
  grep -q "table: $db: $line" "$tmp/e" || fail "table: $(cat "$tmp/e")"
  grep -q "incomplete" "$tmp/o" && fail "table put the note into its CSV"
  "$bin" check "$db" --baseline "$tmp/b.yaml" >"$tmp/o" 2>"$tmp/e" || fail "check: $(cat "$tmp/e")"
  grep -q "check: $db: $line" "$tmp/e" || fail "check: $(cat "$tmp/e")"
  "$bin" report "$db" -o "$tmp/rep" >"$tmp/o" 2>"$tmp/e" || fail "report: $(cat "$tmp/e")"
  grep -q "Sweep tiny (config hash [0-9a-f]*, run(s) 1): 4 of 8 cells: INCOMPLETE" "$tmp/rep/report.md" ||
    fail "the report does not say incomplete"
  for k in "primitives | with | 64x64 | 64 | nsm" "primitives | with | 64x64 | 128 | csm"; do
    grep -q "| $k |" "$tmp/rep/report.md" || fail "the report does not list $k"
  done
  # the other half merged in: complete, exit 0
  run --out "$tmp/h2" --cells 4:
  "$bin" merge "$db" "$tmp/h2/shadowlab.db" -o "$tmp/m/shadowlab.db" >/dev/null 2>"$tmp/e" || fail "merge: $(cat "$tmp/e")"
  "$bin" verify "$tmp/m/shadowlab.db" >"$tmp/o" 2>"$tmp/e" || fail "verify of the whole: $(cat "$tmp/e")"
  grep -q "8 of 8 cells$" "$tmp/e" || fail "the merged sweep: $(cat "$tmp/e")"
  "$bin" table "$tmp/m/shadowlab.db" --format csv >/dev/null 2>"$tmp/e" || fail "table of the whole"
  [ -s "$tmp/e" ] && fail "table of a whole sweep says: $(cat "$tmp/e")"
  ;;
old_schemas)
  # tests/stores/vNN.db: 2 cells (primitives/side, 32x32, map 64, nsm and
  # csm) written by the build of each schema version (tests/stores/README.md
  # names the commits); v16 ran twice (4 rows, 2 keys: before 17's UNIQUE)
  dir=$(dirname "$0")/stores
  mkdir "$tmp/priv" && export TMPDIR=$tmp/priv   # where the private copies go
  n=0
  for src in "$dir"/v*.db; do
    v=$(basename "$src" .db); v=${v#v}
    cp "$src" "$tmp/s.db" && sum=$(sha256sum <"$tmp/s.db")
    [ "$(sqlite3 "$tmp/s.db" 'PRAGMA user_version')" = "$v" ] || fail "$src is not of schema $v"
    "$bin" verify "$tmp/s.db" >"$tmp/o" 2>"$tmp/e" || fail "v$v: verify: $(cat "$tmp/e")"
    # the figure rows of the later cell of each key, as the old file holds them
    figs=$(sqlite3 "$tmp/s.db" "SELECT count(*) FROM figures WHERE cell_id IN (SELECT max(cell_id) FROM cells
                                GROUP BY config_hash, scene, viewpoint, vw, vh, map_size, label)")
    grep -q "2 cell(s), $figs figure row(s) checked .*: 0 damaged" "$tmp/o" || fail "v$v: verify read ($figs rows): $(cat "$tmp/o")"
    grep -q "a store of schema $v, read through a private copy upgraded" "$tmp/o" || fail "v$v: $(cat "$tmp/o")"
    "$bin" table "$tmp/s.db" --format csv >"$tmp/o" 2>"$tmp/e" || fail "v$v: table: $(cat "$tmp/e")"
    [ "$(cut -d, -f6 "$tmp/o" | sort -u | tr '\n' ' ')" = "csm label nsm " ] || fail "v$v: table's labels: $(cut -d, -f6 "$tmp/o" | sort -u)"
    grep -q "^primitives,side,32x32,64,nsm,nsm,image,wrong," "$tmp/o" || fail "v$v: no wrong row of nsm"
    "$bin" check "$tmp/s.db" --baseline "$tmp/b$v.yaml" --update >/dev/null 2>"$tmp/e" || fail "v$v: check --update: $(cat "$tmp/e")"
    "$bin" check "$tmp/s.db" --baseline "$tmp/b$v.yaml" >"$tmp/o" 2>"$tmp/e" || fail "v$v: check: $(cat "$tmp/e")"
    "$bin" report "$tmp/s.db" -o "$tmp/rep$v" >"$tmp/o" 2>"$tmp/e" || fail "v$v: report: $(cat "$tmp/e")"
    grep -q "its plan is not recorded" "$tmp/rep$v/report.md" || fail "v$v: the report's completeness"
    [ "$(sha256sum <"$tmp/s.db")" = "$sum" ] || fail "v$v: a reader changed the store"
    [ -z "$(ls -A "$tmp/priv")" ] || fail "v$v: the private copy was left: $(ls -A "$tmp/priv")"
    # the nsm cell's wrong pixels, as the build of that schema stored them
    want=$(sqlite3 "$tmp/s.db" "SELECT count FROM figures f JOIN cells c USING (cell_id) WHERE c.label = 'nsm' AND
           f.region = 'image' AND f.figure = 'wrong' ORDER BY c.run_id DESC, c.cell_id DESC LIMIT 1")
    # (the whole output to a file: a reader killed by SIGPIPE leaves its copy)
    "$bin" table "$tmp/s.db" --format csv >"$tmp/o" 2>/dev/null
    grep -q "^primitives,side,32x32,64,nsm,nsm,image,wrong,$want," "$tmp/o" || fail "v$v: nsm's wrong count is not the stored $want"
    # a writer refuses every older store, the file untouched
    cat >"$tmp/tiny2.yaml" <<'YAML'
name: tiny
scenes: [{scene: primitives, viewpoints: [side]}]
viewports: [{width: 32, height: 32}]
map_sizes: [64]
methods:
  - {label: nsm, method: nsm}
  - {label: csm, method: csm}
outputs: {overlays: false}
YAML
    rm -rf "$tmp/w" && mkdir "$tmp/w" && cp "$src" "$tmp/w/shadowlab.db"
    "$bin" run "$tmp/tiny2.yaml" -q --out "$tmp/w" --resume >"$tmp/o" 2>"$tmp/e"; rc=$?
    [ $rc -eq 2 ] && grep -q "results store of schema version $v; this build writes version 23" "$tmp/e" ||
      fail "v$v: a writer: exit $rc: $(cat "$tmp/e")"
    cmp -s "$src" "$tmp/w/shadowlab.db" || fail "v$v: the refused writer changed the store"
    # merge takes shards of 23 only, saying so of older ones
    rm -rf "$tmp/mg"
    "$bin" merge "$src" -o "$tmp/mg/shadowlab.db" >"$tmp/o" 2>"$tmp/e"; rc=$?
    [ $rc -eq 2 ] && grep -q "$src: a results store of schema $v: merge takes shards of schema 23" "$tmp/e" ||
      fail "v$v as a shard: exit $rc: $(cat "$tmp/e")"
    [ -e "$tmp/mg/shadowlab.db" ] && fail "v$v as a shard: a store was written"
    # from 17 on, a cell whose rows fail their own digest stays damaged through the upgrade
    if [ "$v" -ge 17 ]; then
      sqlite3 "$tmp/s.db" "UPDATE figures SET count = count + 1 WHERE figure = 'wrong' AND region = 'image' AND
                           cell_id = (SELECT cell_id FROM cells WHERE label = 'csm')"
      "$bin" verify "$tmp/s.db" >"$tmp/o" 2>"$tmp/e"; rc=$?
      [ $rc -eq 2 ] && grep -q "damaged cell primitives/side/32x32/64/csm" "$tmp/e" ||
        fail "v$v: a changed count: verify exit $rc: $(cat "$tmp/e")"
    fi
    n=$((n + 1))
    echo "v$v read"
  done
  [ $n -ge 1 ] && [ -e "$dir/v16.db" ] || fail "no stores in $dir"
  ;;
doc)
  # verify --help and doc/store.md state the same promise: what is checked
  # and the exit codes
  doc=$(dirname "$0")/../doc/store.md
  "$bin" verify --help >"$tmp/h" 2>&1 || fail "verify --help"
  h=$(tr -s ' \n' '  ' <"$tmp/h"); m=$(tr -s ' \n' '  ' <"$doc")
  for w in "Exit 0 when all is whole, 1 when a sweep is incomplete, 2 when" "quick_check" "CRC-32" "--files" "--no-files"; do
    grep -qF -- "$w" <<<"$h" || fail "verify --help lacks '$w'"
  done
  for w in "Exit 0 when all is whole, 1 for an incomplete sweep (and no damage), 2" "the \`.db\` alone holds everything" \
           "\`--files\` checks them anyway" "\`--no-files\` skips them" "Old stores stay readable"; do
    grep -qF -- "$w" <<<"$m" || fail "doc/store.md lacks '$w'"
  done
  ;;
*)
  fail "unknown case $case_"
  ;;
esac
echo "ok $case_"
