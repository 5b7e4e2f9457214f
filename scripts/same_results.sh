#!/usr/bin/env bash
# scripts/same_results.sh OUT_A OUT_B [STUDY...] — are two results folders
# the same results? For a change that must not move a number (a
# restructuring): run the studies with the old binary into OUT_A and with the
# new one into OUT_B (`shadowlab run CONFIG --no-cache -q -o OUT`), then
# compare, per study folder: figures.csv, motion.csv and patterns.csv with
# the git SHA column left out, every cell of the store (every column but
# timings, ids and the digest that covers them) and every overlay PNG byte
# for byte (a PNG that differs in bytes, as its text chunks name the git
# SHA, is compared by its header and inflated image data, so only a pixel
# difference fails). Prints one line per study; exit 0 when all match.
set -u
a=${1:?usage: same_results.sh OUT_A OUT_B [STUDY...]}
b=${2:?usage: same_results.sh OUT_A OUT_B [STUDY...]}
shift 2
studies=("$@")
if [ ${#studies[@]} -eq 0 ]; then
  for d in "$a"/*/; do [ -f "$d/run.yaml" ] && studies+=("$(basename "$d")"); done
fi
# a CSV without its git_sha column (found by name in the header)
no_sha() {
  [ -f "$1" ] || { echo "(absent)"; return; }
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "git_sha") skip = i }
           { out = ""; for (i = 1; i <= NF; i++) if (i != skip) out = out (out == "" ? "" : ",") $i; print out }' "$1"
}
cells_of() {
  local cols
  cols=$(sqlite3 "$1" "SELECT group_concat(name, ' || ''|'' || ') FROM pragma_table_info('cells')
                       WHERE name NOT LIKE 'ms%' AND name NOT IN ('cell_id', 'run_id', 'digest')")
  sqlite3 "$1" "SELECT $cols FROM cells" | sort
}
fail=0
for s in "${studies[@]}"; do
  bad=""
  for f in figures.csv motion.csv patterns.csv; do
    cmp -s <(no_sha "$a/$s/$f") <(no_sha "$b/$s/$f") || bad="$bad $f"
  done
  n=0 px=0
  if [ -d "$a/$s/overlays" ] || [ -d "$b/$s/overlays" ]; then
    cmp -s <(cd "$a/$s/overlays" 2>/dev/null && ls) <(cd "$b/$s/overlays" 2>/dev/null && ls) || bad="$bad overlay-names"
    # PNGs whose bytes differ (their text chunks name the git SHA) are
    # compared by their decoded image data and header (IHDR + inflated IDAT)
    read -r n px diff < <(python3 - "$a/$s/overlays" "$b/$s/overlays" <<'PY'
import os, sys, zlib
def image(path):
    d = open(path, "rb").read()
    i, ihdr, idat = 8, b"", []
    while i < len(d):
        n = int.from_bytes(d[i:i + 4], "big"); t = d[i + 4:i + 8]
        if t == b"IHDR": ihdr = d[i + 8:i + 8 + n]
        if t == b"IDAT": idat.append(d[i + 8:i + 8 + n])
        i += 12 + n
    return ihdr, zlib.decompress(b"".join(idat))
a, b = sys.argv[1:3]
n = px = 0; bad = []
for f in sorted(os.listdir(a)) if os.path.isdir(a) else []:
    if not f.endswith(".png"): continue
    n += 1
    q = os.path.join(b, f)
    if not os.path.exists(q): continue
    if open(os.path.join(a, f), "rb").read() != open(q, "rb").read():
        px += 1
        if image(os.path.join(a, f)) != image(q): bad.append(f)
print(n, px, ",".join(bad) or "-")
PY
)
    [ "$diff" = "-" ] || bad="$bad pixels:$diff"
  fi
  if [ -z "$bad" ]; then
    echo "same  $s ($n overlays, $px differing only in bytes)"
  else
    echo "DIFF  $s:$bad"
    fail=1
  fi
done
if cmp -s <(cells_of "$a/shadowlab.db") <(cells_of "$b/shadowlab.db"); then
  echo "same  store ($(cells_of "$a/shadowlab.db" | wc -l) cells)"
else
  echo "DIFF  store: the cells differ"
  fail=1
fi
exit $fail
