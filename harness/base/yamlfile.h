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
 * bytes that are not UTF-8 text (named with their line) and for a file over
 * max_bytes (refused before it is read, so a huge file costs nothing). On
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

/* Line of a dotted key path, 0 if unknown. */
int sl_yaml_line(const struct sl_yaml_pos *pos, const char *path);

/* Fail with `kind`, naming file, the key's line and the key. */
enum sl_err sl_yaml_bad(struct sl_diag *d, enum sl_err kind, const char *file,
                        const struct sl_yaml_pos *pos, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 6, 7)));

#endif
