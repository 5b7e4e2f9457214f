/*
 * dlib.c — a library's entry points through dlopen, once (dlib.h).
 * Loading is serialised by one mutex: callers may race to the first use.
 */
#define _GNU_SOURCE   /* RTLD_NODELETE */
#include "dlib.h"
#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

static pthread_mutex_t load_lock = PTHREAD_MUTEX_INITIALIZER;

int sl_dl_table(int *loaded, const char *const *names, const char *const *syms, int nsyms, void *table,
                char *why, size_t n)
{
    pthread_mutex_lock(&load_lock);
    int rc = 0;
    if (!*loaded) {
        void *h = NULL;
        const char *err = "not found";
        for (int i = 0; names[i] && !h; i++)
            if (!(h = dlopen(names[i], RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE)))
                err = dlerror();
        if (!h) {
            snprintf(why, n, "cannot load %s: %s", names[0], err);
            rc = -1;
        }
        for (int i = 0; i < nsyms && rc == 0; i++) {
            void *f = dlsym(h, syms[i]);
            if (!f) {
                snprintf(why, n, "%s lacks %s", names[0], syms[i]);
                rc = -1;
            } else {
                memcpy((char *)table + (size_t)i * sizeof f, &f, sizeof f);
            }
        }
        *loaded = rc == 0;
    }
    pthread_mutex_unlock(&load_lock);
    return rc;
}

