/*
 * extras.h — the keys of a config's method entries that the config's
 * schema cannot hold: a technique package's own parameters (any name the
 * package declares, technique.h) and sweeps (a knob or a parameter given as
 * a list: `kernel: [1, 3, 5]`, one label per value).
 *
 * They are taken out of the config's text before libcyaml reads it: each
 * such key and its value are overwritten with blanks (newlines kept, so
 * every other key keeps its line, and a flow mapping's comma goes with
 * its entry), and handed back with their lines, the values as written.
 * Which keys are taken is the caller's choice (a callback that knows the
 * method names and knobs): everything else reaches the schema unchanged,
 * so an unknown key of a C method is refused exactly as before.
 *
 * Owns: nothing beyond the text it edits. Does not: check a value (the
 * config does, against the knob's kind or the package's declaration).
 */
#ifndef SL_EXTRAS_H
#define SL_EXTRAS_H
#include <stddef.h>
#include "sl_error.h"

#define SL_EXTRA_KEYS   16   /* taken keys per method entry */
#define SL_EXTRA_VALUES 16   /* values of one list */

struct sl_extra_key {
    char key[32];
    int  line;                          /* 1-based, of the key */
    int  is_list;                       /* written as a sequence (a sweep) */
    int  nvalues;                       /* 1 for a scalar */
    char value[SL_EXTRA_VALUES][64];    /* each as written (plain, quoted text unquoted) */
};

struct sl_method_extras {
    char method[64];                    /* the entry's `method:` ("" if none) */
    int  n;
    struct sl_extra_key k[SL_EXTRA_KEYS];
};

/* Whether key `key` of an entry naming `method` is to be taken out (1) or
 * left to the schema (0); is_list: its value is a sequence. */
typedef int (*sl_extras_take_fn)(const char *method, const char *key, int is_list, void *user);

/* Over the top-level `methods:` sequence of the YAML in text[0..len):
 * entry i's taken keys into out[i] (max entries; out zeroed first),
 * blanked in the text. A text that is not YAML, or has no such sequence,
 * is left alone (the loader names its own error). Errors (SL_E_CONFIG,
 * naming `file`, the line and methods[i].key): a taken key whose value is
 * a mapping, a list nested or empty or longer than SL_EXTRA_VALUES, a
 * value longer than 63 bytes, more than SL_EXTRA_KEYS taken keys. */
enum sl_err sl_extras_take(unsigned char *text, size_t len, sl_extras_take_fn take, void *user,
                           struct sl_method_extras *out, int max, const char *file, struct sl_diag *d);

#endif
