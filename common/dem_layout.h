/* dem_layout.h - buffer layouts shared by the host, the kernels and the reference (declared once).
 *
 * Per-particle vectors are interleaved xyz: x[3*i+0..2]. Tables are flat `real` arrays with a fixed
 * stride and the named offsets below, so no struct layout has to agree between host and device compilers.
 * Units are SI throughout: m, kg, s, Pa, N, N m, rad/s.
 */
#ifndef DEM_LAYOUT_H
#define DEM_LAYOUT_H

/* Per material pair (table index mi*nmat+mj, symmetric), computed on the host once. */
enum {
    PM_ESTAR = 0, /* effective Young's modulus E*  [Pa]   (seed 000 Eq. 3) */
    PM_GSTAR = 1, /* effective shear modulus G*    [Pa]   (seed 000 Eq. 5) */
    PM_MU = 2,    /* Coulomb friction coefficient  [-] */
    PM_DAMP_N = 3, /* c sqrt(2 E*): normal damping is -PM_DAMP_N sqrt(sqrt(r* d) m*) v_n   [sqrt(Pa)] */
    PM_DAMP_T = 4, /* c sqrt(8 G*): tangential damping is -PM_DAMP_T sqrt(sqrt(r* d) m*) v_t [sqrt(Pa)] */
                   /* c: damping factor calibrated from restitution (host/physics/restitution.c) */
    PM_MC_STRESS = 5, /* pi beta nu, mean of the two materials' beta nu (seed 000 Eq. 10: A = pi r* d) [-] */
    /* MC-strain constants of ONE material (Eq. 7); meaningful on the diagonal entry m*nmat+m of material m, which
     * is where a particle of material m looks them up (the deformation field is that of its own material). */
    PM_MCS_K = 6,  /* gamma (1 + nu) / (2 pi E) [1/Pa] */
    PM_MCS_C1 = 7, /* 3 - 4 nu */
    PM_MCS_C2 = 8, /* 1 - 2 nu */
    PM_MC_REACH = 9, /* MC-strain contact distance factor F >= 1, the same in every entry (dem_effects.h) [-] */
    PM_APART = 10,   /* 1: particles of this pair of materials never touch - two vertices of one membrane, whose
                        spheres may overlap (dem_add_membrane); read with DEM_EFFECT_SPRINGS only (neighbor.h) */
    /* Thornton-Ning's yield (common/laws/thornton_ning.h), from p_y, the smaller yield stress of the two materials
     * (dem_material.yield_stress; 0 in all three when neither yields: the law is then Hertz's) */
    PM_TN_PIPY = 11, /* pi p_y: the plastic branch's slope per r* [Pa] */
    PM_TN_DY = 12,   /* delta_y / r* = (pi p_y / (2 E*))^2: the overlap at first yield per effective radius [-] */
    PM_TN_FY = 13,   /* F_y / r*^2 = 4/3 E* (delta_y / r*)^(3/2): the force at first yield per r*^2 [Pa] */
    PM_MU_ROLL = 14, /* rolling resistance coefficient mu_r, the mean of the two materials' (common/rolling.h) [-] */
    PM_TN_SIGB = 15, /* pi sigma_b: a yielded Thornton-Ning contact's bond holds a tension up to PM_TN_SIGB a_p^2, its
                        plastic contact area times the bond strength sigma_b (dem_material.bond_strength; the smaller
                        of the two materials', 0: no bond); an MDR side's up to PM_TN_SIGB a_max^2 (laws/mdr_core.h
                        mdr_side_bond) [Pa] */
    PM_ROLL_DAMP = 16, /* rolling viscous damping ratio eta_r of the spring model, the mean of the two materials'
                          (common/rolling.h) [-] */
    /* MDR (common/laws/mdr.h): the material of the row's sphere in mdr_material's order (laws/mdr_core.h): E* =
     * E/(1 - nu^2) of one sphere on a rigid flat, G, the bulk modulus, nu, the yield stress Y, the surface energy (a
     * wall material's own at a wall), psi_b and eta_d (host/core/sim_setup.c pack_pairs) */
    PM_MDR = 17,
    /* Thornton-Ning's JKR adhesion (DEM_EFFECT_ADHESION, laws/thornton_ning.h): k = sqrt(2 pi w / E*), w the pair's
     * work of adhesion (the geometric mean of its materials' surface_energy; 0: none), so that a contact of radius a
     * sits k sqrt(a) below its non-adhesive overlap and pulls with 2 E* k a sqrt(a) (JKR) [m^(1/2)] */
    PM_TN_K = 25,
    PM_STRIDE = 26
};

/* MDR's state (common/laws/mdr.h, docs/laws/mdr.md (M37)). One side of a contact, mdr_side's order (laws/mdr_core.h):
 * its overlap share and that against R_o of the last step, the MDR and bulk parts of it, its last area, the largest
 * MDR part, the yield flag, the area intercept, the adhesive radius, the last strain and the plastic overlap. */
enum { MDR_SIDE = 11 };
/* A pair's row (in PAIR_LAW): the contact's largest overlap, its penalty of this step (M40), side 0 (the sphere of
 * higher stable id), side 1, and the contact's elastic normal force of the last step (the stress output's); a
 * particle-wall slot's row (in WALL_LAW): the largest overlap, the elastic normal force, the side. A particle's row (MDR_PART): mdr_particle's 14 reals. A pair side's sums for its particle (PAIR_MDR_SUM: 6 per
 * side, mdr_particle's vcaps .. atot_sum). */
enum {
    MDR_CMAX = 0,
    MDR_PEN = 1,
    MDR_S0 = 2,
    MDR_FEL_PAIR = 2 + 2 * MDR_SIDE,
    MDR_PAIR_STRIDE = 3 + 2 * MDR_SIDE,
    MDR_FEL_WALL = 1,
    MDR_WALL_STRIDE = 2 + MDR_SIDE,
    MDR_P_STRIDE = 14,
    MDR_P_SUMS = 4, /* where the six sums start in a particle's row */
    MDR_NSUM = 6
};

/* Spring table, real part (index s*SP_STRIDE + ...; seed 001 Eq. 6): the two particles are in the int table
 * spring_int[2s], [2s+1]. */
enum {
    SP_K = 0,    /* spring constant k [N/m] */
    SP_REST = 1, /* rest length rho^0 [m] */
    SP_DAMP = 2, /* 2 gamma sqrt(k m_eff) [kg/s], m_eff of the two particles (host/core/sim_setup.c) */
    SP_STRIDE = 3
};

/* Hinge table, real part (index h*HG_STRIDE + ...; seed 001 Eq. 11-12): the four particles are in hinge_int[4h..] */
enum {
    HG_KEL = 0,  /* elastic constant k_el [N/m] */
    HG_KDISS = 1, /* dissipative constant k_diss [N s/m] */
    HG_SIN0 = 2, /* sin(theta0 / 2) of the rest angle, signed as theta (bending.h) */
    HG_STRIDE = 3
};

/* Wall geometry and motion, real part (index w*W_STRIDE + ...). */
enum {
    W_PX = 0, W_PY, W_PZ, /* plane: a point on it; cylinder: a point on its axis [m] */
    W_NX, W_NY, W_NZ,     /* plane: unit normal pointing into the particle side; cylinder: unit axis */
    W_RADIUS,             /* cylinder radius [m] (particles live inside); cup plane: the cup's radius [m] */
    W_VX, W_VY, W_VZ,     /* wall velocity during the current step [m/s] */
    W_HEIGHT,             /* cylinder length from the point along the axis [m]; 0: endless; cup plane: its depth [m] */
    W_STRIDE
};
/* Wall integer part (index w*WI_STRIDE + ...). */
enum { WI_TYPE = 0, WI_MATERIAL = 1, WI_STRIDE = 2 };
/* WALL_PLANE_CUP: a plane whose face has a spherical cup about the normal through its point, recessed away from the
 * particles (a concave punch): W_RADIUS the cup's radius at the face, W_HEIGHT its depth at the centre */
enum { WALL_PLANE = 0, WALL_CYLINDER_INSIDE = 1, WALL_PLANE_CUP = 2 };

/* Result of a touching pair, left by contact_pairs (one work item per listed pair) for contact_forces: the force on
 * the pair's particle of lower stable id. Records are numbered by the pair's host, the particle stored first
 * (neighbor.h): particle i's hosted pairs (partners stored after it) are own_start[i] ... own_start[i + 1] - 1, the
 * others are in_pair[in_start[i] ...]. 7 reals per pair. */
enum {
    PR_FX = 0, PR_FY, PR_FZ, /* force on the lower id [N] */
    PR_CX, PR_CY, PR_CZ,     /* n x f_t [N] */
    PR_DELTA,                /* overlap [m] */
    PR_STRIDE = 7            /* unpadded: 56 bytes per pair in fp64 (padding to 8 bought no speed) */
};

/* A sphere's patch contact, left by patch_forces for the triangle's vertices (patch_contacts.h): one record per
 * sphere row slot. */
enum {
    PK_FX = 0, PK_FY, PK_FZ, /* force on the sphere [N] */
    PK_W0, PK_W1, PK_W2,     /* barycentric weights of the contact point on the triangle's vertices 0, 1, 2 */
    PK_STRIDE = 6
};

/* A sphere-patch contact's flags (BUF_PTOUCH, common/patch_contacts.h): kept in the previous step (a contact: its
 * force, its tangential history); the side of the patch the sphere is on is known, and it is below (where the
 * triangle's normal N = (x_b - x_a) x (x_c - x_a) points away from); the sphere's centre has crossed the patch's plane
 * (the contact pushes it back). The side is kept for every slot whose sphere touches the patch, kept by the selection
 * or not. PATCH_KEPT and PATCH_NEXT_*: kept now and the next step's side, only between patch_forces' passes.
 * PATCH_SAVED: the bits a state and a checkpoint keep. */
#define PATCH_TOUCHED 1u
#define PATCH_KEPT 2u
#define PATCH_BELOW 4u
#define PATCH_KNOWN 8u
#define PATCH_CROSSED 16u
#define PATCH_NEXT_BELOW 32u
#define PATCH_NEXT_KNOWN 64u
#define PATCH_NEXT_CROSSED 128u
#define PATCH_SAVED (PATCH_TOUCHED | PATCH_BELOW | PATCH_KNOWN | PATCH_CROSSED)

/* Integer status flags written by kernels (integer atomics only), read by the host. */
enum {
    FLAG_REBUILD = 0,       /* set to 1 when some particle moved more than skin/2 since the last build */
    FLAG_OUT_OF_DOMAIN = 1, /* smallest id of a particle outside the binning domain (or non-finite); INT_MAX if none */
    FLAG_NBR_WIDEST = 2,    /* the longest neighbour row counted since the flags were last reset */
    FLAG_ASYMMETRIC = 3,    /* a bug: 1 when some row lacks its partner's mirror slot (rows are symmetric), 2 when a
                               row's fill found other partners than its count (neighbor.h) */
    FLAG_MC_PENDING = 4,    /* MC-strain iteration: 1 when some contact force changed by more than the tolerance */
    FLAG_PATCH_NEEDED = 5,  /* largest sphere patch row found (patch_contacts.h); > capacity: overflowed */
    FLAG_VROW_NEEDED = 6,   /* largest vertex row found; > capacity: overflowed */
    FLAG_PATCH_REACH = 7,   /* 1 when a patch edge is not shorter than the search reach */
    FLAG_CELL_LO = 8,       /* 8, 9, 10: the lowest cell along x, y, z of the domain's grid that holds a particle
                               (bin_bounds; INT_MAX when none) ... */
    FLAG_CELL_HI = 11,      /* 11, 12, 13: ... and the highest (-1 when none): the cells the binning uses */
    FLAG_MDR_CAPPED = 14,   /* MDR: smallest storage slot of a particle whose apparent radius met the law's cap of
                               1.5 R_o this step (mdr_begin, laws/mdr_core.h mdr_particle_begin); INT_MAX if none */
    FLAG_COUNT = 15
};
#define DEM_NO_PARTICLE 2147483647
/* Per-particle symmetric stress tensor (DEM_FIELD_STRESS): 6 reals per particle in this order [Pa]. */
enum { ST_XX = 0, ST_YY, ST_ZZ, ST_XY, ST_XZ, ST_YZ, ST_STRIDE };

/* A block's sums for one wall (wall_reduce_block; exact accumulators, common/exact_sum.h, in the partial buffers; the
 * rounded sums in a series row): the force the wall received, and the sum of the normal
 * force components (each particle's force from the wall along its contact normal: for a cylinder the radial force on
 * the die wall, for a plane its normal force) [N]. */
enum { WP_FX = 0, WP_FY, WP_FZ, WP_FN, WP_STRIDE };
/* The wall-force reduction is a tree of three levels of exact sums: blocks of DEM_REDUCE_BLOCK particles as stored
 * (wall_reduce_block), groups of DEM_REDUCE_FAN consecutive blocks (wall_reduce_mid), and the groups
 * (wall_reduce_final), which rounds once. The sums are exact, so the bits are the correctly rounded sum's whatever the
 * tree, the order or the device; the tree only spreads the work: no level's item merges more than max(256, 64,
 * n / 16384) terms (62 at 1e6), where one item per wall adding every block was 73 % of a 1e6 press's step on a GPU
 * (docs/design.md "The walls' sum as a tree"). */
#define DEM_REDUCE_BLOCK 256
#define DEM_REDUCE_FAN 64
/* A particle's wall mask holds one bit per wall: the most walls a kernel meets (dem.h's DEM_MAX_WALLS, checked
 * against it in host/core/sim_setup.c) */
#define DEM_WALL_MASK_BITS 32
/* A time-series row's terms per particle (series.h), in the ring's slot of each particle and sampled step: kinetic
 * energy (translation and rotation) [J], gravitational potential energy [J], Hertz elastic energy of the contacts it
 * owns (pairs with higher ids, walls) [J], those touching pairs, those touching walls. */
enum { SE_KIN = 0, SE_POT, SE_ELA, SE_CON, SE_WCON, SE_STRIDE };
/* Sampled steps the device holds before the host reads them: up to DEM_SERIES_RING, as many as fit in
 * DEM_SERIES_RING_BYTES of per-particle terms (at least one). */
#define DEM_SERIES_RING 64
#define DEM_SERIES_RING_BYTES (8 << 20)
/* A message row of a run split over ranks (halo.h): what a step reads of a particle, 3 reals each: position [m],
 * velocity [m/s], spin [rad/s], force [N], torque [N m]. */
enum { HALO_X = 0, HALO_V = 3, HALO_WV = 6, HALO_F = 9, HALO_T = 12, HALO_W = 15 };
/* Items per block of the integer exclusive scan (binning.h). */
#define DEM_SCAN_BLOCK 1024

#endif /* DEM_LAYOUT_H */
