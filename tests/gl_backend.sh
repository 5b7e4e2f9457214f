#!/usr/bin/env bash
# cli::gl_backend — choosing the GL backend fails clearly: --gl nonsense is
# usage (2, with the usage text); a bad SHADOWLAB_EGL_DEVICE names the
# variable (2); a backend not built says so (2); an unknown 'gl:' in a config
# is a config error (2); a bad SHADOWLAB_GL is usage (2), a good one chooses
# the backend below --gl and gl: (checked in run.yaml's provenance).
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
expect 2 "'gl': 'vulkan': one of default, osmesa, egl" -- "$bin" validate "$tmp/bad.yaml"
case ";$backends;" in
*";egl;"*)
    expect 2 "SHADOWLAB_EGL_DEVICE.*no EGL device 99" -- env SHADOWLAB_EGL_DEVICE=99 "$bin" run configs/ci.yaml --gl egl --out "$tmp/o"
    expect 2 "SHADOWLAB_EGL_DEVICE.*'x' is not an EGL device number" -- env SHADOWLAB_EGL_DEVICE=x "$bin" run configs/ci.yaml --gl egl --out "$tmp/o"
    ;;
*)  expect 2 "built without the egl backend" -- "$bin" run configs/ci.yaml --gl egl --out "$tmp/o" ;;
esac
# SHADOWLAB_GL: a bad value is refused (2) whatever else is asked
expect 2 "SHADOWLAB_GL.*'vulkan': osmesa or egl" -- env SHADOWLAB_GL=vulkan "$bin" run configs/ci.yaml --out "$tmp/o"
# the order of choice: --gl, then the config's gl:, then SHADOWLAB_GL, then
# the build's default; the backend used is the run's provenance (run.yaml)
cat >"$tmp/tiny.yaml" <<'EOF'
name: tiny
scenes: [{scene: primitives, viewpoints: [side]}]
viewports: [{width: 64, height: 64}]
map_sizes: [64]
contours: [2]
methods: [{label: nsm, method: nsm}]
outputs: {tables: false, overlays: false}
EOF
sed 's/^name: .*/&\ngl: osmesa/' "$tmp/tiny.yaml" >"$tmp/tiny_osmesa.yaml"
used() { # used ENV-VALUE CONFIG [ARGS...] -> the backend run.yaml names
    local env=$1 cfg=$2; shift 2
    rm -rf "$tmp/u"
    if ! env SHADOWLAB_GL="$env" "$bin" run "$cfg" --out "$tmp/u" "$@" >"$tmp/uout" 2>&1; then
        echo "run failed"; cat "$tmp/uout" >&2; return
    fi
    sed -n 's/^gl_backend: \([a-z]*\).*/\1/p' "$tmp/u/tiny/run.yaml"
}
want() { # want EXPECTED WHAT GOT
    if [ "$3" = "$1" ]; then echo "ok: $2 -> $3"; else echo "FAIL: $2 -> '$3' (want $1)"; fails=1; fi
}
if [[ ";$backends;" == *";egl;"* && ";$backends;" == *";osmesa;"* ]]; then
    want egl "SHADOWLAB_GL=egl" "$(used egl "$tmp/tiny.yaml")"
    want osmesa "SHADOWLAB_GL=osmesa" "$(used osmesa "$tmp/tiny.yaml")"
    want osmesa "SHADOWLAB_GL=egl, gl: osmesa" "$(used egl "$tmp/tiny_osmesa.yaml")"
    want egl "SHADOWLAB_GL=egl, gl: osmesa, --gl egl" "$(used egl "$tmp/tiny_osmesa.yaml" --gl egl)"
    want osmesa "SHADOWLAB_GL=egl, --gl osmesa" "$(used egl "$tmp/tiny.yaml" --gl osmesa)"
fi
case ";$backends;" in
*";osmesa;"*) ;;
*)  expect 2 "built without the osmesa backend" -- "$bin" run configs/ci.yaml --gl osmesa --out "$tmp/o" ;;
esac
exit $fails
