/*
 * yamlfile.h — YAML files read with libcyaml against a schema, with errors
 * that name file, line and key.
 *
 * libcyaml's own backtrace gives the line of type errors; a position index
 * built with libyaml (dotted key path -> line, e.g. "methods[1].bias") gives
 * it for unknown keys and for values that fail the caller's own checks
 * (sl_yaml_bad). Shared by configs and scene files.
 */
#ifndef SL_YAMLFILE_H
#define SL_YAMLFILE_H
#include <stddef.h>
#include <cyaml/cyaml.h>
#include "sl_error.h"

struct sl_yaml_pos;

/* Load path into *out. Errors: SL_E_IO (unreadable), `kind` (the file's own
 * error id, e.g. SL_E_CONFIG or SL_E_SCENE) for YAML and schema errors, for
 * bytes that are not UTF-8 text (named with their line), for a file over
 * max_bytes (refused before it is read, so a huge file costs nothing), for
 * nesting past SL_YAML_MAX_DEPTH and for a value that is not a whole
 * number where the schema wants an integer ("7.9", "1e3": libcyaml alone
 * would read 7 and 1), and for an alias (*name: refused at its line, never
 * expanded, since each alias copies its anchor's node and a few bytes can
 * stand for gigabytes). Only a regular file is opened (sl_open_regular). On
 * success *pos is the position index (free both with sl_yaml_free). */
enum sl_err sl_yaml_load(const char *path, const cyaml_schema_value_t *schema, void **out,
                         struct sl_yaml_pos **pos, size_t max_bytes, enum sl_err kind, struct sl_diag *d);
/* The same, with the checked text handed to edit() before it is parsed
 * (the command line's -D overrides): edit may replace *text (malloc'd; the
 * old one freed by it) and *len, or fail with its own diag. */
typedef enum sl_err (*sl_yaml_edit_fn)(unsigned char **text, size_t *len, void *user, struct sl_diag *d);
enum sl_err sl_yaml_load_edited(const char *path, const cyaml_schema_value_t *schema, void **out,
                                struct sl_yaml_pos **pos, size_t max_bytes, enum sl_err kind,
                                sl_yaml_edit_fn edit, void *edit_user, struct sl_diag *d);
void        sl_yaml_free(const cyaml_schema_value_t *schema, void *data, struct sl_yaml_pos *pos);

/* Nesting: a file nested deeper than this (mappings and sequences, flow
 * or block) is refused with the line where it goes past it, before it is
 * parsed further: libyaml's cost grows with the square of the nesting, and
 * libyaml's emitter (used for -D) recurses once per level. No schema of
 * shadowlab nests past 6. */
#define SL_YAML_MAX_DEPTH 64
/* The nesting of text: the deepest level seen, stopping at the first one
 * past max (its line in *line, else 0, and in key, if not NULL, the
 * top-level key it is under, else ""); -1 if libyaml cannot start. */
int sl_yaml_depth(const unsigned char *text, size_t len, int max, int *line, char *key, size_t nkey);

/* Line of a dotted key path, 0 if unknown. */
int sl_yaml_line(const struct sl_yaml_pos *pos, const char *path);

/* Fail with `kind`, naming file, the key's line and the key. */
enum sl_err sl_yaml_bad(struct sl_diag *d, enum sl_err kind, const char *file,
                        const struct sl_yaml_pos *pos, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 6, 7)));

/* A path a file names (key: a scene, a base:, a model) that is there but
 * not a regular file (a FIFO, a device, a folder) fails with `kind`,
 * naming file, the key's line and the key, before anything opens it. */
enum sl_err sl_yaml_ref_check(struct sl_diag *d, enum sl_err kind, const char *file,
                              const struct sl_yaml_pos *ix, const char *key, const char *target);

#endif
