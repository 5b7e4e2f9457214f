/*
 * moderno::* — the confirmation methods of Moderno 2011: a confirmation or a
 * correction is never wrong (only coherence hints may be), on all four
 * scenes; 9 neighbours confirm at least what 4 do and vertex adjacency at
 * least what edge adjacency does, on every view; the chain that traces
 * what is left errs only where a hint erred.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "sl_test.h"
#include "config.h"
#include "run.h"

static uint64_t img(const struct sl_cell *c, enum sl_figure f)
{
    return c->fig.r[c->fig.nregions - 1].n[f];
}

static void moderno_proofs_never_wrong(void **st)
{
    (void)st;
    struct sl_config c;
    struct sl_diag d;
    sl_test_config("c.yaml", "scenes: [{scene: primitives}, {scene: bench}, {scene: trees}, {scene: flowers}]\n"
          "viewports: [{width: 256, height: 192}]\nmap_sizes: [1024, 2048]\nmethods:\n"
          "  - {label: texel, method: texel}\n"
          "  - {label: nb4, method: neighbours, texels: 4}\n  - {label: nb9, method: neighbours, texels: 9}\n"
          "  - {label: adj1, method: adjacency, level: 1}\n  - {label: adj2, method: adjacency, level: 2}\n"
          "  - {label: chain, method: chain, finish: trace}\n", &c);
    struct sl_run_opts o = {.write_files = 0, .store = "", .cache_dir = ""};
    struct sl_run_result r;
    assert_int_equal(sl_run(&c, &o, &r, &d), SL_OK);
    assert_int_equal(r.ncells, 12 * 2 * 6);
    uint64_t proofs = 0, corrections = 0, adj_step = 0;
    for (int i = 0; i < r.ncells; i += 6) {
        const struct sl_cell *tx = &r.cells[i], *n4 = &r.cells[i + 1], *n9 = &r.cells[i + 2],
                             *a1 = &r.cells[i + 3], *a2 = &r.cells[i + 4], *ch = &r.cells[i + 5];
        for (int k = 0; k < 6; k++) {
            assert_int_equal(r.cells[i + k].violations, 0);      /* no proof is ever wrong */
            proofs += img(&r.cells[i + k], SL_FIG_confirmed) + img(&r.cells[i + k], SL_FIG_corrected);
            corrections += img(&r.cells[i + k], SL_FIG_corrected);
        }
        uint64_t p4 = img(n4, SL_FIG_confirmed) + img(n4, SL_FIG_corrected);
        uint64_t p9 = img(n9, SL_FIG_confirmed) + img(n9, SL_FIG_corrected);
        uint64_t pt = img(tx, SL_FIG_confirmed) + img(tx, SL_FIG_corrected);
        uint64_t l1 = img(a1, SL_FIG_confirmed) + img(a1, SL_FIG_corrected);
        uint64_t l2 = img(a2, SL_FIG_confirmed) + img(a2, SL_FIG_corrected);
        assert_true(p9 >= p4 && p4 >= pt);
        assert_true(l2 >= l1 && l1 >= pt);
        /* the traced chain is wrong only where a hint was */
        assert_int_equal(ch->fig.wrong_image, img(ch, SL_FIG_hinted_wrong));
        /* its steps: hints, neighbour proofs, adjacency proofs, rays cover
         * every PFL pixel once */
        assert_int_equal(img(ch, SL_FIG_hinted) + img(ch, SL_FIG_confirmed) + img(ch, SL_FIG_corrected) +
                             img(ch, SL_FIG_traced), ch->n_pfl);
        adj_step += img(ch, SL_FIG_confirmed_adj);
        /* corrections are only ever L->S, never turning a right pixel bad */
        assert_int_equal(img(n9, SL_FIG_broken_ls), 0);
    }
    printf("moderno::proofs: %llu confirmations and corrections (%llu corrections), none wrong\n",
           (unsigned long long)proofs, (unsigned long long)corrections);
    assert_true(proofs > 1000 && corrections > 0);
    assert_true(adj_step > 0);      /* the adjacency step confirms what neighbours could not */
    printf("moderno::proofs: the chain's adjacency step confirmed %llu pixels\n", (unsigned long long)adj_step);
    sl_run_result_free(&r);
}



int main(void)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(moderno, proofs_never_wrong),
    };
    return cmocka_run_group_tests_name("moderno", tests, sl_test_setup, sl_test_teardown);
}
