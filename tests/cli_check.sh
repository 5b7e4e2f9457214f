#!/usr/bin/env bash
# cli::check — `shadowlab check` against baselines written with --update and
# then edited: a store equals its own baseline (exit 0, nothing moved); a
# figure moved beyond its class tolerance fails (exit 1) and is named; a move
# within tolerance passes when counts are not exact and fails under --exact;
# a violation fails at any
# tolerance; a missing cell fails; a bad baseline is exit 2 naming file and line.
set -u
bin=${1:?usage: cli_check.sh path/to/shadowlab}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
fail() { echo "FAIL $*"; fails=$((fails + 1)); }
cat >"$tmp/c.yaml" <<'YAML'
name: checkme
scenes: [{scene: primitives, viewpoints: [side]}]
viewports: [{width: 128, height: 128}]
map_sizes: [256]
methods:
  - {label: nsm, method: nsm}
  - {label: csm, method: csm}
outputs: {overlays: false}
YAML
"$bin" run "$tmp/c.yaml" --out "$tmp/r" --no-cache >/dev/null 2>&1 || { echo "FAIL run"; exit 1; }
db=$tmp/r/shadowlab.db
"$bin" check "$db" --baseline "$tmp/b.yaml" --update 2>/dev/null || { echo "FAIL --update"; exit 1; }
grep -q '^  - cell: "primitives/side/128x128/256/nsm"' "$tmp/b.yaml" || fail "baseline lacks the nsm cell"

out=$("$bin" check "$db" --baseline "$tmp/b.yaml"); rc=$?
[ $rc -eq 0 ] || fail "a store against its own baseline: exit $rc"
echo "$out" | grep -q " 0 moved, 0 outside tolerance, 0 cell(s) missing" || fail "own baseline moved: $out"
echo "$out" | grep -q "Counts compared exactly" || fail "same machine, counts not exact"

# the nsm cell's whole-image wrong count (last value of its 'wrong' list) + 50
awk 'BEGIN{c=0} /cell: "primitives\/side\/128x128\/256\/nsm"/{c=1} c && /^      wrong: /{sub(/\]$/,""); n=split($0,a,", "); a[n]+=50; s=a[1]; for(i=2;i<=n;i++) s=s", "a[i]; print s"]"; c=0; next} {print}' \
  "$tmp/b.yaml" >"$tmp/moved.yaml"
cmp -s "$tmp/b.yaml" "$tmp/moved.yaml" && fail "the edit did not change the baseline"
out=$("$bin" check "$db" --baseline "$tmp/moved.yaml" --format md); rc=$?
[ $rc -eq 1 ] || fail "50 wrong pixels moved: exit $rc, want 1"
echo "$out" | grep -q '| primitives/side/128x128/256/nsm | image | wrong | error | .* | \*\*FAIL\*\* |' ||
  fail "the moved figure is not named: $out"

# the same move is within a 5 pp tolerance when counts are compared by tolerance
sed -e 's/^counts: same_machine/counts: tolerance/' -e 's/^  error: .*/  error: 5/' "$tmp/moved.yaml" >"$tmp/loose.yaml"
out=$("$bin" check "$db" --baseline "$tmp/loose.yaml" --format md); rc=$?
[ $rc -eq 0 ] || fail "a move within tolerance: exit $rc, want 0: $out"
echo "$out" | grep -q '| wrong | error | .* | ok |' || fail "a move within tolerance is not listed as ok"
# ... and fails under --exact, whatever the baseline's count mode (CI's platform matrix)
out=$("$bin" check "$db" --baseline "$tmp/loose.yaml" --exact --format md); rc=$?
[ $rc -eq 1 ] || fail "--exact, a move within tolerance: exit $rc, want 1: $out"
echo "$out" | grep -q 'Counts compared exactly (--exact)' || fail "--exact not said: $out"
"$bin" check "$db" --baseline "$tmp/b.yaml" --exact >/dev/null || fail "--exact against its own baseline"

# a violation fails whatever the tolerances
sed -e 's/violations: 0\([,}]\)/violations: 1\1/' "$tmp/loose.yaml" >"$tmp/viol.yaml"
"$bin" check "$db" --baseline "$tmp/viol.yaml" --format md >"$tmp/viol.out"; rc=$?
[ $rc -eq 1 ] || fail "a violation: exit $rc, want 1"
grep -q '| violations | invariant | 1 | 0 | .* | exact | \*\*FAIL\*\* |' "$tmp/viol.out" || fail "violation row missing"

# a baseline cell the store lacks
sed -e 's#primitives/side/128x128/256/csm#primitives/side/128x128/512/csm#' "$tmp/b.yaml" >"$tmp/missing.yaml"
out=$("$bin" check "$db" --baseline "$tmp/missing.yaml"); rc=$?
[ $rc -eq 1 ] || fail "a missing cell: exit $rc, want 1"
echo "$out" | grep -q "1 cell(s) missing" || fail "missing cell not counted"
echo "$out" | grep -q "^- primitives/side/128x128/256/csm" || fail "the store's extra cell is not listed"

# bad baselines: exit 2, file and line
sed -e 's/^      traced: .*/      tracedd: [1, 2, 3, 4]/' "$tmp/b.yaml" >"$tmp/badkey.yaml"
err=$("$bin" check "$db" --baseline "$tmp/badkey.yaml" 2>&1 >/dev/null); rc=$?
[ $rc -eq 2 ] || fail "unknown figure: exit $rc, want 2"
echo "$err" | grep -q "badkey.yaml:[0-9]" || fail "unknown figure: no file:line in '$err'"
sed -e 's/^  error: .*/  error: -1/' "$tmp/b.yaml" >"$tmp/badtol.yaml"
err=$("$bin" check "$db" --baseline "$tmp/badtol.yaml" 2>&1 >/dev/null); rc=$?
[ $rc -eq 2 ] || fail "negative tolerance: exit $rc, want 2"
echo "$err" | grep -q "badtol.yaml:[0-9]*: 'tolerances.error'" || fail "negative tolerance: '$err'"
err=$("$bin" check "$tmp/nope.db" --baseline "$tmp/b.yaml" 2>&1 >/dev/null); rc=$?
[ $rc -eq 2 ] || fail "no store: exit $rc, want 2"
echo "$err" | grep -q "nope.db: no results store" || fail "no store: '$err'"
[ -e "$tmp/nope.db" ] && fail "check created a store"

# --update keeps the tolerances it replaces
"$bin" check "$db" --baseline "$tmp/loose.yaml" --update 2>/dev/null || fail "--update over an edited file"
grep -q '^  error: 5 ' "$tmp/loose.yaml" || fail "--update lost the tolerance"
grep -q '^counts: tolerance' "$tmp/loose.yaml" || fail "--update lost the count mode"

# a soft-shadow cell (area light): its means compared in pp of visibility
cat >"$tmp/s.yaml" <<'YAML'
name: softcheck
scenes: [{scene: curtis_box, viewpoints: [above]}]
viewports: [{width: 64, height: 64}]
map_sizes: [256]
methods: [{label: point, method: hard_point}]
area_samples: 4
outputs: {overlays: false}
YAML
"$bin" run "$tmp/s.yaml" --out "$tmp/s" --no-cache >/dev/null 2>&1 || { echo "FAIL soft run"; exit 1; }
"$bin" check "$tmp/s/shadowlab.db" --baseline "$tmp/sb.yaml" --update 2>/dev/null || fail "soft --update"
grep -q "^    soft_mean: {soft_mae: " "$tmp/sb.yaml" || fail "soft baseline has no means"
"$bin" check "$tmp/s/shadowlab.db" --baseline "$tmp/sb.yaml" >/dev/null || fail "soft cell against its own baseline"
sed -E 's/soft_mean: \{soft_mae: [0-9.]+/soft_mean: {soft_mae: 99/' "$tmp/sb.yaml" >"$tmp/sb2.yaml"
out=$("$bin" check "$tmp/s/shadowlab.db" --baseline "$tmp/sb2.yaml" --format md); rc=$?
[ $rc -eq 1 ] || fail "a moved soft MAE: exit $rc, want 1"
echo "$out" | grep -q '| soft_mae | soft | 99 |' || fail "the moved soft MAE is not named: $out"

# issue 37: a store of another config (a -D override) is said to differ
# before any figure, with both hashes; the exit status is the figures' alone
"$bin" run "$tmp/c.yaml" --out "$tmp/d" --no-cache -D 'methods[0].self_shadow=none' >/dev/null 2>&1 || fail "run -D"
out=$("$bin" check "$tmp/d/shadowlab.db" --baseline "$tmp/b.yaml"); rc=$?
[ $rc -eq 1 ] || fail "another config's store: exit $rc, not 1 (its nsm figures moved)"
first=$(echo "$out" | sed -n 3,4p)
bh=$(sed -n 's/^config_hash: "\(.*\)"/\1/p' "$tmp/b.yaml")
echo "$first" | grep -q "^Before the figures, what differs from the baseline:" || fail "the difference is not said first: $out"
echo "$first" | grep -q "^- config hash: the store's 2 cell(s) have [0-9a-f]*, the baseline $bh" ||
  fail "the config hashes are not named: $first"
out=$("$bin" check "$db" --baseline "$tmp/b.yaml")
echo "$out" | grep -q "what differs from the baseline" && fail "its own baseline said to differ: $out"
[ $fails -eq 0 ] && echo "cli::check passed" || exit 1
