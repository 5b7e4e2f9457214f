/*
 * suggest.h — "did you mean": the name of a closed set nearest to a word
 * that is not in it, by edit distance (Damerau–Levenshtein, optimal string
 * alignment: an insertion, a deletion, a substitution or a swap of two
 * neighbours costs 1), case ignored. Used wherever a name is checked
 * against a set (config keys, methods, packages, scenes, labels, figures).
 * It only proposes: the caller still refuses the word.
 *
 * What counts as near: at most max(1, strlen(word) / 3) edits, so a
 * 3-letter word allows 1 and "shadowmap" 3; and a candidate at that
 * distance is proposed only when it is the single nearest one (a tie names
 * none, as a guess between two names would mislead). The rule is git's and
 * cargo's in spirit: short words get few edits.
 */
#ifndef SL_SUGGEST_H
#define SL_SUGGEST_H
#include <stddef.h>
#ifdef __cplusplus
extern "C" {
#endif

/* Edit distance of a and b (case ignored); words over 63 bytes count as
 * far (a large number). */
int sl_edit_distance(const char *a, const char *b);

/* The set's member nearest to word, or NULL when none is near enough (see
 * above) or word is itself a member. A running search: sl_suggest_init,
 * sl_suggest_add per candidate, then sl_suggest_best. */
struct sl_suggest {
    const char *word;
    const char *best;
    int         dist, ties;
};
void        sl_suggest_init(struct sl_suggest *s, const char *word);
void        sl_suggest_add(struct sl_suggest *s, const char *candidate);
const char *sl_suggest_best(const struct sl_suggest *s);
/* " (did you mean 'X'?)" into buf for the best, "" when there is none;
 * returns buf, so it fits straight into a message's %s. */
const char *sl_suggest_text(const struct sl_suggest *s, char *buf, size_t n);

#ifdef __cplusplus
}
#endif
#endif
