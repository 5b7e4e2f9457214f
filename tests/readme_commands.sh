#!/usr/bin/env bash
# doc::readme_commands — the README's commands work as written, and the
# documentation's links lead somewhere.
#
# - A ```yaml block whose first line is a comment naming a file
#   (`# study/bias.yaml`) is written to that file in a temporary folder.
# - Every ```sh block is run there, line by line, with bash -e, in order;
#   `build/shadowlab` is the binary under test and every `/tmp/` path is
#   moved into the temporary folder. A failing line fails the test, naming it.
# - A ```sh block that runs scripts/setup.sh (the Quick start: it installs
#   packages) is not run; the files its lines name must exist.
# - Every relative link ](path) in README.md and doc/*.md points at a file or
#   folder that exists (anchors and web links are not followed).
# Usage: readme_commands.sh SHADOWLAB_BINARY   (run from the source tree)
set -u
bin=$(readlink -f "$1")
root=$(pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/build"
ln -s "$bin" "$tmp/build/shadowlab"
fail=0

# split README.md into blocks: tmp/blocks/N.<lang>
mkdir -p "$tmp/blocks"
awk -v dir="$tmp/blocks" '
  /^```/ {
    if (inb) { inb = 0; close(f); next }
    lang = substr($0, 4); if (lang == "") lang = "none"
    n++; f = sprintf("%s/%03d.%s", dir, n, lang); inb = 1; printf "" > f; next
  }
  inb { print > f }
' README.md

nrun=0
for b in "$tmp"/blocks/*; do
  case "$b" in
    *.yaml)
      first=$(head -n 1 "$b")
      case "$first" in
        "# "*.yaml)
          name=${first#\# }
          mkdir -p "$tmp/$(dirname "$name")"
          cp "$b" "$tmp/$name"
          echo "wrote $name" ;;
      esac ;;
    *.sh)
      if grep -q 'scripts/setup.sh' "$b"; then
        for f in $(grep -oE '(scripts|configs|\.ci)/[A-Za-z0-9_./-]+' "$b" | sort -u); do
          if [ -e "$root/$f" ]; then echo "exists $f"; else echo "FAIL the Quick start names $f, which is not there"; fail=1; fi
        done
        continue
      fi
      while IFS= read -r line; do
        case "$line" in ''|'#'*) continue ;; esac
        cmd=${line//\/tmp\//$tmp\/}
        echo "+ $line"
        if ! (cd "$tmp" && bash -e -c "$cmd") >"$tmp/out.txt" 2>&1; then
          echo "FAIL README command: $line"
          sed 's/^/  | /' "$tmp/out.txt" | tail -n 20
          fail=1
        fi
        nrun=$((nrun + 1))
      done < "$b" ;;
  esac
done
if [ "$nrun" -lt 5 ]; then echo "FAIL only $nrun README commands found to run"; fail=1; fi

# relative links in the documentation
for doc in README.md doc/*.md; do
  dir=$(dirname "$doc")
  for target in $(grep -oE '\]\([^)# ]+(#[^) ]*)?\)' "$doc" | sed -E 's/^\]\(//; s/\)$//; s/#.*$//' | sort -u); do
    case "$target" in http://*|https://*|mailto:*|'') continue ;; esac
    if [ ! -e "$dir/$target" ]; then echo "FAIL $doc links to $target, which is not there"; fail=1; fi
  done
done

[ $fail -eq 0 ] && echo "ok: $nrun README commands ran; every relative link in README.md and doc/*.md resolves"
exit $fail
