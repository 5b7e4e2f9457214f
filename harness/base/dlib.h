/*
 * dlib.h — a library loaded with dlopen on first use instead of linked, for
 * the heavy ones a verb may not need (Mesa's GL backends, Embree): each
 * stage keeps a struct of function pointers, one per name, and calls them
 * under their usual names through macros (render/glload.h, truth/rtload.h).
 * A loaded library is never closed (RTLD_NODELETE): it stays until exit, as
 * a linked one would.
 */
#ifndef SL_DLIB_H
#define SL_DLIB_H
#include <stddef.h>

/* Once per *loaded flag: the first of names (NULL-terminated) that loads,
 * with each of syms[0..nsyms) resolved, in order, into table, a struct of
 * nsyms function pointers. 0 when loaded (now or before); otherwise -1 and
 * why holds "cannot load NAME: reason" or "NAME lacks SYMBOL". */
int sl_dl_table(int *loaded, const char *const *names, const char *const *syms, int nsyms, void *table,
                char *why, size_t n);

#endif
