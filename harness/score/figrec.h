/*
 * figrec.h — the figures of a cell as a record: the lists of figure names
 * (Moderno's and Morais's counts, SL_FIGURES; the aliasing error's bands,
 * SL_ALIAS_FIGURES), their enums and the structs that hold a cell's counts
 * and percentages per region.
 *
 * Apart from figures.h and aliasing.h, which compute them, so the results
 * store, its tables and the report read a cell's figures without the
 * renderer's, the methods' or the scene's headers (the build gives them
 * this folder and not those: CMakeLists.txt, sl_score_records).
 * Owns: nothing. Does not: count anything (figures.h, aliasing.h do).
 */
#ifndef SL_FIGREC_H
#define SL_FIGREC_H
#include <stdint.h>

#define SL_MAX_REGIONS 8

/* name, what it counts, the figure its percentage is taken of ("" = none) */
#define SL_FIGURES(X)                                                              \
    X(pixels,           "pixels in the region (not background)",      "")         \
    X(pfl,              "pixels facing the light",                    "pixels")   \
    X(pnfl,             "pixels not facing the light",                "pixels")   \
    X(light,            "pixels the method puts in light",            "pixels")   \
    X(shadow,           "pixels the method puts in shadow (with PnFL)", "pixels") \
    X(uncertain,        "pixels the method leaves undecided",         "pixels")   \
    X(light_correct,    "in light, lit in truth",                     "light")    \
    X(light_incorrect,  "in light, shadowed in truth (wrongly lit)",  "light")    \
    X(shadow_correct,   "in shadow, shadowed in truth",               "shadow")   \
    X(shadow_incorrect, "in shadow, lit in truth (wrongly shadowed)", "shadow")   \
    X(wrong,            "wrong pixels (both kinds)",                  "pixels")   \
    X(wrong_caught,     "wrong pixels of the whole image inside this region", "wrong_image") \
    X(traced,           "pixels decided by a shadow ray (uncertain to the maps)", "pixels") \
    X(traced_shadow,    "of those, shadowed in truth",                "traced")   \
    X(hinted,           "PFL pixels given a coherence hint (PnFL apart)",              "pixels")   \
    X(hinted_wrong,     "of those, hinted wrongly",                   "hinted")   \
    X(nsm_light,        "pixels NSM puts in light (PFL; PnFL are never lit)",             "pixels")   \
    X(nsm_shadow,       "pixels NSM puts in shadow (PFL only: Morais's count)",            "pixels")   \
    X(hinted_light,     "NSM-lit pixels hinted (Moderno Tables 7-8 light)", "nsm_light") \
    X(hinted_light_wrong, "NSM-lit pixels hinted wrongly",            "nsm_light") \
    X(hinted_shadow,    "NSM-shadowed PFL pixels hinted (PnFL apart)",                 "nsm_shadow") \
    X(hinted_shadow_wrong, "NSM-shadowed pixels hinted wrongly",      "nsm_shadow") \
    X(confirmed,        "shadow confirmed by a ray-triangle hit",     "pixels")   \
    X(confirmed_adj,    "of those, in the chain's adjacency step",    "confirmed") \
    X(corrected,        "lit turned shadowed by a ray-triangle hit",  "pixels")   \
    X(fixed_ls,         "vs NSM: L->S, now right (corrected)",        "pixels")   \
    X(broken_ls,        "vs NSM: L->S, now wrong (turned bad)",       "pixels")   \
    X(fixed_sl,         "vs NSM: S->L, now right (corrected)",        "pixels")   \
    X(broken_sl,        "vs NSM: S->L, now wrong (turned bad)",       "pixels")   \
    X(kept_right,       "vs NSM: unchanged and right (maintained correct)", "pixels") \
    X(kept_wrong,       "vs NSM: unchanged and wrong (maintained incorrect)", "pixels") \
    X(ray_tri_tests,    "ray-triangle tests outside Embree spent on these pixels", "")         \
    X(nsm_shadow_moderno, "pixels NSM puts in shadow, PnFL with them (Moderno's count)", "pixels") \
    X(hinted_moderno,   "pixels hinted, PnFL with them when the method hints (Moderno's count)", "pixels") \
    X(hinted_shadow_moderno, "NSM-shadowed pixels hinted, PnFL with them (Moderno Tables 7-8 shadow)", "nsm_shadow_moderno") \
    X(hinted_shadow_wrong_moderno, "NSM-shadowed pixels hinted wrongly (Moderno Tables 7-8)", "nsm_shadow_moderno") \
    X(conf_moderno,     "hints + confirmations + corrections, PnFL with them (Moderno Table 13)", "pixels") \
    X(conf_step2_moderno, "the same without the adjacency step's (Moderno Table 12)", "pixels") \
    X(conf_light_moderno, "NSM-lit pixels hinted or corrected (Moderno Table 12 light)", "nsm_light") \
    X(conf_shadow_moderno, "NSM-shadowed hinted or confirmed, PnFL with them (Moderno Table 13 shadow)", "nsm_shadow_moderno") \
    X(conf_shadow_step2_moderno, "the same without the adjacency step's (Moderno Table 12 shadow)", "nsm_shadow_moderno")    \
    X(kept_ll_right,    "vs NSM: L->L and right (Moderno Table 23 maintained correct L->L)", "pixels") \
    X(kept_ss_right_moderno, "vs NSM: S->S and right, PnFL with them (Table 23 maintained correct S->S)", "pixels") \
    X(kept_ll_wrong,    "vs NSM: L->L and wrong (Table 23 maintained incorrect L->L)", "pixels") \
    X(kept_ss_wrong,    "vs NSM: S->S and wrong (Table 23 maintained incorrect S->S)", "pixels")

enum sl_figure {
#define SL_FIG_ENUM(name, text, of) SL_FIG_##name,
    SL_FIGURES(SL_FIG_ENUM)
#undef SL_FIG_ENUM
    SL_FIG_COUNT
};

const char *sl_figure_name(enum sl_figure f);
const char *sl_figure_text(enum sl_figure f);
const char *sl_figure_of(enum sl_figure f);

struct sl_region_figures {
    int      thickness;                 /* 0 = whole image */
    uint64_t n[SL_FIG_COUNT];
    double   pct[SL_FIG_COUNT];         /* of the base figure; NAN when none */
};

struct sl_figures {
    uint64_t background;
    uint64_t wrong_image;               /* wrong pixels in the whole image */
    int      nregions;
    struct sl_region_figures r[SL_MAX_REGIONS];
};

/* The bands: m <= 1, (1, 2], (2, 4], (4, 8], > 8. */
#define SL_ALIAS_BANDS 5

/* name, what it counts, the figure of the region its percentage is taken of */
#define SL_ALIAS_FIGURES(X)                                                                   \
    X(px_m_le1,    "PFL pixels with m <= 1",                          "pfl")                  \
    X(px_m_1_2,    "PFL pixels with 1 < m <= 2",                      "pfl")                  \
    X(px_m_2_4,    "PFL pixels with 2 < m <= 4",                      "pfl")                  \
    X(px_m_4_8,    "PFL pixels with 4 < m <= 8",                      "pfl")                  \
    X(px_m_gt8,    "PFL pixels with m > 8",                           "pfl")                  \
    X(wrong_m_le1, "wrong pixels with m <= 1",                        "wrong")                \
    X(wrong_m_1_2, "wrong pixels with 1 < m <= 2",                    "wrong")                \
    X(wrong_m_2_4, "wrong pixels with 2 < m <= 4",                    "wrong")                \
    X(wrong_m_4_8, "wrong pixels with 4 < m <= 8",                    "wrong")                \
    X(wrong_m_gt8, "wrong pixels with m > 8",                         "wrong")                \
    X(m_none,      "PFL pixels whose m is undefined (both footprints infinite)", "pfl")       \
    X(m_median_milli, "median m of the PFL pixels, x 1000 (rounded)", "")                     \
    X(wrong_m_median_milli, "median m of the wrong pixels, x 1000 (rounded; 0: none wrong)", "")

enum sl_alias_figure {
#define SL_AFIG_ENUM(name, text, of) SL_AFIG_##name,
    SL_ALIAS_FIGURES(SL_AFIG_ENUM)
#undef SL_AFIG_ENUM
    SL_AFIG_COUNT
};

const char *sl_alias_figure_name(enum sl_alias_figure f);
const char *sl_alias_figure_text(enum sl_alias_figure f);
const char *sl_alias_figure_of(enum sl_alias_figure f);   /* "pfl", "wrong" or "" */
int         sl_alias_figure_parse(const char *name);      /* -1 if unknown */

/* Per region, in the order of the cell's figures (fig.r[]). */
struct sl_alias_figures {
    int      nregions;
    int      thickness[SL_MAX_REGIONS];
    uint64_t n[SL_MAX_REGIONS][SL_AFIG_COUNT];
    double   pct[SL_MAX_REGIONS][SL_AFIG_COUNT];   /* of the region's pfl / wrong; NAN when none */
};

/* One stored figure back into a: returns 0 if `figure` is not an aliasing
 * figure's name, else 1 (the region is added in the order met). */
int sl_alias_figures_put(struct sl_alias_figures *a, int thickness, const char *figure, uint64_t count, double pct);


#endif
