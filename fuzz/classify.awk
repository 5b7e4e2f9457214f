# fuzz/classify.awk — read one sanitizer report (ASan, UBSan, LSan, or a
# libFuzzer timeout/out-of-memory stack) and print one line: "assimp" when
# every stack that matters first reaches code of libassimp, else
# "ours <frame>" (shadowlab's code, or a frame it cannot place: that fails).
# Frames of the sanitizers (their interceptors of libc's string functions
# too) and libFuzzer are skipped, and so are the system
# libraries assimp calls (libc, libm, libgcc_s, libstdc++, libz): the first
# frame left decides. Which stacks matter: the first of an ASan report (the
# others say where the memory came from), each of a leak report.
function skip(l) {
  if (l ~ / in (__asan|__lsan|__ubsan|__sanitizer|__interceptor_|__cxa_|__gxx_|_Unwind_|__libc_|__GI_|__restore_rt|fuzzer::|std::terminate|abort|raise|gsignal)/) return 1
  # the allocator's entry points ("operator new[](unsigned long)" too): the
  # caller asked for the memory, the caller decides
  if (l ~ / in (malloc|calloc|realloc|free|posix_memalign|memalign|aligned_alloc|valloc|operator new(\[\])?|operator delete(\[\])?)([ (<]|$)/) return 1
  # ASan's interceptors of the libc string and memory functions show as the
  # bare libc name in the fuzz binary ("in strncmp (build-fuzz/...+0x...)",
  # no source line): the sanitizer's frame, the caller decides
  if (l ~ / in (strn?cmp|strn?casecmp|strn?len|strn?cpy|stpn?cpy|strn?cat|strr?chr|strstr|strcasestr|strspn|strcspn|strpbrk|strtok|strn?dup|memcmp|bcmp|memcpy|memmove|memset|memr?chr|memmem|ato[ifl]l?|strto[a-z]+) \(/ && l !~ /\.[ch](pp)?:[0-9]+/) return 1
  if (l ~ /compiler-rt|\/lib\/clang\/|\/sanitizer_common\/|\/asan\/|\/ubsan\/|\/fuzzer\/Fuzzer/) return 1
  if (l ~ /\((\/usr)?\/lib[^ ]*\/(libc\.so|libc-|libm\.so|libm-|libgcc_s|libstdc\+\+|libz\.so|ld-linux|libpthread)/) return 1
  if (l ~ /<unknown module>/) return 1
  if (l ~ / [a-z_-]+\/\.\/[a-z_-]+\/[^ ]+\.[ch]:[0-9]+/) return 1   # glibc with its debug info (libio/./libio/genops.c)
  return 0
}
BEGIN { verdict = ""; nstack = 0; inframe = 0; decided = 0 }
/LeakSanitizer/ { leak = 1 }
# ASan's allocator finds a freed chunk's header overwritten when it recycles
# it from quarantine: a write to freed memory that ASan did not see, so by
# code it does not instrument. All of shadowlab's code is instrumented in
# the fuzz build (its libc calls go through ASan's interceptors), so the
# writer is libassimp or what it calls; the stack only says who freed next.
/AddressSanitizer: CHECK failed: asan_allocator\.cpp:[0-9]+ "\(\(old_chunk_state\)\) == \(\(CHUNK_QUARANTINE\)\)"/ { quarantine = 1 }
/runtime error:/ && verdict == "" { verdict = "ours " $0 }
/^ *#[0-9]+ 0x/ {
  if (!inframe) { nstack++; decided = 0 }
  inframe = 1
  if (decided || (nstack > 1 && !leak)) next
  if (skip($0)) next
  decided = 1
  sub(/^ */, "")
  if ($0 ~ /libassimp/) { nassimp++ } else if (verdict == "") { verdict = "ours " $0 }
  next
}
{ inframe = 0 }
END {
  if (quarantine && verdict !~ /runtime error:/) print "assimp"
  else if (verdict != "") print verdict
  else if (nassimp > 0) print "assimp"
  else print "ours (no stack that names a module)"
}
