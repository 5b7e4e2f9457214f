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
# difference fails), the run's tables (table.md, table.tex, table-detail.tex)
# byte for byte but their tables of times (two runs never time alike: the
# cost section of table.md, each LaTeX table whose caption names ms), with
# each side's git SHA read from its run.yaml put back as one word, and
# costs.csv's counts (every column but times, the git SHA
# and the machine). With BIN_A and BIN_B set (the two binaries), also the
# tables each binary renders from its own store: `shadowlab table` in every
# format (md, csv, latex), its --summary, and a pivot in every format
# (json too). Prints one line per study; exit 0 when all match.
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
# a file with the git SHA its run.yaml names (12 hex digits) put back as SHA
sha_of() { sed -n 's/^git_sha: //p' "$1/run.yaml" 2>/dev/null | head -n 1; }
unsha() {
  [ -f "$2" ] || { echo "(absent)"; return; }
  python3 - "$1" "$2" <<'PY'
import re, sys
sha, path = sys.argv[1:3]
text = open(path, encoding="utf-8").read()
if sha:
    text = text.replace(sha, "SHA")
if path.endswith(".md"):   # the cost section: times
    text = re.sub(r"\n## Cost per cell.*?(?=\n## |\Z)", "\n## Cost per cell (times)\n", text, flags=re.S)
else:                       # a table whose caption names a time
    parts = re.split(r"(\\begin\{(?:table|longtable)\*?\}.*?\\end\{(?:table|longtable)\*?\})", text, flags=re.S)
    text = "".join("(a table of times)\n" if re.search(r"\\caption\{[^\n]*(ms\\_|step ms|, ms[;.]| ms\b)", p) else p
                   for p in parts)
sys.stdout.write(text)
PY
}
# costs.csv's counts: the columns but times (ms*), git_sha and machine
counts_of() {
  [ -f "$1" ] || { echo "(absent)"; return; }
  python3 - "$1" <<'PY'
import csv, sys
rows = list(csv.reader(open(sys.argv[1], newline="")))
keep = [i for i, h in enumerate(rows[0]) if not h.startswith("ms") and h not in ("git_sha", "machine")]
for r in rows:
    print(",".join(r[i] for i in keep))
PY
}
# the store's cells of the studies compared (all of them without a list)
cells_of() {
  local cols where=""
  cols=$(sqlite3 "$1" "SELECT group_concat(name, ' || ''|'' || ') FROM pragma_table_info('cells')
                       WHERE name NOT LIKE 'ms%' AND name NOT IN ('cell_id', 'run_id', 'digest')")
  if [ ${#studies[@]} -gt 0 ]; then
    where="WHERE run_id IN (SELECT run_id FROM runs WHERE study IN ($(printf "'%s'," "${studies[@]}" | sed 's/,$//')))"
  fi
  sqlite3 "$1" "SELECT $cols FROM cells $where" | sort
}
fail=0
for s in "${studies[@]}"; do
  bad=""
  for f in figures.csv motion.csv patterns.csv; do
    cmp -s <(no_sha "$a/$s/$f") <(no_sha "$b/$s/$f") || bad="$bad $f"
  done
  sa=$(sha_of "$a/$s") sb=$(sha_of "$b/$s")
  for f in table.md table.tex table-detail.tex; do
    cmp -s <(unsha "$sa" "$a/$s/$f") <(unsha "$sb" "$b/$s/$f") || bad="$bad $f"
  done
  cmp -s <(counts_of "$a/$s/costs.csv") <(counts_of "$b/$s/costs.csv") || bad="$bad costs.csv-counts"
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
# the tables each binary renders from its own store, in every format
if [ -n "${BIN_A:-}" ] && [ -n "${BIN_B:-}" ]; then
  tabs() {   # tabs BIN DB: every table form, the git SHAs of the store's runs put back as SHA
    local bin=$1 db=$2 shas
    shas=$(sqlite3 "$db" "SELECT DISTINCT git_sha FROM runs" 2>/dev/null | tr '\n' ' ')
    {
      for f in md csv latex; do
        echo "== table --format $f"; "$bin" table "$db" --format "$f" 2>&1
        echo "== table --summary wrong --format $f"; "$bin" table "$db" --summary wrong --format "$f" 2>&1
      done
      for f in md csv latex json; do
        echo "== pivot --format $f"; "$bin" table "$db" --rows label --cols map_size --figure wrong --format "$f" 2>&1
      done
    } | sed "s#$db#DB#g" |   # the store's path, which the tables name
      { if [ -n "${shas// /}" ]; then sed -E "s/$(echo $shas | sed 's/ /|/g')/SHA/g"; else cat; fi; }
  }
  if cmp -s <(tabs "$BIN_A" "$a/shadowlab.db") <(tabs "$BIN_B" "$b/shadowlab.db"); then
    echo "same  tables ($(tabs "$BIN_A" "$a/shadowlab.db" | wc -l) lines in every format)"
  else
    echo "DIFF  tables: 'shadowlab table' renders the stores differently"
    diff <(tabs "$BIN_A" "$a/shadowlab.db") <(tabs "$BIN_B" "$b/shadowlab.db") | head -n 20
    fail=1
  fi
fi
exit $fail
