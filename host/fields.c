/* fields.c - byte sizes of the fields a backend exposes (see backend.h and common/dem_layout.h). */
#include "backend.h"
#include "dem_layout.h"

size_t dem_field_size(dem_field f, unsigned effects, size_t n, size_t maxn, size_t nwalls, size_t ncells, size_t rs)
{
    int friction = (effects & DEM_EFFECT_FRICTION) != 0; /* tangential history exists only with friction */
    int mcs = (effects & DEM_EFFECT_MC_STRESS) != 0, mce = (effects & DEM_EFFECT_MC_STRAIN) != 0;
    switch (f) {
    case FIELD_X: case FIELD_V: case FIELD_W: case FIELD_FORCE: case FIELD_TORQUE: case FIELD_X_BUILD:
        return 3 * n * rs;
    case FIELD_NBR_COUNT: case FIELD_CELL_PARTICLES: return n * sizeof(int);
    case FIELD_NBR_LIST: return n * maxn * sizeof(int);
    case FIELD_HIST: return friction ? 3 * n * maxn * rs : 0;
    case FIELD_WALL_HIST: return friction ? 3 * n * nwalls * rs : 0;
    case FIELD_TOUCH: return n * maxn;
    case FIELD_WALL_MASK: return n * sizeof(unsigned);
    case FIELD_WALL_FORCE: return 3 * nwalls * rs;
    case FIELD_CELL_START: return (ncells + 1) * sizeof(int);
    case FIELD_FLAGS: return FLAG_COUNT * sizeof(int);
    case FIELD_WALL_REAL: return W_STRIDE * nwalls * rs;
    case FIELD_STRESS: return ST_STRIDE * n * rs;
    case FIELD_STRESS_TRACE: return mcs ? n * rs : 0;
    case FIELD_MC_FORCE: case FIELD_MC_DISP: return mce ? n * maxn * rs : 0;
    case FIELD_MC_WALL_FORCE: case FIELD_MC_WALL_DISP: return mce ? n * nwalls * rs : 0;
    default: return 0;
    }
}
