/* build::graph — with the report's compile flags, method.h must not be found */
#include "method.h"
int sl_graph_method;
