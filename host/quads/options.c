/* quads/options.c: the table of the user-settable quad-mesh options
 * (glpgp_quads_option_table, glpgp/quads.h; descriptors: glpgp/optdesc.h),
 * read by the CLI (--keep-polygons, --smooth, ...) and the Python keyword
 * arguments of Result.quads (keep_polygons, smooth, ...). */
#include "glpgp/quads.h"

#include <stddef.h>

#define OFF(m) offsetof(glpgp_quads_options, m)

static const glpgp_optdesc k_table[] = {
    {.name = "keep-polygons", .kind = GLPGP_OPTK_FLAG, .offset = OFF(keep_polygons), .ival = 1,
     .help = "keep the faces left around dislocations as polygons\n"
             "(default: join them pairwise or to the boundary by strips\n"
             "of quads cut in two: all quads, same size)"},
    {.name = "smooth", .kind = GLPGP_OPTK_INT, .offset = OFF(smooth), .lo = 0, .hi = 100000, .meta = "N",
     .help = "smoothing sweeps around the new vertices and the faces with\n"
             "scaled Jacobian < 0.5 (0: off; a move is kept only if no nearby\n"
             "corner gets worse)"},
    {.name = "all-quads", .kind = GLPGP_OPTK_FLAG, .offset = OFF(all_quads), .ival = 1,
     .help = "refine every face into quads (centroid + edge midpoints):\n"
             "half the element size"},
    {.name = "no-repair", .kind = GLPGP_OPTK_FLAG, .offset = OFF(repair), .ival = 0,
     .help = "do not re-mesh the regions where the extracted mesh is invalid\n"
             "(default: remove the bad faces and their neighbours and fill the\n"
             "hole with quads)"},
    {.name = "no-cleanup", .kind = GLPGP_OPTK_FLAG, .offset = OFF(cleanup), .ival = 0,
     .help = "keep the irregular vertices the repair and the strips leave\n"
             "(default: doublet removal, diagonal collapse and edge rotation\n"
             "where they lower the irregular vertices and keep the quality)"},
    {.name = NULL}};

const glpgp_optdesc *glpgp_quads_option_table(void) { return k_table; }
