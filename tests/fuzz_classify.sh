#!/usr/bin/env bash
# fuzz::classify — fuzz/classify.awk on sanitizer reports: ASan's libc
# interceptors (a bare "strncmp" in the fuzz binary) and the allocator's
# entry points (operator new[]) are skipped like the sanitizers' own
# frames, so the caller decides: assimp's code is assimp's,
# shadowlab's code (or a frame it cannot place) is ours and fails the run.
set -u
awkf=${1:?usage: fuzz_classify.sh path/to/fuzz/classify.awk}
fail() { echo "FAIL $*"; exit 1; }
report() {  # the frame after the interceptor
  cat <<R
==1==ERROR: AddressSanitizer: heap-buffer-overflow on address 0x6030003be1fa at pc 0x1 bp 0x2 sp 0x3
READ of size 1 at 0x6030003be1fa thread T0
    #0 0x561c893b5fbc in strncmp (/tmp/x/build-fuzz/fuzz/fuzz_mesh_gltf+0x9efbc) (BuildId: 9d63)
$1
    #2 0x561c89472835 in read_scene /tmp/x/harness/scene/meshio.c:526:39
    #3 0x561c8945cca5 in LLVMFuzzerTestOneInput /tmp/x/fuzz/fuzz_mesh.c:59:15

0x6030003be1fa is located 1 bytes to the right of 25-byte region [0x6030003be1e0,0x6030003be1f9)
allocated by thread T0 here:
    #0 0x561c89421d5e in __interceptor_malloc (/tmp/x/build-fuzz/fuzz/fuzz_mesh_gltf+0x10ad5e) (BuildId: 9d63)
R
}
v=$(report '    #1 0x7f114f3477d2  (/lib/x86_64-linux-gnu/libassimp.so.5+0x7477d2) (BuildId: e482)' | awk -f "$awkf")
[ "$v" = assimp ] || fail "strncmp called by libassimp: '$v', want assimp"
v=$(report '    #1 0x561c89472000 in sl_mesh_name /tmp/x/harness/scene/meshio.c:100:5' | awk -f "$awkf")
case $v in ours*meshio.c:100*) ;; *) fail "strncmp called by shadowlab: '$v', want ours (meshio.c:100)" ;; esac
# an interceptor's name compiled from a source line is a function of ours, not skipped
v=$(printf '    #0 0x1 in strtok_r_own /tmp/x/harness/base/util.c:7:3\n' | awk -f "$awkf")
case $v in ours*util.c:7*) ;; *) fail "a frame of ours: '$v'" ;; esac
v=$(printf '    #0 0x1 in strncmp /tmp/x/harness/base/util.c:9:3\n    #1 0x2 (/lib/x86_64-linux-gnu/libassimp.so.5+0x1)\n' | awk -f "$awkf")
case $v in ours*util.c:9*) ;; *) fail "a strncmp with a source line of ours: '$v'" ;; esac
# an allocation assimp asks for and ASan cannot give (a length read from
# the file): operator new[] is the allocator's frame, libassimp decides
v=$(printf '%s\n' '==1==ERROR: AddressSanitizer: allocator is out of memory trying to allocate 0xfffffffe8 bytes' \
    '    #0 0x560c1f941bcd in operator new[](unsigned long) (/tmp/x/build-fuzz/fuzz/fuzz_mesh_gltf+0x147bcd) (BuildId: 8689)' \
    '    #1 0x7f727921b43f  (/lib/x86_64-linux-gnu/libassimp.so.5+0x61b43f) (BuildId: e482)' | awk -f "$awkf")
[ "$v" = assimp ] || fail "operator new[] called by libassimp: '$v', want assimp"
v=$(printf '%s\n' '    #0 0x1 in operator new[](unsigned long) (/tmp/x/build-fuzz/fuzz/fuzz_mesh_gltf+0x1)' \
    '    #1 0x2 in sl_mesh_load /tmp/x/harness/scene/meshio.c:300:9' | awk -f "$awkf")
case $v in ours*meshio.c:300*) ;; *) fail "operator new[] called by shadowlab: '$v', want ours (meshio.c:300)" ;; esac
echo "ok: 6 reports classified"
