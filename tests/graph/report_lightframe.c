/* build::graph — with the report's compile flags, lightframe.h must not be found */
#include "lightframe.h"
int sl_graph_lightframe;
