/* backend.c - the buffer registry (common/dem_buffers.h) and the kernels' argument lists (common/dem_kernels.h)
 * walked for every backend: sizes, creation, field lookup, work-item counts, and the compile-time check that each
 * kernel argument's element type is its buffer's. */
#include "backend.h"
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#define DEM_NAME_KERNEL(name) #name,
const char *const dem_kernel_names[K__COUNT] = {DEM_KERNEL_LIST(DEM_NAME_KERNEL)};
#undef DEM_NAME_KERNEL

/* ---- element types: each kernel argument's against its registry entry, at compile time ---- */
#define ELEM_BUF(id, elem, count, gate, field, init, part, move, ckpt) BUFELEM_##id = DEM_ELEM_##elem,
#define ELEM_ROW(id, elem, count, gate, field) ROWELEM_##id = DEM_ELEM_##elem,
enum { DEM_BUFFERS(ELEM_BUF) BUFELEM__END };
enum { DEM_ROWS(ELEM_ROW) ROWELEM__END };
#define ALIASELEM_SCAN_COUNT DEM_ELEM_INT /* the scan's operands are integer buffers */
#define ALIASELEM_SCAN_BLOCK_SUM DEM_ELEM_INT
#define ALIASELEM_SCAN_START DEM_ELEM_INT
#define ALIASELEM_HALO_ROWS DEM_ELEM_REAL /* a per-particle buffer of reals (halo.h) */
#define CHECK_I(type, src) _Static_assert(SI_##src >= 0, "int scalar");
#define CHECK_R(type, src) _Static_assert(SR_##src >= 0, "real scalar");
#define CHECK_BIN(type, src) _Static_assert((int)BUFELEM_##src == (int)DEM_ELEM_OF_##type, #src ": element type");
#define CHECK_BOUT CHECK_BIN
#define CHECK_CIN(type, src) _Static_assert((int)ROWELEM_##src == (int)DEM_ELEM_OF_##type, #src ": element type");
#define CHECK_COUT CHECK_CIN
#define CHECK_NIN CHECK_CIN
#define CHECK_NOUT CHECK_CIN
#define CHECK_AIN(type, src) _Static_assert((int)ALIASELEM_##src == (int)DEM_ELEM_OF_##type, #src ": element type");
#define CHECK_AOUT CHECK_AIN
#define CHECK_ARG(kind, type, name, src) CHECK_##kind(type, src)
#define CHECK_KERNEL(name) DEM_ARGS_##name(CHECK_ARG, CHECK_ARG)
DEM_KERNEL_LIST(CHECK_KERNEL)
_Static_assert(PR_STRIDE == 7 && W_STRIDE == 11 && WI_STRIDE == 2 && PM_STRIDE == 26 && ST_STRIDE == 6 &&
                   MDR_PAIR_STRIDE == 25 && MDR_WALL_STRIDE == 13 && MDR_P_STRIDE == 14,
               "record layouts (dem_layout.h) changed: checkpoints and kernels depend on them");
_Static_assert(FLAG_COUNT == 15 && FLAG_MDR_CAPPED == 14 && FLAG_CELL_HI == FLAG_CELL_LO + 3, "flags (dem_layout.h): host/steps/binning.c resets the cell bounds");
_Static_assert(K__COUNT <= 256, "kernel ids fit the trace's bytes");
_Static_assert(DEM_PAIR_RECORD_REALS == PR_STRIDE, "the pair records' size in dem.h (checkpoints)");
_Static_assert(DEM_MDR_LAW_REALS == MDR_PAIR_STRIDE, "the mdr law's reals per pair in dem.h (checkpoints)");
_Static_assert(DEM_MAX_WALLS <= 8 * sizeof(unsigned), "a particle's wall mask is one unsigned (WALL_MASK)");

int dem_core_fail(dem_core *c, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->err, sizeof c->err, fmt, ap);
    va_end(ap);
    return 1;
}

void dem_core_init(dem_core *c, const dem_setup *s)
{
    memset(c, 0, sizeof *c);
    c->fx = s->effects;
    c->rs = s->real_size;
    c->n = s->n;
    c->nmat = s->nmat;
    c->nwalls = s->nwalls;
    c->ncells = c->cell_cap = s->cells[0] * s->cells[1] * s->cells[2];
    c->nblocks_red = (s->n + DEM_REDUCE_BLOCK - 1) / DEM_REDUCE_BLOCK;
    c->nmid_red = (c->nblocks_red + DEM_REDUCE_FAN - 1) / DEM_REDUCE_FAN;
    size_t row_bytes = (size_t)s->n * SE_STRIDE * (size_t)s->real_size; /* a sampled step's terms (series.h) */
    c->series_rows = row_bytes ? (int)(DEM_SERIES_RING_BYTES / row_bytes) : DEM_SERIES_RING;
    c->series_rows = c->series_rows < 1 ? 1 : c->series_rows > DEM_SERIES_RING ? DEM_SERIES_RING : c->series_rows;
    c->nsprings = s->nsprings;
    c->ntriangles = s->ntriangles;
    c->nhinges = s->nhinges;
    c->nriders = s->nriders;
    c->maxn[0] = c->maxn[1] = s->maxn;
    c->maxp = c->maxp_old = s->maxp, c->maxv = s->maxv;
    int *si = c->si;
    si[SI_N] = s->n, si[SI_NMAT] = s->nmat, si[SI_NWALLS] = s->nwalls, si[SI_NCELLS] = c->ncells;
    si[SI_NBLOCKS_RED] = c->nblocks_red, si[SI_NMID_RED] = c->nmid_red;
    si[SI_NSPRINGS] = c->nsprings;
    si[SI_NTRIANGLES] = c->ntriangles;
    si[SI_NHINGES] = c->nhinges;
    si[SI_NRIDERS] = c->nriders;
    si[SI_NCX] = s->cells[0], si[SI_NCY] = s->cells[1], si[SI_NCZ] = s->cells[2];
    si[SI_CX0] = s->cell0[0], si[SI_CY0] = s->cell0[1], si[SI_CZ0] = s->cell0[2];
    si[SI_DCX] = s->ncell[0], si[SI_DCY] = s->ncell[1], si[SI_DCZ] = s->ncell[2];
    double *sr = c->sr;
    sr[SR_DT] = s->dt, sr[SR_SKIN] = s->skin, sr[SR_HALF_SKIN2] = s->half_skin2, sr[SR_INV_CELL] = s->inv_cell;
    sr[SR_LOX] = s->lo[0], sr[SR_LOY] = s->lo[1], sr[SR_LOZ] = s->lo[2];
    sr[SR_GX] = s->gravity[0], sr[SR_GY] = s->gravity[1], sr[SR_GZ] = s->gravity[2];
    sr[SR_PRESSURE] = s->pressure;
    sr[SR_REACH] = s->reach, sr[SR_RMAX] = s->rmax;
    si[SI_MAXP] = c->maxp, si[SI_MAXPO] = c->maxp_old, si[SI_MAXV] = c->maxv;
}

size_t dem_elem_size(int elem, int rs)
{
    return elem == DEM_ELEM_REAL ? (size_t)rs : elem == DEM_ELEM_BYTE ? 1 : sizeof(int);
}

/* the size rules' names, bound to a core */
#define SIZE_NAMES(c, maxn_)                                                                                         \
    size_t N = (size_t)(c)->n, NMAT = (size_t)(c)->nmat, NW = (size_t)(c)->nwalls, NC = (size_t)(c)->cell_cap,         \
           NBS = ((size_t)(c)->cell_cap + DEM_SCAN_BLOCK - 1) / DEM_SCAN_BLOCK, NBR = (size_t)(c)->nblocks_red, NMR = (size_t)(c)->nmid_red, PAIRS = (c)->pair_cap,                   \
           MAXN = (size_t)(maxn_), NS = (size_t)(c)->nsprings, NT = (size_t)(c)->ntriangles,                         \
           NH = (size_t)(c)->nhinges, NR = (size_t)(c)->nriders, MAXP = (size_t)(c)->maxp,                           \
           MAXPO = (size_t)(c)->maxp_old, MAXV = (size_t)(c)->maxv, NSR = (size_t)(c)->series_rows,                  \
           MAXC = (size_t)(c)->maxn[(c)->cur], NHALO = (size_t)(c)->halo_cap, LAWP = (size_t)DEM_LAW_PAIR_W((c)->fx),                               \
           LAWW = (size_t)DEM_LAW_WALL_W((c)->fx);                                                                   \
    (void)N, (void)NMAT, (void)NW, (void)NC, (void)NBS, (void)NBR, (void)NMR, (void)PAIRS, (void)MAXN, (void)NS, (void)NT,      \
        (void)NH, (void)NR, (void)MAXP, (void)MAXPO, (void)MAXV, (void)NSR, (void)MAXC, (void)NHALO, (void)LAWP, (void)LAWW

static int gate_open(unsigned fx, unsigned gate) { return gate == 0 || (gate != DEM_GATE_LAZY && (fx & gate)); }

size_t dem_buffer_bytes(const dem_core *c, int id)
{
    SIZE_NAMES(c, 0);
    switch (id) {
#define SIZE_BUF(id_, elem, count, gate, field, init, part, move, ckpt)                                                \
    case BUF_##id_:                                                                                                  \
        return gate_open(c->fx, gate) ? (size_t)(count) * dem_elem_size(DEM_ELEM_##elem, c->rs) : 0;
        DEM_BUFFERS(SIZE_BUF)
#undef SIZE_BUF
    }
    return 0;
}

int dem_buffer_part(int id)
{
    switch (id) {
#define PART_BUF(id_, elem, count, gate, field, init, part, move, ckpt)                                                \
    case BUF_##id_:                                                                                                  \
        return DEM_MEM_##part;
        DEM_BUFFERS(PART_BUF)
#undef PART_BUF
    }
    return DEM_MEM_PARTICLES;
}

/* the lazy buffers' size once they are made */
static size_t lazy_bytes(const dem_core *c, int id)
{
    SIZE_NAMES(c, 0);
    switch (id) {
#define SIZE_LAZY(id_, elem, count, gate, field, init, part, move, ckpt)                                               \
    case BUF_##id_:                                                                                                  \
        return (size_t)(count) * dem_elem_size(DEM_ELEM_##elem, c->rs);
        DEM_BUFFERS(SIZE_LAZY)
#undef SIZE_LAZY
    }
    return 0;
}

size_t dem_row_bytes(const dem_core *c, int id, int maxn)
{
    SIZE_NAMES(c, maxn);
    switch (id) {
#define SIZE_ROW(id_, elem, count, gate, field)                                                                      \
    case ROW_##id_:                                                                                                  \
        return gate_open(c->fx, gate) ? (size_t)(count) * dem_elem_size(DEM_ELEM_##elem, c->rs) : 0;
        DEM_ROWS(SIZE_ROW)
#undef SIZE_ROW
    }
    return 0;
}

int dem_buffers_create(const dem_backend_ops *ops, dem_backend *b, const dem_setup *s)
{
    dem_core *c = DEM_CORE(b);
#define SETUP(member) ((const void *)s->member)
#define NONE NULL
#define CREATE_BUF(id, elem, count, gate, field, init, part, move, ckpt)                                               \
    if (ops->alloc(b, TABLE_ONE, 0, BUF_##id, dem_buffer_bytes(c, BUF_##id), dem_buffer_bytes(c, BUF_##id) ? init : NULL)) \
        return 1;
    DEM_BUFFERS(CREATE_BUF)
#undef CREATE_BUF
#undef SETUP
#undef NONE
    for (int set = 0; set < 2; set++)
        for (int id = 0; id < ROW__COUNT; id++)
            if (ops->alloc(b, TABLE_CUR, set, id, dem_row_bytes(c, id, c->maxn[set]), NULL))
                return 1;
    return 0;
}

/* Makes a lazy buffer when first needed. */
int dem_buffer_ensure(const dem_backend_ops *ops, dem_backend *b, int id)
{
    dem_core *c = DEM_CORE(b);
    size_t need = lazy_bytes(c, id);
    return c->bytes[id] >= need ? 0 : ops->alloc(b, TABLE_ONE, 0, id, need, NULL);
}

int dem_field_ref(const dem_core *c, dem_field f, dem_bufref *r, size_t *bytes)
{
    int fi = (int)f;
#define FIELD_BUF(id_, elem, count, gate, field, init, part, move, ckpt)                                               \
    if (field >= 0 && fi == field) {                                                                                 \
        r->table = TABLE_ONE, r->id = BUF_##id_;                                                                     \
        *bytes = gate == DEM_GATE_LAZY ? lazy_bytes(c, BUF_##id_) : dem_buffer_bytes(c, BUF_##id_);                  \
        return 0;                                                                                                    \
    }
#define FIELD_ROW(id_, elem, count, gate, field)                                                                     \
    if (field >= 0 && fi == field) {                                                                                 \
        r->table = TABLE_CUR, r->id = ROW_##id_;                                                                     \
        *bytes = dem_row_bytes(c, ROW_##id_, c->maxn[c->cur]);                                                       \
        return 0;                                                                                                    \
    }
    DEM_BUFFERS(FIELD_BUF)
    DEM_ROWS(FIELD_ROW)
#undef FIELD_BUF
#undef FIELD_ROW
    *bytes = 0;
    return -1;
}

/* ---- each buffer's life beyond its creation: how it follows its particles, and what a checkpoint calls it ---- */
/* The setup member of an integer buffer is of the buffer's element type (a real one is raw bytes of either
 * precision): a SETUP init that does not fit stops the build. */
typedef struct dem_no_init dem_no_init;
#define SETUP(member) (((const dem_setup *)0)->member)
#define NONE ((const dem_no_init *)0)
#define INIT_OK_REAL(init) _Generic((init), const void *: 1, const dem_no_init *: 1, default: 0)
#define INIT_OK_INT(init) _Generic((init), const int *: 1, const dem_no_init *: 1, default: 0)
#define INIT_OK_UINT(init) _Generic((init), const unsigned *: 1, const dem_no_init *: 1, default: 0)
#define INIT_OK_BYTE(init) _Generic((init), const dem_no_init *: 1, default: 0)
#define CHECK_INIT(id_, elem, count, gate, field, init, part, move, ckpt)                                           \
    _Static_assert(INIT_OK_##elem(init), #id_ ": its SETUP member is not of its element type");
DEM_BUFFERS(CHECK_INIT)
#undef CHECK_INIT
#undef SETUP
#undef NONE

const void *dem_buffer_init(const dem_setup *s, int id)
{
#define SETUP(member) ((const void *)s->member)
#define NONE NULL
#define INIT_BUF(id_, elem, count, gate, field, init, part, move, ckpt)                                             \
    case BUF_##id_:                                                                                                  \
        return init;
    switch (id) {
        DEM_BUFFERS(INIT_BUF)
    }
#undef INIT_BUF
#undef SETUP
#undef NONE
    return NULL;
}

static int move_of(size_t *item, size_t elem_bytes, int kind, size_t per)
{
    *item = elem_bytes * per;
    return kind;
}

int dem_buffer_move(const dem_core *c, int id, size_t *item)
{
    SIZE_NAMES(c, 0);
#define STAY DEM_MOVE_STAY, 0
#define P(per) DEM_MOVE_P, (size_t)(per)
#define G(per) DEM_MOVE_G, (size_t)(per)
#define MOVE_BUF(id_, elem, count, gate, field, init, part, move, ckpt)                                             \
    case BUF_##id_:                                                                                                  \
        return move_of(item, dem_elem_size(DEM_ELEM_##elem, c->rs), move);
    switch (id) {
        DEM_BUFFERS(MOVE_BUF)
    }
#undef MOVE_BUF
#undef STAY
#undef P
#undef G
    *item = 0;
    return DEM_MOVE_STAY;
}

#define NO NULL, NULL, 0, 0
#define CK(name, width, unit) #name, unit, width, 1
#define CK_OPT(name, width, unit) #name, unit, width, 0
#define CKPT_BUF(id_, elem, count, gate, field, init, part, move, ckpt) {BUF_##id_, DEM_ELEM_##elem, gate, ckpt},
static const dem_saved_buffer saved_all[] = {DEM_BUFFERS(CKPT_BUF)};
#undef CKPT_BUF
#undef NO
#undef CK
#undef CK_OPT

const dem_saved_buffer *dem_saved_buffers(void) { return saved_all; }

size_t dem_field_size(dem_field f, unsigned effects, size_t n, size_t maxn, size_t nwalls, size_t ncells, size_t rs)
{
    dem_core c;
    memset(&c, 0, sizeof c);
    c.fx = effects, c.rs = (int)rs, c.n = (int)n, c.nwalls = (int)nwalls, c.ncells = c.cell_cap = (int)ncells;
    c.maxn[0] = c.maxn[1] = (int)maxn;
    dem_bufref r;
    size_t bytes;
    return dem_field_ref(&c, f, &r, &bytes) ? 0 : bytes;
}

size_t dem_kernel_items(const dem_core *c, dem_kernel_id k)
{
#define BIND_I(type, name, src) int name = c->si[SI_##src]; (void)name;
#define BIND_R(type, name, src)
#define BIND_BIN(type, name, src)
#define BIND_BOUT BIND_BIN
#define BIND_CIN BIND_BIN
#define BIND_COUT BIND_BIN
#define BIND_NIN BIND_BIN
#define BIND_NOUT BIND_BIN
#define BIND_AIN BIND_BIN
#define BIND_AOUT BIND_BIN
#define BIND_ARG(kind, type, name, src) BIND_##kind(type, name, src)
#define ITEMS_CASE(name)                                                                                             \
    case K_##name: {                                                                                                 \
        DEM_ARGS_##name(BIND_ARG, BIND_ARG) long items = (long)(DEM_ITEMS_##name);                                   \
        return items > 0 ? (size_t)items : 0;                                                                        \
    }
    switch (k) {
        DEM_KERNEL_LIST(ITEMS_CASE)
    default:
        return 0;
    }
}

size_t dem_ref_bytes(const dem_core *c, dem_bufref r)
{
    return r.table == TABLE_ONE ? c->bytes[r.id] : c->row_bytes[r.table == TABLE_CUR ? c->cur : 1 - c->cur][r.id];
}

/* The buffers kernel k is given (its argument list), as bound now: the first max of them, each one's argument name
 * and bytes, in argument order (names and bytes may be NULL when max is 0); *count (if given) says how many it is
 * given. Returns their bytes summed, all of them: what the kernel could move if it touched each byte once - the
 * traffic model of make bench's bandwidth column. */
size_t dem_kernel_bound_list(const dem_core *c, dem_kernel_id k, const char **names, double *bytes, int max, int *count)
{
    size_t total = 0;
    int m = 0;
/* a statement each (the argument lists have no separators between their entries) */
#define BB_ADD(name, b)                                                                                              \
    do {                                                                                                             \
        size_t nb = (b);                                                                                             \
        if (m < max) {                                                                                               \
            names[m] = #name;                                                                                        \
            bytes[m] = (double)nb;                                                                                   \
        }                                                                                                            \
        total += nb;                                                                                                 \
        m++;                                                                                                         \
    } while (0);
#define BB_I(type, name, src)
#define BB_R(type, name, src)
#define BB_BIN(type, name, src) BB_ADD(name, c->bytes[BUF_##src])
#define BB_BOUT BB_BIN
#define BB_CIN(type, name, src) BB_ADD(name, c->row_bytes[c->cur][ROW_##src])
#define BB_COUT BB_CIN
#define BB_NIN(type, name, src) BB_ADD(name, c->row_bytes[1 - c->cur][ROW_##src])
#define BB_NOUT BB_NIN
#define BB_AIN(type, name, src) BB_ADD(name, dem_ref_bytes(c, c->alias[ALIAS_##src]))
#define BB_AOUT BB_AIN
#define BB_ARG(kind, type, name, src) BB_##kind(type, name, src)
#define BB_CASE(name)                                                                                                \
    case K_##name:                                                                                                   \
        DEM_ARGS_##name(BB_ARG, BB_ARG) break;
    switch (k) {
        DEM_KERNEL_LIST(BB_CASE)
    default:
        break;
    }
    if (count)
        *count = m;
    return total;
}

int dem_stage_read_field(const dem_backend_ops *o, dem_backend *b, dem_field f, void *dst, size_t bytes)
{
    return dem_stage_read_fields(o, b, 1, &f, &dst, &bytes);
}

int dem_stage_read_fields(const dem_backend_ops *o, dem_backend *b, int count, const dem_field *f, void *const *dst,
                          const size_t *bytes)
{
    dem_core *c = DEM_CORE(b);
    for (int k = 0; k < count; k++) {
        dem_bufref r;
        size_t have;
        if (dem_field_ref(c, f[k], &r, &have) || bytes[k] > have)
            return dem_core_fail(c, "read of field %d: %zu bytes asked, %zu held", (int)f[k], bytes[k], have);
        if (bytes[k] && o->read(b, r, 0, dst[k], bytes[k], 0))
            return 1;
    }
    return o->finish(b);
}

int dem_stage_write_field(const dem_backend_ops *o, dem_backend *b, dem_field f, const void *src, size_t bytes)
{
    dem_core *c = DEM_CORE(b);
    dem_bufref r;
    size_t have;
    if (dem_field_ref(c, f, &r, &have) || bytes > have)
        return dem_core_fail(c, "write of field %d: %zu bytes given, %zu held", (int)f, bytes, have);
    return bytes ? o->write(b, r, 0, src, bytes, 1) : 0;
}

int dem_launch(const dem_backend_ops *o, dem_backend *b, dem_kernel_id k)
{
    dem_core *c = DEM_CORE(b);
    if (c->ntrace < DEM_TRACE_MAX)
        c->trace[c->ntrace] = (unsigned char)k;
    c->ntrace++;
    return o->launch(b, k);
}
