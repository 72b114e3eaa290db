/* struct vt_input_raster (vt_input_raster.h). */
#include "vt_input_raster.h"

#include <stdlib.h>

void vt_input_raster_release(struct vt_input_raster *r)
{
    if (!r)
        return;
    free(r->crs_wkt);
    r->crs_wkt = NULL;
}
