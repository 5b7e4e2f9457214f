#!/usr/bin/env bash
# cli::hostile_input — bounded, checked input (issue 34): a file nested
# 200,000 levels deep (config, scene, baseline, a -D value), a special file
# (FIFO, device, folder) as config, scene, base:, model or baseline, a
# number out of range or not whole (-D and options), a store: path that
# leaves --out, a mesh placed past float range: each is exit 2 with one
# line naming file, line and key, well within a time bound (the target is
# 5 s; 10 s here leaves room for a loaded CI machine), and nothing written.
# The big files are made here, not committed.
set -u
bin=${1:?usage: cli_hostile_input.sh path/to/shadowlab}
case $bin in /*) ;; *) bin=$PWD/$bin ;; esac   # some cases run in another folder
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
limit=10   # seconds

case_() { # name stderr_pattern -- command...   (want: exit 2, pattern on line 1, <= $limit s)
  local name=$1 pat=$2; shift 3
  local t0 t1 rc ms
  t0=$(date +%s%N)
  timeout 30 "$@" >"$tmp/out" 2>"$tmp/err" </dev/null
  rc=$?
  t1=$(date +%s%N)
  ms=$(((t1 - t0) / 1000000))
  if [ "$rc" -ne 2 ]; then
    echo "FAIL $name: exit $rc (want 2) after ${ms} ms"; head -c 600 "$tmp/err"; fail=$((fail + 1)); return 1
  fi
  if ! grep -Eq -- "$pat" <(head -n 1 "$tmp/err"); then
    echo "FAIL $name: first stderr line does not match /$pat/:"; head -c 600 "$tmp/err"; fail=$((fail + 1)); return 1
  fi
  if [ "$ms" -gt $((limit * 1000)) ]; then
    echo "FAIL $name: ${ms} ms (at most ${limit} s)"; fail=$((fail + 1)); return 1
  fi
  if [ -d "$tmp/res" ] && [ -n "$(ls -A "$tmp/res")" ]; then
    echo "FAIL $name: wrote into --out:"; ls -la "$tmp/res"; fail=$((fail + 1)); return 1
  fi
  echo "ok   $name (${ms} ms): $(head -n 1 "$tmp/err" | cut -c1-160)"
  pass=$((pass + 1))
}

nest() { # n: n '[' then n ']'
  head -c "$1" /dev/zero | tr '\0' '['
  head -c "$1" /dev/zero | tr '\0' ']'
}
cfg_head='scenes: [{scene: primitives}]
map_sizes: [1024]
methods: [{method: nsm}]'

# ---- nesting: refused at the line where it passes the limit, naming the key
{ echo "$cfg_head"; printf 'name: '; nest 200000; echo; } >"$tmp/deep.yaml"
case_ "config nested 200,000 deep" "$tmp/deep\.yaml:4: 'name': nested more than 64 levels" -- \
  "$bin" validate "$tmp/deep.yaml"
{ echo "$cfg_head"; printf 'name: '; nest 60000; echo; } >"$tmp/deep60k.yaml"
case_ "config nested 60,000 deep, with -D (was SIGSEGV)" "$tmp/deep60k\.yaml:4: 'name': nested more than 64" -- \
  "$bin" run "$tmp/deep60k.yaml" -D seed=3 --out "$tmp/res"
{ echo "$cfg_head"; echo 'name:'; head -c 200000 /dev/zero | sed 's/\x0/- /g'; echo x; } >"$tmp/deep_block.yaml"
case_ "config nested 100,000 deep in block style" "$tmp/deep_block\.yaml:5: 'name': nested more than 64" -- \
  "$bin" validate "$tmp/deep_block.yaml"
case_ "-D value nested 30,000 deep" "^shadowlab: -D name=.*'name': the value is nested more than 64" -- \
  "$bin" validate configs/default.yaml -D "name=$(nest 30000)"
{ echo 'light: {type: directional, direction: [0, -1, 0]}'; printf 'meshes: '; nest 200000; echo; } \
  >"$tmp/deep_scene.yaml"
case_ "scene nested 200,000 deep" "$tmp/deep_scene\.yaml:2: 'meshes': nested more than 64" -- \
  "$bin" validate "$tmp/deep_scene.yaml"
{ printf 'cells:\n  - '; nest 200000; echo; } >"$tmp/deep_base.yaml"
: >"$tmp/empty.db"
case_ "baseline nested 200,000 deep" "$tmp/deep_base\.yaml:2: 'cells': nested more than 64" -- \
  "$bin" check "$tmp/empty.db" --baseline "$tmp/deep_base.yaml"

# ---- special files: refused by type before any open or read
mkfifo "$tmp/fifo.yaml"
mkdir "$tmp/folder.ply"
case_ "validate /dev/zero" "/dev/zero: cannot read: a character device, not a regular file" -- \
  "$bin" validate /dev/zero
case_ "run /dev/zero" "/dev/zero: cannot read: a character device" -- "$bin" run /dev/zero --out "$tmp/res"
case_ "a FIFO as config" "$tmp/fifo\.yaml: cannot read: a FIFO, not a regular file" -- \
  "$bin" validate "$tmp/fifo.yaml"
case_ "run a FIFO as config" "$tmp/fifo\.yaml: cannot read: a FIFO" -- "$bin" run "$tmp/fifo.yaml" --out "$tmp/res"
printf 'scenes: [{scene: %s}]\nmap_sizes: [1024]\nmethods: [{method: nsm}]\n' "$tmp/fifo.yaml" >"$tmp/cfg_fifo.yaml"
case_ "a FIFO as a config's scene" "$tmp/cfg_fifo\.yaml:1: 'scenes\[0\]\.scene': .*fifo\.yaml is a FIFO" -- \
  "$bin" validate "$tmp/cfg_fifo.yaml"
printf 'name: b\nbase: %s\n' "$tmp/fifo.yaml" >"$tmp/scene_base.yaml"
case_ "a FIFO as a scene's base:" "$tmp/scene_base\.yaml:2: 'base': .*fifo\.yaml is a FIFO" -- \
  "$bin" validate "$tmp/scene_base.yaml"
for m in fifo.yaml:FIFO folder.ply:folder /dev/zero:"character device"; do
  f=${m%%:*} what=${m#*:}
  case $f in /*) p=$f ;; *) p=$tmp/$f ;; esac
  printf 'light: {type: directional, direction: [0, -1, 0]}\nmeshes:\n  - {name: ground, generator: plane, center: [0, 0, 0], size: 10}\n  - {file: %s}\nviewpoints:\n  - {name: a, position: [0, 5, 5], direction: [0, -1, -1], fov: 60, near: 0.1, far: 100}\n' \
    "$p" >"$tmp/scene_mesh.yaml"
  case_ "a $what as a model file" "$tmp/scene_mesh\.yaml:4: 'meshes\[1\]\.file': .* is a $what" -- \
    "$bin" validate "$tmp/scene_mesh.yaml"
done
case_ "a FIFO as baseline" "fifo\.yaml: cannot read: a FIFO" -- \
  "$bin" check "$tmp/empty.db" --baseline "$tmp/fifo.yaml"


# ---- numbers: range-checked before any cast, whole numbers only, the same
# message form for -D, the file's own keys and the options
case_ "-D repetitions.warmup=4294967295 (was -1)" \
  "^shadowlab: -D repetitions\.warmup=4294967295: 'repetitions\.warmup': 4294967295 is outside \[0, 100\]" -- \
  "$bin" validate configs/default.yaml -D repetitions.warmup=4294967295
case_ "-D threads=4294967295" "'threads': 4294967295 is outside \[0, 256\]" -- \
  "$bin" validate configs/default.yaml -D threads=4294967295
case_ "-D seed=7.9 (was 7)" "^shadowlab: -D seed=7\.9: 'seed': '7\.9' is not a whole number" -- \
  "$bin" validate configs/default.yaml -D seed=7.9
case_ "-D map_sizes=[512, 1e3]" "'map_sizes\[1\]': '1e3' is not a whole number" -- \
  "$bin" validate configs/default.yaml -D "map_sizes=[512, 1e3]"
{ echo "$cfg_head"; echo 'seed: 7.9'; } >"$tmp/seed.yaml"
case_ "seed: 7.9 in the file" "$tmp/seed\.yaml:4: 'seed': '7\.9' is not a whole number" -- "$bin" validate "$tmp/seed.yaml"
{ echo "$cfg_head"; echo 'area_samples: 4294967295'; } >"$tmp/samples.yaml"
case_ "area_samples: 4294967295 in the file" "$tmp/samples\.yaml:4: 'area_samples': 4294967295 is outside \[2, 1024\]" -- \
  "$bin" validate "$tmp/samples.yaml"
case_ "--cells 4294967298:4294967300 (was the slice 2:4)" "'--cells': cells 4294967298:4294967300 outside the sweep of 6 cells" -- \
  "$bin" run configs/default.yaml --cells 4294967298:4294967300 --out "$tmp/res"
case_ "--cells 0:99999999999999999999" "'--cells': cells 0:99999999999999999999 outside the sweep of 6 cells" -- \
  "$bin" run configs/default.yaml --cells 0:99999999999999999999 --out "$tmp/res"
case_ "--cells 1.5:3" "run: --cells 1\.5:3: '1\.5' is not a whole number" -- \
  "$bin" run configs/default.yaml --cells 1.5:3 --out "$tmp/res"
case_ "--jobs 4294967297 (was 1)" "run: --jobs '4294967297' must be in 1\.\.64" -- \
  "$bin" run configs/default.yaml --jobs 4294967297 --out "$tmp/res"
case_ "-j 2.5" "run: -j/--threads '2\.5' is not a whole number" -- \
  "$bin" run configs/default.yaml -j 2.5 --out "$tmp/res"
case_ "bench --reps 4294967297 (was 1)" "bench: --reps '4294967297' must be in 1\.\.1000" -- \
  "$bin" bench --reps 4294967297
case_ "table --map 1e3" "table: --map '1e3' is not a whole number" -- "$bin" table "$tmp/empty.db" --map 1e3

# ---- store: paths stay under --out (--db on the command line may go elsewhere)
small='scenes: [{scene: primitives, viewpoints: [side]}]
viewports: [{width: 64, height: 64}]
map_sizes: [64]
methods: [{method: nsm}]'
mkdir -p "$tmp/wd/a/b"
for st in ../../x.db "$tmp/abs.db" "r/../../x.db"; do
  { echo "$small"; echo "store: $st"; } >"$tmp/wd/a/b/st.yaml"
  case_ "store: $st" "st\.yaml:5: 'store': '$st' leaves the output folder" -- \
    "$bin" validate "$tmp/wd/a/b/st.yaml"
  (cd "$tmp/wd/a/b" && case_ "run with store: $st" "st\.yaml:5: 'store': '$st' leaves the output folder" -- \
    "$bin" run st.yaml --out res) && pass=$((pass + 1)) || fail=$((fail + 1))
done
if [ -n "$(find "$tmp/wd" -name '*.db')" ] || [ -e "$tmp/abs.db" ]; then
  echo "FAIL store: a database was written: $(find "$tmp/wd" "$tmp/abs.db" -name '*.db' 2>/dev/null)"
  fail=$((fail + 1))
fi
# a relative store: is a path under --out, not under the working folder
{ echo "$small"; echo "store: elsewhere/x.db"; } >"$tmp/wd/a/b/st.yaml"
if (cd "$tmp/wd/a/b" && "$bin" run st.yaml --out res -q >/dev/null 2>"$tmp/err") &&
   [ -f "$tmp/wd/a/b/res/elsewhere/x.db" ] && [ "$(find "$tmp/wd" -name '*.db' | wc -l)" -eq 1 ]; then
  pass=$((pass + 1))
else
  echo "FAIL store: elsewhere/x.db is not res/elsewhere/x.db: $(cat "$tmp/err"); $(find "$tmp/wd" -name '*.db')"
  fail=$((fail + 1))
fi

# ---- aliases: refused at the first one, never expanded (a 7 MB baseline of
# '- *c' lines, each a copy of one anchored cell, took 22 s and 3.2 GB before)
n=$(grep -n '^cells:' tests/baselines/ci.yaml | cut -d: -f1)
m=$(awk -v n="$n" 'NR > n + 1 && /^  - cell:/ { print NR; exit }' tests/baselines/ci.yaml)
{ sed -n "1,${n}p" tests/baselines/ci.yaml; echo '  - &c'
  sed -n "$((n + 1)),$((m - 1))p" tests/baselines/ci.yaml | sed '1s/^  - /    /'
  yes '  - *c' | head -n 1000000; } >"$tmp/laughs.yaml"
case_ "baseline of 1,000,000 aliases of one cell" \
  "$tmp/laughs\.yaml:$((m + 1)): 'cells\[1\]': an alias \(\*c\): YAML anchors and aliases are not read" -- \
  "$bin" check "$tmp/empty.db" --baseline "$tmp/laughs.yaml"
{ echo "$cfg_head"; echo 'viewports: &v [{name: a}]'; echo 'contours: *v'; } >"$tmp/alias_cfg.yaml"
case_ "config with an alias" "$tmp/alias_cfg\.yaml:5: 'contours': an alias \(\*v\)" -- \
  "$bin" validate "$tmp/alias_cfg.yaml"
{ echo 'light: &l {type: directional, direction: [0, -1, 0]}'; echo 'meshes: [*l]'; } >"$tmp/alias_scene.yaml"
case_ "scene with an alias" "$tmp/alias_scene\.yaml:2: 'meshes\[0\]': an alias \(\*l\)" -- \
  "$bin" validate "$tmp/alias_scene.yaml"

# ---- geometry overflow: blamed on the entry that caused it, not on the
# ground triangle that float precision collapsed
printf 'v 0 0 0\nv 1e30 0 0\nv 0 1e30 0\nf 1 2 3\n' >"$tmp/big.obj"
scene_with() { # the second mesh entry
  printf 'light: {type: directional, direction: [0, -1, 0]}\nmeshes:\n  - {name: ground, generator: plane, center: [0, 0, 0], size: 10}\n  - %s\nviewpoints:\n  - {name: a, position: [0, 5, 5], direction: [0, -1, -1], fov: 60, near: 0.1, far: 100}\n' "$1"
}
scene_with '{name: big, file: big.obj}' >"$tmp/g_file.yaml"
case_ "a model reaching 1e30" "$tmp/g_file\.yaml:4: 'meshes\[1\]\.file': mesh 'big' reaches 1e\+30 units.*triangle 0 of mesh 'ground'" -- \
  "$bin" validate "$tmp/g_file.yaml"
scene_with '{name: box, generator: box, min: [0, 0, 0], max: [1, 1, 1], transform: {translate: [1e9, 0, 0]}}' \
  >"$tmp/g_tr.yaml"
case_ "translate 1e9" "$tmp/g_tr\.yaml:4: 'meshes\[1\]\.transform\.translate': mesh 'box' reaches 1e\+09 units.*triangle 0 of mesh 'ground'" -- \
  "$bin" validate "$tmp/g_tr.yaml"
scene_with '{name: box, generator: box, min: [0, 0, 0], max: [1, 1, 1], transform: {scale: [1e9, 1e9, 1e9]}}' \
  >"$tmp/g_sc.yaml"
case_ "scale 1e9" "$tmp/g_sc\.yaml:4: 'meshes\[1\]\.transform\.scale': mesh 'box' reaches 1e\+09 units" -- \
  "$bin" validate "$tmp/g_sc.yaml"
scene_with '{name: box, generator: box, min: [0, 0, 0], max: [1, 1, 1], transform: {translate: [0, 0, -1e31]}}' \
  >"$tmp/g_tr31.yaml"
case_ "translate 1e31" "$tmp/g_tr31\.yaml:4: 'meshes\[1\]\.transform\.translate': the mesh's coordinates reach 1e\+31" -- \
  "$bin" validate "$tmp/g_tr31.yaml"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
