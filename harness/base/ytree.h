/*
 * ytree.h — a YAML file read once into a tree of positioned nodes.
 *
 * sl_ytree_read opens the file (a regular file only, sl_open_regular),
 * refuses it before reading when it is over the caller's limit, reads it
 * once, checks that it is UTF-8 text without control characters (naming
 * the line of the first bad byte) and runs one libyaml event parse that
 * builds the tree: scalars (their text, whether quoted), mappings (key and
 * value nodes in the file's order) and sequences, each node with its line,
 * column and origin (the file, or a -D value grafted later). A node's key
 * path ("methods[1].bias") is its place in the tree: sl_ynode_path.
 *
 * The same parse enforces the limits every YAML input has: nesting past
 * SL_YAML_MAX_DEPTH is refused at the line where it goes past, naming the
 * top-level key it is under (libyaml's scanner costs the square of the
 * nesting, so the parse stops there); an alias (*name) is refused at its
 * line and never expanded (each alias copies its anchor's node: a few
 * bytes can stand for gigabytes); libyaml's own errors are named with the
 * line and key of the last node read before them; the node count is
 * bounded by the file's byte limit. Only the first document is kept (as
 * libcyaml kept it); the rest of the stream is still checked for depth
 * and aliases.
 *
 * The command line's -D overrides edit the tree: sl_ytree_value parses a
 * value as YAML into detached nodes whose origin is the override itself,
 * and sl_ytree_set grafts them at a key path. Nothing is ever written back
 * out as text or read a second time.
 *
 * Owns: every node (one arena, freed by sl_ytree_free), the file's bytes
 * only while parsing. Does not: know any schema (yamlfile.h binds a tree
 * to C structs).
 */
#ifndef SL_YTREE_H
#define SL_YTREE_H
#include <stddef.h>
#include "sl_error.h"

/* Nesting: a file nested deeper than this (mappings and sequences, flow
 * or block) is refused with the line where it goes past it. No schema of
 * shadowlab nests past 6. */
#define SL_YAML_MAX_DEPTH 64

enum sl_ynode_kind { SL_YSCALAR = 1, SL_YMAP, SL_YSEQ };

struct sl_ynode {
    struct sl_ynode *parent;       /* NULL for the root and for a detached value */
    struct sl_ynode *key;          /* a mapping's value: the key node naming it, else NULL */
    char            *text;         /* a scalar's text (NUL-terminated; a key's too), else NULL */
    struct sl_ynode **kid;         /* a mapping: key, value, key, value...; a sequence: its entries */
    unsigned         n, cap;       /* pairs of a mapping, entries of a sequence; kid's room */
    unsigned         index;        /* its place in the parent: pair or entry number */
    int              line, col;    /* 1-based; within the -D value for an override's node */
    unsigned char    kind;         /* enum sl_ynode_kind */
    unsigned char    quoted;       /* a scalar written in quotes (or as a block scalar) */
    unsigned char    taken;        /* a mapping value the loader took out of the schema's view */
    unsigned char    origin;       /* 0 the file; k > 0 the k-th -D value (sl_ytree_value) */
};

/* One file's tree (the name is the loaders' handle for positions). */
struct sl_yaml_pos;

/* Read path once into *out (free with sl_ytree_free). Errors: SL_E_IO
 * (unreadable), SL_E_NOMEM, else `kind` (the file's own error id) naming
 * file, line and key: over max_bytes, not UTF-8 text, nested too deep, an
 * alias, a YAML syntax error, more nodes than the limit allows. An empty
 * file reads as a tree without root. */
enum sl_err sl_ytree_read(const char *path, size_t max_bytes, enum sl_err kind, struct sl_yaml_pos **out,
                          struct sl_diag *d);
void        sl_ytree_free(struct sl_yaml_pos *t);

/* The file's path, its root (NULL for an empty file), and the 64-bit
 * FNV-1a hash of the bytes read (what sl_hash_file gives for the file). */
const char            *sl_ytree_file(const struct sl_yaml_pos *t);
struct sl_ynode       *sl_ytree_root(const struct sl_yaml_pos *t);
unsigned long long     sl_ytree_hash(const struct sl_yaml_pos *t);

/* The node at a key path ("a.b[2].c"; "" is the root), NULL if none. In a
 * mapping given a key twice the first pair answers. */
struct sl_ynode *sl_ytree_find(const struct sl_yaml_pos *t, const char *path);
/* The value of a mapping's first pair whose key is `key` (NULL if none). */
struct sl_ynode *sl_ynode_get(const struct sl_ynode *map, const char *key);
/* The node's key path into buf (truncated to size); its length. */
size_t           sl_ynode_path(const struct sl_ynode *n, char *buf, size_t size);
/* What an error about the node names: the file or "-D key=value" ... */
const char      *sl_ynode_source(const struct sl_yaml_pos *t, const struct sl_ynode *n);
/* ... and the line: a mapping value's is its key's; 0 for a -D value's node. */
int              sl_ynode_line(const struct sl_ynode *n);

/* ---- -D: values grafted at a key path ---- */

/* Parse text (the VALUE of `-D KEY=VALUE`) as YAML into *out, a detached
 * node whose origin is `source` (the whole "-D KEY=VALUE", named by errors
 * about it). Errors: SL_E_CONFIG naming source and key (the value is not
 * YAML, nested too deep, holds an alias), SL_E_NOMEM. */
enum sl_err sl_ytree_value(struct sl_yaml_pos *t, const char *text, const char *source, const char *key,
                           struct sl_ynode **out, struct sl_diag *d);
/* Set path (name.name[index], e.g. methods[1].bias) in the root mapping to
 * val: a key that is there has its value replaced; a missing key is added
 * (a missing middle key as a new mapping); an index replaces that entry,
 * and one past the last appends, as the path's last step only. 0 and a
 * reason in msg when the path cannot be set. The replaced nodes stay in
 * the arena, out of the tree. */
int sl_ytree_set(struct sl_yaml_pos *t, const char *path, struct sl_ynode *val, char *msg, size_t nmsg);

#endif
