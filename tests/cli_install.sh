#!/usr/bin/env bash
# cli::install — `cmake --install` into a temporary prefix; the installed
# binary, started from another folder with the source tree hidden (an empty
# folder mounted over it in a private mount namespace, so a binary that still
# looked into the tree it was built from would find nothing there), runs the
# shipped default config and finds every scene in <prefix>/share/shadowlab,
# and its report of a study of both theses' methods finds the theses' data
# files there (share/shadowlab/theses). The man page and the bash completion
# are installed and load.
set -u
build=${1:?usage: cli_install.sh BUILD_DIR SOURCE_DIR}
src=${2:?usage: cli_install.sh BUILD_DIR SOURCE_DIR}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefix=$tmp/prefix
cmake --install "$build" --prefix "$prefix" >"$tmp/install.log" 2>&1 || { echo "FAIL cmake --install:"; cat "$tmp/install.log"; exit 1; }
b=$prefix/bin/shadowlab
share=$prefix/share/shadowlab
module=$(find "$prefix" -name shadowlab-oiio.so)
sheet=$(find "$prefix" -name shadowlab-sheet.so)
[ -n "$module" ] && [ -n "$sheet" ] || { echo "FAIL the image modules are not installed"; exit 1; }
for f in "$b" "$share/configs/default.yaml" "$share/scenes/primitives.yaml" "$share/scenes/hard/models/tiny.obj" \
         "$prefix/share/man/man1/shadowlab.1" "$prefix/share/bash-completion/completions/shadowlab"; do
  [ -e "$f" ] || { echo "FAIL not installed: $f"; exit 1; }
done
man -l "$prefix/share/man/man1/shadowlab.1" 2>/dev/null | grep -q "SHADOWLAB_SCENES" || command -v man >/dev/null ||
  true   # man may be missing; the page is checked by groff below when present
if command -v groff >/dev/null; then
  groff -man -Tutf8 -ww -z "$prefix/share/man/man1/shadowlab.1" 2>"$tmp/groff.err"
  [ -s "$tmp/groff.err" ] && { echo "FAIL man page warnings:"; cat "$tmp/groff.err"; exit 1; }
fi
# the completion offers the verbs and a verb's options
out=$(bash -c "source '$prefix/share/bash-completion/completions/shadowlab'
COMP_WORDS=(shadowlab ch); COMP_CWORD=1; _shadowlab; echo \${COMPREPLY[*]}
COMP_WORDS=(shadowlab check x.db --ju); COMP_CWORD=3; _shadowlab; echo \${COMPREPLY[*]}")
[ "$out" = "$(printf 'check\n--junit')" ] || { echo "FAIL completion: '$out'"; exit 1; }

mkdir -p "$tmp/elsewhere" "$tmp/empty"
cd "$tmp/elsewhere"
# a sanitizer build reads its LeakSanitizer suppressions from the source
# tree, which is about to be hidden: a copy outside it serves
case ${LSAN_OPTIONS:-} in
  *suppressions=*)
    supp=${LSAN_OPTIONS#*suppressions=}; supp=${supp%%:*}
    cp "$supp" "$tmp/lsan.supp" && export LSAN_OPTIONS=${LSAN_OPTIONS/$supp/$tmp/lsan.supp} ;;
esac
# the source tree and the build tree hidden where the system allows a
# private mount namespace (the build tree holds the image module too: the
# installed binary must load its own, from <prefix>/lib*/shadowlab)
hide() {
  unshare -m --propagation private sh -c 'mount --bind "$1" "$2" && mount --bind "$1" "$3" && shift 3 && exec "$@"' \
    sh "$tmp/empty" "$src" "$build" "$@"
}
if hide true 2>/dev/null; then
  [ -z "$(hide ls -A "$src")" ] || { echo "FAIL the source tree is not hidden"; exit 1; }
  [ -z "$(hide ls -A "$build")" ] || { echo "FAIL the build tree is not hidden"; exit 1; }
  echo "source tree $src and build tree $build hidden in a mount namespace"
else
  hide() { "$@"; }
  echo "note: no mount namespace here; the source tree stays visible (origins are still checked)"
fi
out=$(hide "$b" list scenes) || { echo "FAIL list scenes"; exit 1; }
[ "$(echo "$out" | wc -l)" -ge 9 ] || { echo "FAIL list scenes: $out"; exit 1; }
echo "$out" | grep -v "\[installed: $share/scenes/" && { echo "FAIL a scene not from the installed folder"; exit 1; }
echo "$out" | grep -q "$src" && { echo "FAIL the installed binary lists the source tree"; exit 1; }
hide "$b" run "$share/configs/default.yaml" -o "$tmp/elsewhere/out" --no-cache >"$tmp/run.out" 2>"$tmp/run.err" ||
  { echo "FAIL installed run:"; cat "$tmp/run.out" "$tmp/run.err"; exit 1; }
grep -q "^default: 6 cell(s) computed, 0 already stored" "$tmp/run.out" || { echo "FAIL run summary:"; cat "$tmp/run.out"; exit 1; }
grep -q "^written to $tmp/elsewhere/out/default/" "$tmp/run.out" || { echo "FAIL no 'written to'"; exit 1; }
# the overlays went through the installed sheet module
ls out/default/overlays/*.png >/dev/null 2>&1 || { echo "FAIL no overlay written by the installed binary"; exit 1; }
[ "$(tail -n +2 out/default/figures.csv | cut -d, -f1-6 | sort -u | wc -l)" -eq 6 ] || { echo "FAIL figures.csv"; exit 1; }
# a config elsewhere that names a scene of its own folder, and SHADOWLAB_SCENES in front of the installed folder
printf 'name: mine\nbase: primitives\nviewpoints:\n  - {name: side, position: [35, 50, -43], direction: [-1, -1.2, 1], fov: 60, near: 20, far: 250}\n  - {name: with, position: [35, 50, -43], direction: [-1, -1.2, 1], fov: 60, near: 20, far: 250}\n' >"$tmp/elsewhere/mine.yaml"
mkdir -p "$tmp/extra"
printf 'name: extra\ndescription: "an extra scene"\nbase: primitives\nviewpoints:\n  - {name: side, position: [35, 50, -43], direction: [-1, -1.2, 1], fov: 60, near: 20, far: 250}\n  - {name: with, position: [35, 50, -43], direction: [-1, -1.2, 1], fov: 60, near: 20, far: 250}\n' >"$tmp/extra/extra.yaml"
printf 'name: own\nscenes: [{scene: mine, viewpoints: [side]}, {scene: extra, viewpoints: [with]}]\nmap_sizes: [256]\nmethods: [{method: nsm}]\n' >"$tmp/elsewhere/own.yaml"
SHADOWLAB_SCENES=$tmp/extra hide "$b" validate own.yaml >"$tmp/v.out" 2>&1 || { echo "FAIL search path:"; cat "$tmp/v.out"; exit 1; }
grep -q "ok: 2 scene(s), 2 cell(s)" "$tmp/v.out" || { echo "FAIL search path: $(cat "$tmp/v.out")"; exit 1; }
hide "$b" validate own.yaml >"$tmp/v.out" 2>&1 && { echo "FAIL 'extra' found without SHADOWLAB_SCENES"; exit 1; }
grep -q "unknown scene 'extra'" "$tmp/v.out" || { echo "FAIL: $(cat "$tmp/v.out")"; exit 1; }
# the report of a study of both theses' methods reads the theses' numbers
# from <prefix>/share/shadowlab/theses (report/theses.h): the Morais section
# reads its two files whatever the views; the fidelity section, which reads
# Moderno's file first, is left out (nothing at the thesis's 1024 x 1024)
for f in moderno-2011.csv morais-2015.csv morais-2015-times.csv; do
  [ -s "$share/theses/$f" ] || { echo "FAIL not installed: $share/theses/$f"; exit 1; }
done
if command -v gnuplot >/dev/null; then
  printf 'name: theses\nscenes: [{scene: primitives, viewpoints: [side]}]\nviewports: [{width: 64, height: 64}]\nmap_sizes: [256]\ncontours: [2]\nmethods: [{method: nsm}, {method: texel}, {method: csm}]\nrepetitions: {warmup: 0, runs: 1}\n' >"$tmp/elsewhere/theses.yaml"
  hide "$b" run theses.yaml -o "$tmp/elsewhere/th" --no-cache -q >"$tmp/th.out" 2>&1 ||
    { echo "FAIL installed run of theses.yaml:"; cat "$tmp/th.out"; exit 1; }
  hide "$b" report "$tmp/elsewhere/th/shadowlab.db" -o "$tmp/elsewhere/threp" >"$tmp/th.out" 2>&1 ||
    { echo "FAIL installed report:"; cat "$tmp/th.out"; exit 1; }
  grep -q "^### theses: tables in Morais 2015's layout" "$tmp/elsewhere/threp/report.md" &&
    ! grep -q "not measured |" "$tmp/elsewhere/threp/report.md" ||
    { echo "FAIL the installed report lacks the theses' sections or has a fidelity table of nothing measured"; exit 1; }
  # SHADOWLAB_THESES in front of the installed folder: an empty one stops the report (exit 2, the file named)
  SHADOWLAB_THESES=$tmp/empty hide "$b" report "$tmp/elsewhere/th/shadowlab.db" -o "$tmp/elsewhere/threp2" \
    >"$tmp/th.out" 2>&1; rc=$?
  [ "$rc" -eq 2 ] && grep -q "$tmp/empty/moderno-2011.csv: cannot open" "$tmp/th.out" ||
    { echo "FAIL SHADOWLAB_THESES=empty: exit $rc:"; cat "$tmp/th.out"; exit 1; }
else
  echo "note: no gnuplot here; the installed report is not run"
fi
echo "1 passed, 0 failed"
