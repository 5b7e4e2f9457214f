/*
 * methodparams.h — the parameters of one labelled method entry, apart from
 * the plugin face (method.h), so a config holds a label's parameters
 * without the methods' types.
 *
 * Owns: nothing (the values point at their method's declarations).
 */
#ifndef SL_METHODPARAMS_H
#define SL_METHODPARAMS_H
#include "params.h"

/* The parameters of one labelled method entry: the method's declarations
 * and a checked value for each (base/params.h), and, for a technique
 * package's method, its package (methods/package.h): its parameters come
 * first in the declarations, in the package's order, so values.v[k] is
 * the package's parameter k; NULL for a C method. */
struct sl_technique;
struct sl_external;   /* methods/external.h */
struct sl_method_params {
    struct sl_params           values;
    const struct sl_technique *tech;
    const struct sl_external  *external;   /* method external: the image `shadowlab grade` hands it; else NULL */
};

#endif
