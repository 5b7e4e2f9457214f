/*
 * yamlfile.h — YAML files bound to C structs by a libcyaml schema, with
 * errors that name file, line and key.
 *
 * A file is read once into a positioned node tree (ytree.h); the tree is
 * then bound to the caller's structs, driven by the caller's libcyaml
 * schema tables (cyaml_schema_value_t / cyaml_schema_field_t stay the
 * declarations of every file's keys, and `shadowlab help --config` is
 * written from them). libcyaml's loader is no longer used: it reads text
 * only and reports no node positions, so naming a key's line took a second
 * libyaml pass beside it, and a -D override meant writing the edited
 * config out as text and loading it again. The binding here walks the
 * tree, so each key's line is the node's own, -D values are edited into
 * the tree, and the memory it allocates is laid out as libcyaml's would be
 * (cyaml_free frees it: sl_yaml_free).
 *
 * Supported, as the schemas use them: mappings (fields required or
 * CYAML_FLAG_OPTIONAL, each at most once, an unknown key refused), sequences
 * (their count field, min and max entries), strings (min and max length),
 * INT, UINT, FLOAT and BOOL of any size, and CYAML_FLAG_POINTER on any of
 * them. Values are read as libcyaml read them (its error texts too), plus
 * one check libcyaml lacks: an integer field takes a whole number in
 * decimal digits ("7.9" and "1e3" are refused, libcyaml would read 7 and
 * 1). A mapping's value the caller took out of the tree (struct sl_ynode's
 * taken: a config's sweeps and package parameters) is not bound.
 *
 * Owns: the bound data (sl_yaml_free). Does not: check values beyond the
 * schema (the callers do, naming the key with sl_yaml_bad).
 */
#ifndef SL_YAMLFILE_H
#define SL_YAMLFILE_H
#include <stddef.h>
#include <cyaml/cyaml.h>
#include "sl_error.h"
#include "ytree.h"

/* Load path into *out: sl_ytree_read, then sl_yaml_bind. Errors: those
 * of both. On success *pos is the file's tree (free both with
 * sl_yaml_free). */
enum sl_err sl_yaml_load(const char *path, const cyaml_schema_value_t *schema, void **out,
                         struct sl_yaml_pos **pos, size_t max_bytes, enum sl_err kind, struct sl_diag *d);

/* Bind the tree to schema (a mapping with CYAML_FLAG_POINTER) into *out.
 * Errors (`kind`, naming the node's file or -D value, its line and key):
 * an empty file, a root that is not a mapping, an unknown or repeated key,
 * a missing required key, a value of the wrong kind or out of range, too
 * few or too many entries. *out is NULL on error. */
enum sl_err sl_yaml_bind(const struct sl_yaml_pos *t, const cyaml_schema_value_t *schema, void **out,
                         enum sl_err kind, struct sl_diag *d);

void sl_yaml_free(const cyaml_schema_value_t *schema, void *data, struct sl_yaml_pos *pos);

/* Line of a dotted key path ("methods[1].bias": a mapping value's is its
 * key's), 0 if unknown or given by a -D value. */
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
