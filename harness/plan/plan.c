/*
 * plan.c — see plan.h.
 *
 * Invariant: sl_plan_cell is the inverse of the sweep order sl_plan_count
 * counts, scene by scene: viewport, then viewpoint, then map size, then
 * method label, the last varying fastest.
 */
#include "plan.h"
#include <string.h>
#include "method.h"

static int popcount(unsigned m)
{
    int n = 0;
    for (; m; m &= m - 1)
        n++;
    return n;
}

/* The j-th set bit of mask (j < popcount(mask)). */
static int nth_bit(unsigned mask, int j)
{
    int b = 0;
    while (!(mask & (1u << b)) || j-- > 0)
        b++;
    return b;
}

int sl_plan_count(const struct sl_config *c)
{
    int n = 0;
    for (int s = 0; s < c->nscenes; s++)
        n += c->nviewports * c->scenes[s].nviewpoints * popcount(c->scenes[s].map_mask) *
             popcount(c->scenes[s].method_mask);
    return n;
}

void sl_plan_cell(const struct sl_config *c, int index, struct sl_cell_key *k)
{
    memset(k, 0, sizeof *k);
    for (int s = 0; s < c->nscenes; s++) {
        const struct sl_config_scene *cs = &c->scenes[s];
        int nm = popcount(cs->map_mask), nl = popcount(cs->method_mask);
        int per = c->nviewports * cs->nviewpoints * nm * nl;
        if (index < per) {
            k->scene = s;
            k->method = nth_bit(cs->method_mask, index % nl);
            index /= nl;
            k->map = nth_bit(cs->map_mask, index % nm);
            index /= nm;
            k->vp = index % cs->nviewpoints;
            k->viewport = index / cs->nviewpoints;
            return;
        }
        index -= per;
    }
}

/* The set bits of mask below bit b. */
static int below(unsigned mask, int b)
{
    return popcount(b >= 32 ? mask : mask & ((1u << b) - 1u));
}

int sl_plan_index(const struct sl_config *c, const struct sl_cell_key *k)
{
    int base = 0;
    for (int s = 0; s < k->scene; s++)
        base += c->nviewports * c->scenes[s].nviewpoints * popcount(c->scenes[s].map_mask) *
                popcount(c->scenes[s].method_mask);
    const struct sl_config_scene *cs = &c->scenes[k->scene];
    int nm = popcount(cs->map_mask), nl = popcount(cs->method_mask);
    return base + ((k->viewport * cs->nviewpoints + k->vp) * nm + below(cs->map_mask, k->map)) * nl +
           below(cs->method_mask, k->method);
}

/* The layers wanted by the selected cells of the (view, map) group that
 * starts at cell `from` (the group's cells are contiguous in sweep order),
 * leaving out cells a resumed run will skip. */
/* The layers the group's remaining cells from `from` need (mask), and of
 * those the ones some cell reads beyond its pixels' own texels (*dense). */
static unsigned group_layers(const struct sl_config *c, int from, int last, const uint8_t *skip,
                             unsigned *dense, unsigned looks[2])
{
    struct sl_cell_key k0, k;
    sl_plan_cell(c, from, &k0);
    unsigned needs = 0;
    *dense = looks[0] = looks[1] = 0;
    for (int i = from; i < last; i++) {
        sl_plan_cell(c, i, &k);
        if (k.scene != k0.scene || k.viewport != k0.viewport || k.vp != k0.vp || k.map != k0.map)
            break;
        if (skip && skip[i])
            continue;
        const struct sl_method *m = c->methods[k.method].method;
        const unsigned n = m->needs(&c->methods[k.method].params);
        needs |= n;
        *dense |= n & ~sl_method_at_pixel(m);
        looks[1] |= looks[0] & n & sl_method_looks(m);
        looks[0] |= n & sl_method_looks(m);
    }
    return needs;
}

unsigned sl_plan_group_needs(const struct sl_config *c, int from, int last, const uint8_t *skip)
{
    unsigned dense, looks[2];
    return group_layers(c, from, last, skip, &dense, looks);
}

unsigned sl_plan_group_at_pixel(const struct sl_config *c, int from, int last, const uint8_t *skip)
{
    unsigned dense, looks[2], needs = group_layers(c, from, last, skip, &dense, looks);
    return needs & ~dense & ((1u << SL_LAYER_COUNT) - 1u);
}

void sl_plan_group_looks(const struct sl_config *c, int from, int last, const uint8_t *skip, unsigned looks[2])
{
    unsigned dense;
    group_layers(c, from, last, skip, &dense, looks);
}

/* 2 where a view (scene, viewport, viewpoint) starts at cell i, 1 where only
 * its map size changes, 0 inside a (view, map size) group. */
static int boundary_level(const struct sl_config *c, int i)
{
    if (i == 0)
        return 2;
    struct sl_cell_key a, b;
    sl_plan_cell(c, i - 1, &a);
    sl_plan_cell(c, i, &b);
    if (a.scene != b.scene || a.viewport != b.viewport || a.vp != b.vp)
        return 2;
    return a.map != b.map;
}

/* Each cut goes to the view boundary nearest its even share of the cells
 * when one lies within a quarter of a slice of it, else to the nearest
 * (view, map size) boundary so near (the layers stay shared, the view is
 * computed twice), else exactly at the share. A quarter: every slice holds
 * between half and one and a half of its even share, and a sweep whose views
 * hold at most half a slice's cells loses no view. Cells differ in cost (a soft cell costs more than a
 * hard one), so the balance is by count, not time: a cost per method would be
 * a guess the bench does not back. */
int sl_plan_slices(const struct sl_config *c, int n, int *b)
{
    int total = sl_plan_count(c);
    if (n > total)
        n = total;
    if (n < 1)
        n = 1;
    int k = 0;
    b[k++] = 0;
    double share = (double)total / n;
    for (int i = 1; i < n; i++) {
        int t = (int)(i * share + 0.5), cut = -1;
        for (int level = 2; level >= 1 && cut < 0; level--)
            for (int dist = 0; dist <= (int)(share / 4) && cut < 0; dist++) {
                if (t - dist > b[k - 1] && t - dist < total && boundary_level(c, t - dist) >= level)
                    cut = t - dist;
                else if (t + dist > b[k - 1] && t + dist < total && boundary_level(c, t + dist) >= level)
                    cut = t + dist;
            }
        if (cut < 0)
            cut = t;
        if (cut > b[k - 1] && cut < total)
            b[k++] = cut;
    }
    b[k] = total;
    return k;
}

int sl_plan_split_views(const struct sl_config *c, const int *b, int n, int *nviews)
{
    int views = 0, extra = 0;
    for (int s = 0; s < n; s++)
        for (int i = b[s]; i < b[s + 1]; i++) {
            int lvl = boundary_level(c, i);
            views += lvl == 2;
            /* a slice that starts inside a view computes that view again */
            extra += i == b[s] && lvl < 2;
        }
    if (nviews)
        *nviews = views;
    return extra;
}
