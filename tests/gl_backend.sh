#!/usr/bin/env bash
# cli::gl_backend — choosing the GL backend fails clearly: --gl nonsense is
# usage (2, with the usage text); a bad SHADOWLAB_EGL_DEVICE names the
# variable (2); a backend not built says so (2); an unknown 'gl:' in a config
# is a config error (2).
set -u
bin=${1:?usage: gl_backend.sh path/to/shadowlab BACKENDS}
backends=${2:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
expect() { # expect CODE PATTERN -- command...
    local code=$1 pat=$2; shift 3
    "$@" >"$tmp/out" 2>&1
    local rc=$?
    if [ "$rc" != "$code" ] || ! grep -q -- "$pat" "$tmp/out"; then
        echo "FAIL: $* -> rc $rc (want $code), output:"; cat "$tmp/out"; fails=1
    else
        echo "ok: $* -> $rc: $(head -1 "$tmp/out")"
    fi
}
expect 2 "usage: shadowlab run" -- "$bin" run configs/ci.yaml --gl nonsense --out "$tmp/o"
expect 2 "usage: shadowlab run" -- "$bin" run configs/ci.yaml --gl --out "$tmp/o"
sed 's/^name: .*/&\ngl: vulkan/' configs/ci.yaml >"$tmp/bad.yaml"
expect 2 "gl 'vulkan': osmesa or egl" -- "$bin" validate "$tmp/bad.yaml"
case ";$backends;" in
*";egl;"*)
    expect 2 "SHADOWLAB_EGL_DEVICE.*no EGL device 99" -- env SHADOWLAB_EGL_DEVICE=99 "$bin" run configs/ci.yaml --gl egl --out "$tmp/o"
    expect 2 "SHADOWLAB_EGL_DEVICE.*'x' is not an EGL device number" -- env SHADOWLAB_EGL_DEVICE=x "$bin" run configs/ci.yaml --gl egl --out "$tmp/o"
    ;;
*)  expect 2 "built without the egl backend" -- "$bin" run configs/ci.yaml --gl egl --out "$tmp/o" ;;
esac
case ";$backends;" in
*";osmesa;"*) ;;
*)  expect 2 "built without the osmesa backend" -- "$bin" run configs/ci.yaml --gl osmesa --out "$tmp/o" ;;
esac
exit $fails
