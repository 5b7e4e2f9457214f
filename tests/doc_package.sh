#!/usr/bin/env bash
# doc::package_* — what a lab installs and cites agrees with the binary
# (issue 37, item 6). One case per argument:
#   version     `shadowlab --version` prints "shadowlab X.Y.Z (git SHA)"; X.Y.Z is
#               CMakeLists.txt's project(VERSION), CITATION.cff's version and the
#               man page's; LICENSE is MIT; CITATION.cff is CFF 1.2.0 with its keys
#   man         doc/shadowlab.1 is what `shadowlab help --man` writes (from usage.c's
#               table and help texts) byte for byte; groff reads it without a warning;
#               it has every verb and the environment, --jobs, --cache and config sections
#   completion  scripts/shadowlab.bash-completion is what `shadowlab help --bash-completion`
#               writes; every long option a verb's parser accepts (its struct option
#               table in harness/cli/, submit's in harness/cluster/submit.c) is in the
#               verb's --help and completes; verbs, bench stages, --scene, --summary,
#               --figures, -D and show technique complete
#   setup       scripts/setup.sh: `run` installs no test-only tool (Slurm, munge,
#               Chromium, clang, TeX Live, the sqlite3 shell), `test` installs them;
#               a bad mode exits 2 before installing anything; the guide's cmake
#               recipe names what CMake looks for
# Usage: doc_package.sh SHADOWLAB_BINARY CASE   (run from the source tree)
set -u
bin=${1:?usage: doc_package.sh path/to/shadowlab CASE}
case_=${2:?usage: doc_package.sh path/to/shadowlab CASE}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0; passes=0
fail() { echo "FAIL $*"; fails=$((fails + 1)); }
ok() { passes=$((passes + 1)); }

cmake_version() { sed -n 's/^project(shadowlab VERSION \([0-9][0-9.]*\) .*/\1/p' CMakeLists.txt; }

case $case_ in
version)
  v=$("$bin" --version | head -n 1)
  echo "$v" | grep -Eq '^shadowlab [0-9]+\.[0-9]+\.[0-9]+ \(git ([0-9a-f]{7,40}(-dirty)?|unknown)\)$' && ok ||
    fail "--version prints '$v', not 'shadowlab X.Y.Z (git SHA)'"
  bv=$(echo "$v" | awk '{ print $2 }')
  cv=$(cmake_version)
  [ -n "$cv" ] && [ "$bv" = "$cv" ] && ok || fail "the binary says $bv, CMakeLists.txt's project(VERSION) '$cv'"
  ffv=$(sed -n 's/^version: *"\{0,1\}\([^"]*\)"\{0,1\} *$/\1/p' CITATION.cff)
  [ "$ffv" = "$cv" ] && ok || fail "CITATION.cff's version '$ffv' is not CMakeLists.txt's '$cv'"
  grep -q '^cff-version: 1\.2\.0$' CITATION.cff && ok || fail "CITATION.cff: no 'cff-version: 1.2.0'"
  grep -q '^license: MIT$' CITATION.cff && ok || fail "CITATION.cff: no 'license: MIT'"
  # the keys CFF 1.2.0 requires, the authors entity, and the references' types
  if python3 -c 'import yaml' 2>/dev/null; then
    python3 - <<'PY' && ok || fail "CITATION.cff is not valid CFF 1.2.0 (above)"
import sys, yaml
d = yaml.safe_load(open("CITATION.cff", encoding="utf-8"))
bad = []
for k in ("cff-version", "message", "title", "authors"):
    if k not in d:
        bad.append("missing required key " + k)
known = {"abstract", "authors", "cff-version", "commit", "contact", "date-released", "doi", "identifiers",
         "keywords", "license", "license-url", "message", "preferred-citation", "references", "repository",
         "repository-artifact", "repository-code", "title", "type", "url", "version"}
bad += ["unknown key " + k for k in d if k not in known]
if d.get("type") not in (None, "software", "dataset"):
    bad.append("type must be software or dataset")
if d.get("authors") != [{"name": "the shadowlab authors"}]:
    bad.append("authors must be the entity 'the shadowlab authors'")
if not isinstance(d.get("version"), str):
    bad.append("version must be a string (quoted)")
for r in d.get("references", []):
    for k in ("type", "title", "authors"):
        if k not in r:
            bad.append("a reference lacks " + k + ": " + str(r.get("title")))
    if not isinstance(r.get("year"), int):
        bad.append("a reference's year is not a number: " + str(r.get("title")))
    for a in r.get("authors", []):
        if not ("family-names" in a or "name" in a):
            bad.append("an author of " + r["title"] + " has neither family-names nor name")
for b in bad:
    print("  " + b)
sys.exit(1 if bad else 0)
PY
  fi
  head -n 1 LICENSE | grep -q '^MIT License$' && ok || fail "LICENSE is not the MIT licence"
  grep -q '^Copyright (c) 2026 the shadowlab authors$' LICENSE && ok || fail "LICENSE: no copyright line"
  # the man page carries the same version (it is written by the binary: doc::package_man)
  grep -q "^\.TH SHADOWLAB 1 .*\"shadowlab $cv\"" doc/shadowlab.1 && ok ||
    fail "doc/shadowlab.1's .TH line does not name shadowlab $cv"
  ;;
man)
  "$bin" help --man >"$tmp/shadowlab.1" && ok || fail "help --man failed"
  if cmp -s "$tmp/shadowlab.1" doc/shadowlab.1; then ok; else
    fail "doc/shadowlab.1 is not what the binary writes: run 'build/shadowlab help --man > doc/shadowlab.1' (edit harness/cli/usage.c, not the page)"
    diff -u doc/shadowlab.1 "$tmp/shadowlab.1" | head -n 40
  fi
  if command -v groff >/dev/null; then
    w=$(groff -man -ww -z -K utf8 "$tmp/shadowlab.1" 2>&1)
    [ -z "$w" ] && ok || fail "groff warns: $w"
  fi
  for verb in $("$bin" --help | awk 'NR > 1 && $1 !~ /^-|,$/ { print $1 }' | sort -u); do
    [ "$verb" = help ] && continue
    grep -q "^\.SS $verb\( \|\$\|,\)" "$tmp/shadowlab.1" && ok || fail "the man page has no section for '$verb'"
  done
  for want in SHADOWLAB_GL SHADOWLAB_SCENES SHADOWLAB_TECHNIQUES '\\-\\-jobs N' '\\-\\-cache DIR' \
              '^\.SH CONFIGURATION' 'doc/guide\.md' '^\.SH ENVIRONMENT' '^\.SH EXIT STATUS'; do
    grep -q -- "$want" "$tmp/shadowlab.1" && ok || fail "the man page lacks $want"
  done
  # the figures a table and a pivot take, the fractional ones and the count of values not finite among them
  for f in leaking over_dark nonfinite soft_mae; do
    "$bin" help table | grep -qw -- "$f" && ok || fail "'shadowlab help table' does not name the figure $f"
    grep -qw -- "$f" "$tmp/shadowlab.1" && ok || fail "the man page does not name the figure $f"
  done
  ;;
config)
  # doc/config.md is what the binary writes from the parser's schema, and it
  # holds every top-level key of CONFIG_KEYS and every built-in method's parameters
  "$bin" help --config >"$tmp/config.md" && ok || fail "help --config failed (a key without its text?)"
  if cmp -s "$tmp/config.md" doc/config.md; then ok; else
    fail "doc/config.md is not what the binary writes: run 'build/shadowlab help --config > doc/config.md' (edit key_docs in harness/plan/config.c)"
    diff -u doc/config.md "$tmp/config.md" | head -n 20
  fi
  keys=$(sed -n '/^#define CONFIG_KEYS(X)/,/^$/p' harness/plan/config.c | grep -oE '^ *X\([a-z_]+' | sed 's/.*(//')
  [ "$(echo "$keys" | wc -l)" -ge 10 ] && ok || fail "CONFIG_KEYS not found in config.c"
  for k in $keys; do grep -q "^| \`$k\` |" "$tmp/config.md" && ok || fail "doc/config.md lacks the key $k"; done
  # every built-in method's declared parameters (their SL_PARAM_*_DECL lines,
  # by name) have a row of their method's table
  params=$(grep -ohE 'SL_PARAM_[A-Z]+_DECL\("[a-z_]+"' methods/*.c methods/selfshadow.h | sed 's/.*("//; s/"//' | sort -u)
  [ "$(echo "$params" | wc -l)" -ge 10 ] && ok || fail "no method parameter declarations found in methods/"
  for k in $params; do grep -qE "^\| \`[a-z_0-9]+\` \| \`$k\` \|" "$tmp/config.md" && ok || fail "doc/config.md lacks the method parameter $k"; done
  # the man page carries the same keys
  "$bin" help --man | grep -q '^\.B outputs\.aliasing$' && ok || fail "the man page lacks the config keys"
  ;;
completion)
  comp=scripts/shadowlab.bash-completion
  "$bin" help --bash-completion >"$tmp/comp" && ok || fail "help --bash-completion failed"
  if cmp -s "$tmp/comp" "$comp"; then ok; else
    fail "$comp is not what the binary writes: run 'build/shadowlab help --bash-completion > $comp' (edit harness/cli/usage.c, not the script)"
    diff -u "$comp" "$tmp/comp" | head -n 40
  fi
  bash -n "$comp" && ok || fail "$comp is not valid bash"
  # the completion as bash runs it: complete WORDS... (the last one is completed);
  # `shadowlab` on PATH is the binary under test (scene, label, key and technique lists)
  mkdir -p "$tmp/bin"; ln -s "$(readlink -f "$bin")" "$tmp/bin/shadowlab"
  complete_() {
    PATH="$tmp/bin:$PATH" bash -c 'source "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); _shadowlab
      printf "%s\n" "${COMPREPLY[@]}"' _ "$comp" "$@"
  }
  has() { # has WORD COMPLETION-WORDS...: the completion offers WORD
    local w=$1; shift
    complete_ "$@" | grep -qxF -- "$w" && ok || fail "completing '$*' does not offer '$w'"
  }
  # the options each verb's parser accepts, read from its source
  opts_of() { grep -oE '\{"[a-z][a-z-]*", *(no|required|optional)_argument' "$@" | sed 's/{"\([a-z-]*\)".*/--\1/' | sort -u; }
  for pair in run:run validate:validate table:table report:report check:check bench:bench \
              preview:preview "store:merge verify" list:list "list:show"; do
    file=harness/cli/${pair%%:*}.c verbs=${pair#*:}
    for o in $(opts_of "$file"); do
      [ "$o" = --help ] && continue
      found=0
      for v in $verbs; do "$bin" help "$v" | grep -q -- "$o\b" && found=1; done
      [ $found = 1 ] && ok || fail "$o (accepted by $file) is not in 'shadowlab help $verbs'"
      for v in $verbs; do
        "$bin" help "$v" | grep -q -- "$o\b" || continue
        has "$o" shadowlab "$v" "${o:0:3}"
      done
    done
  done
  for o in $(grep -oE 'strcmp\(a, "--[a-z-]+"\)' harness/cluster/submit.c | sed 's/.*"\(--[a-z-]*\)".*/\1/' | sort -u); do
    "$bin" help submit | grep -q -- "$o\b" && ok || fail "$o (accepted by submit) is not in 'shadowlab help submit'"
    has "$o" shadowlab submit "${o:0:3}"
  done
  # every verb, and help's
  for verb in $("$bin" --help | awk 'NR > 1 && $1 !~ /^-|,$/ { print $1 }' | sort -u); do
    has "$verb" shadowlab "${verb:0:2}"
    [ "$verb" = help ] || has "$verb" shadowlab help "${verb:0:2}"
  done
  has --man shadowlab help --m
  # every bench stage (bench.h's list) after --only, also after a comma
  for st in $(sed -n 's/^ *X([A-Z]*, *"\([a-z]*\)").*/\1/p' harness/bench/bench.h); do
    has "$st" shadowlab bench --only "${st:0:2}"
    "$bin" help bench | grep -qE "^    $st " && ok || fail "bench's help does not describe stage $st"
  done
  has truth,layers shadowlab bench --only truth,la
  # values: the scenes, figures, config keys, techniques, listed values
  has primitives shadowlab run x.yaml --scene pri
  has primitives shadowlab table x.db --scene pri
  has wrong shadowlab table x.db --summary wro
  has wrong_caught shadowlab table x.db --summary wrong_c
  has pfl,wrong shadowlab table x.db --figures pfl,wro
  has leaking shadowlab table x.db --figures leak
  has over_dark shadowlab table x.db --figure over
  has nonfinite shadowlab table x.db --figure nonf
  has ms_method shadowlab table x.db --figure ms_m
  has map_sizes= shadowlab run configs/default.yaml -D map_s
  has methods= shadowlab validate configs/default.yaml --define meth
  has pcf shadowlab show technique pc
  has technique shadowlab show te
  has method shadowlab show me
  has soft_mc shadowlab show method soft
  has latex shadowlab table x.db --format la
  has md shadowlab check x.db --format m
  has egl shadowlab run x.yaml --gl e
  has contours shadowlab table x.db --region con
  has scenes shadowlab list sc
  has configs/default.yaml shadowlab run configs/def
  ;;
setup)
  bash -n scripts/setup.sh && ok || fail "scripts/setup.sh is not valid bash"
  eval "$(sed -n '/^RUN_PACKAGES=(/,/^)/p; /^TEST_PACKAGES=(/,/^)/p' scripts/setup.sh)"
  [ ${#RUN_PACKAGES[@]} -gt 10 ] && ok || fail "no RUN_PACKAGES list in scripts/setup.sh"
  for p in slurm-wlm munge chromium clang libclang-rt-14-dev texlive-latex-recommended lmodern sqlite3 libcmocka-dev; do
    printf '%s\n' "${RUN_PACKAGES[@]}" | grep -qx -- "$p" && fail "setup.sh run installs $p (tests only)" || ok
    printf '%s\n' "${TEST_PACKAGES[@]}" | grep -qx -- "$p" && ok || fail "setup.sh test does not install $p"
  done
  for p in libembree-dev libosmesa6-dev libegl-dev libopenimageio-dev libcyaml-dev libsqlite3-dev gnuplot-nox \
           libunistring-dev glslang-dev; do
    printf '%s\n' "${RUN_PACKAGES[@]}" | grep -qx -- "$p" && ok || fail "setup.sh run does not install $p"
  done
  out=$(bash scripts/setup.sh bogus 2>&1); rc=$?
  [ $rc -eq 2 ] && ! echo "$out" | grep -q "installing" && ok || fail "setup.sh bogus: rc $rc, '$out'"
  # the guide's recipe names every pkg-config module and CMake package CMakeLists.txt asks for
  for m in $(sed -n 's/^pkg_check_modules([A-Z]* \(REQUIRED \)\{0,1\}IMPORTED_TARGET \([a-z0-9.-]*\)).*/\2/p' CMakeLists.txt) \
           $(sed -n 's/^find_package(\([A-Za-z]*\) .*/\1/p' CMakeLists.txt | grep -v -e PkgConfig -e OpenGL -e OpenMP); do
    grep -q "\`$m\`" doc/guide.md && ok || fail "doc/guide.md's cmake recipe does not name $m"
  done
  ;;
*) echo "doc_package.sh: unknown case $case_" >&2; exit 2 ;;
esac
echo "doc::package_$case_: $passes passed, $fails failed"
[ $fails -eq 0 ]
