/* test_bad_input.c - bad input: one test per class of held-out bad inputs, each through the dem command as a user meets
 * it (status, message, and what is left on disk). Classes: 1 memory safety (sizes from user numbers counted before any
 * allocation), 2 one output silently replacing another, 3 restored state checked, 4 inputs that hang or cost before
 * they are refused, 5 exit codes and messages against the docs, 6 the output's name escaped in the XDMF sidecar. */
#include "test_util.h"
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#define DEM DEM_DEFAULT_SOURCE_DIR "/build/dem"
#define SRC DEM_DEFAULT_SOURCE_DIR
#define TUBE SRC "/tests/scenes/membrane_tube.yaml"
#define TWO SRC "/scenes/two_spheres.yaml"
static char tmp[256];

/* A shell command (printf-style) run in the test's folder, its stderr into err; its exit status */
static int sh(char *err, size_t len, const char *fmt, ...)
{
    char cmd[4096];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(cmd, sizeof cmd, fmt, ap);
    va_end(ap);
    return test_sh(tmp, err, len, "cd '%s' && { %s; }", tmp, cmd);
}

static int exists(const char *name)
{
    char p[512];
    struct stat sb;
    snprintf(p, sizeof p, "%s/%s", tmp, name);
    return stat(p, &sb) == 0;
}

typedef struct {
    const char *cmd; /* run in tmp by sh; %1$s: the dem command, %2$s: the sources, %3$s: test_python()'s Python */
    int code;
    const char *expect, *expect2; /* both in its messages (expect2 may be NULL) */
} cli_case;

/* Each case's status and message; never HDF5's own error stack, never a sanitizer's or the C library's abort. */
static void run_cases(const char *what, const cli_case *c, size_t n)
{
    char err[16384];
    for (size_t k = 0; k < n; k++) {
        /* a case that runs Python looks for it (and fails the test, saying what is missing, without one) */
        int rc = sh(err, sizeof err, c[k].cmd, DEM, SRC, strstr(c[k].cmd, "%3$s") ? test_python() : "");
        if (rc != c[k].code || !strstr(err, c[k].expect) || (c[k].expect2 && !strstr(err, c[k].expect2)) ||
            strstr(err, "HDF5-DIAG") || strstr(err, "runtime error") || strstr(err, "malloc"))
            fail_msg("%s, case %zu (%s): status %d (want %d), message: %s (want '%s'%s%s)", what, k, c[k].cmd, rc,
                     c[k].code, err, c[k].expect, c[k].expect2 ? " and " : "", c[k].expect2 ? c[k].expect2 : "");
    }
}

/* A checkpoint of restart_box at step 100 (good.ckpt.h5), once */
static void good_checkpoint(void)
{
    char err[8192];
    if (!exists("good.ckpt.h5"))
        assert_int_equal(sh(err, sizeof err, "%s run %s/tests/scenes/restart_box.yaml -o good.h5 --quiet --stop-after 100",
                            DEM, SRC),
                         0);
}

/* Class 1: memory safety. An array where the checkpoint's scene text or path is one string overwrote the heap; a
 * tube of radius 1e-30 m and height 5.3e18 m wrapped its vertex count to 2051 and crashed dem check; a huge sheet
 * overflowed its count; an infinite bound of a random region reached the placement hash as a signed overflow. */
static void test_memory_safety(void **st)
{
    (void)st;
    good_checkpoint();
    static const cli_case c[] = {
        {"%3$s %2$s/tests/craft_checkpoint.py good.ckpt.h5 t.ckpt.h5 text_array && %1$s run --restart "
         "t.ckpt.h5 -o a1.h5 --quiet", 65, "/scene/text is missing or not one fixed-length string", NULL},
        {"%3$s %2$s/tests/craft_checkpoint.py good.ckpt.h5 p.ckpt.h5 path_array && %1$s run --restart "
         "p.ckpt.h5 -o a1.h5 --quiet", 65, "/scene/path is missing or not one fixed-length string", NULL},
        {"sed 's|mesh: {kind: tube.*|mesh: {kind: tube, radius: 1.0e-30, height: 5.3e18, edge: 1}|' " TUBE " > t1.yaml "
         "&& %1$s check t1.yaml", 65, "t1.yaml:23: membranes[0].mesh.edge: edges of 1 m make 1.84e+19 vertices", NULL},
        {"sed 's|mesh: {kind: tube.*|mesh: {kind: sheet, size: [1.0e18, 1.0e18], edge: 1.0e-3}|' " TUBE " > t2.yaml "
         "&& %1$s check t2.yaml", 65, "t2.yaml:23: membranes[0].mesh.edge: edges of 0.001 m make", "vertices (at most"},
        {"sed 's|mesh: {kind: tube.*|mesh: {kind: tube, radius: 1.0e150, height: 1.0e150, edge: 1.0e-150}|' " TUBE
         " > t3.yaml && %1$s check t3.yaml", 65, "membranes[0].mesh.edge: edges of 1e-150 m make inf vertices", NULL},
        {"sed 's|kind: lattice, shape: cylinder, region: {base: \\[0, 0, 0.0035\\]|kind: random, count: 10, shape: "
         "cylinder, region: {base: [0, 0, inf]|' " TUBE " > t4.yaml && %1$s check t4.yaml", 65,
         "t4.yaml:10: particles[0].generate.region: a cylinder region needs a finite base", NULL},
    };
    run_cases("memory safety", c, sizeof c / sizeof c[0]);
    char err[8192]; /* a box region with an infinite bound, written out whole */
    assert_int_equal(sh(err, sizeof err, "printf 'effects: [hertz]\\nmaterials: [{name: m, density: 1000, young: 1e6, "
                                         "poisson: 0.3, restitution: 0.5}]\\nparticles:\\n  - {material: m, generate: "
                                         "{kind: random, shape: box, region: {lo: [0, 0, 0], hi: [1, 1, inf]}, count: "
                                         "5, radius: 0.01, seed: 1}}\\ntime: {dt_rayleigh: 0.2, duration: 0.001}\\n' > "
                                         "inf.yaml && %s check inf.yaml", DEM),
                     65);
    assert_non_null(strstr(err, "inf.yaml:4: particles[0].generate.region: a box region needs finite lo < hi"));
    assert_false(exists("a1.h5") || exists("a1.h5.part") || exists("a1.ckpt.h5"));
}

/* Class 2: one output may not silently replace another. --checkpoint naming OUT.h5, OUT.xmf or OUT.h5.part was
 * accepted (with OUT.h5.part the finished OUT.h5 was the checkpoint, the frames gone); a finished run's checkpoint
 * restarted exited 0 and wrote no OUT.ckpt.h5. */
static void test_outputs_distinct(void **st)
{
    (void)st;
    static const cli_case c[] = {
        {"%1$s run " TWO " -o o.h5 --checkpoint o.h5 --quiet", 2, "o.h5: the run would write the output and the "
                                                                 "checkpoint to this one file; choose another --checkpoint",
         NULL},
        {"%1$s run " TWO " -o o.h5 --checkpoint o.xmf --quiet", 2, "would write the XDMF sidecar and the checkpoint", NULL},
        {"%1$s run " TWO " -o o.h5 --checkpoint o.h5.part --quiet", 2, "would write the output's .part and the checkpoint",
         NULL},
        {"mkdir -p sub && %1$s run " TWO " -o sub/../o.h5 --checkpoint ./o.xmf.part --quiet", 2,
         "would write the XDMF sidecar's .part and the checkpoint", NULL},
        {"%1$s run " TWO " -o o.h5.tmp --checkpoint o.h5 --quiet", 2,
         "o.h5.tmp: the run would write the output and the checkpoint's .tmp to this one file", NULL},
    };
    run_cases("outputs", c, sizeof c / sizeof c[0]);
    assert_false(exists("o.h5") || exists("o.h5.part") || exists("o.xmf") || exists("o.ckpt.h5") || exists("o.h5.tmp"));
    char err[8192];
    assert_int_equal(sh(err, sizeof err, "%s run " TWO " -o done.h5 --quiet", DEM), 0);
    static const cli_case again[] = {
        {"%1$s run --restart done.ckpt.h5 -o more.h5 --quiet", 65,
         "done.ckpt.h5: the checkpoint is at step 3000, the end of the scene (3000 steps", "nothing is left to run"},
    };
    run_cases("a finished run", again, 1);
    assert_false(exists("more.h5") || exists("more.h5.part") || exists("more.xmf") || exists("more.ckpt.h5"));
}

/* Class 3: restored state is checked. A nan wall position was accepted (the wall stopped acting, the nan went to the
 * next checkpoint), an infinite spin ran on, a nan velocity failed at step 10 with status 1: each is refused with 65
 * and the dataset's name, and nothing is written. */
static void test_restored_state(void **st)
{
    (void)st;
    good_checkpoint();
    static const cli_case c[] = {
        {"%3$s %2$s/tests/craft_checkpoint.py good.ckpt.h5 b.ckpt.h5 wall_pos_nan && %1$s run --restart "
         "b.ckpt.h5 -o r.h5 --quiet", 65, "b.ckpt.h5: /state/wall_pos: element 2 is nan", NULL},
        {"%3$s %2$s/tests/craft_checkpoint.py good.ckpt.h5 b.ckpt.h5 spin_inf && %1$s run --restart "
         "b.ckpt.h5 -o r.h5 --quiet", 65, "b.ckpt.h5: /state/w: element 10 is inf", NULL},
        {"%3$s %2$s/tests/craft_checkpoint.py good.ckpt.h5 b.ckpt.h5 v_nan && %1$s run --restart "
         "b.ckpt.h5 -o r.h5 --quiet", 65, "b.ckpt.h5: /state/v: element 15 is nan", NULL},
        {"%3$s %2$s/tests/craft_checkpoint.py good.ckpt.h5 b.ckpt.h5 radius_zero && %1$s run --restart "
         "b.ckpt.h5 -o r.h5 --quiet", 65, "b.ckpt.h5: /state/radius: element 2 is 0", NULL},
    };
    run_cases("restored state", c, sizeof c / sizeof c[0]);
    assert_false(exists("r.h5") || exists("r.h5.part") || exists("r.xmf") || exists("r.ckpt.h5"));
}

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Class 4: inputs that hang or cost before they are refused. A named pipe as the scene, a mesh, a CSV file or the
 * checkpoint blocked for ever (timeout 20 would kill it: status 124); /dev/zero as the scene was read to 1 GB; a tube
 * of 1.9e6 vertices took 17.6 s and 1.35 GB in dem check before its time step was refused. */
static void test_costly_inputs(void **st)
{
    (void)st;
    char err[8192];
    assert_int_equal(sh(err, sizeof err, "mkfifo pipe.yaml pipe.obj pipe.csv pipe.ckpt.h5"), 0);
    static const cli_case c[] = {
        {"timeout 20 %1$s check pipe.yaml", 66, "pipe.yaml:0: cannot open the scene file: not a regular file (a pipe)",
         NULL},
        {"timeout 20 %1$s run pipe.yaml -o x.h5", 66, "pipe.yaml:0: cannot open the scene file: not a regular file", NULL},
        {"timeout 20 %1$s check /dev/zero", 66, "/dev/zero:0: cannot open the scene file: not a regular file (a device)",
         NULL},
        {"timeout 20 %1$s check .", 66, "cannot open the scene file: not a regular file (a folder)", NULL},
        {"sed 's|mesh: {kind: tube.*|mesh: {kind: file, path: pipe.obj}|' " TUBE " > m.yaml && timeout 20 %1$s check "
         "m.yaml", 66, "m.yaml:23: membranes[0].mesh.path: ./pipe.obj: cannot open the mesh file: not a regular file",
         NULL},
        {"sed 's|csv: data/hydrogel_514.csv|csv: pipe.csv|' %2$s/scenes/hydrogel_514.yaml > c.yaml && timeout 20 %1$s "
         "check c.yaml", 66, "c.yaml:17: particles[0].csv: cannot open './pipe.csv': not a regular file (a pipe)", NULL},
        {"timeout 20 %1$s run --restart pipe.ckpt.h5 -o x.h5", 66,
         "pipe.ckpt.h5: cannot open the checkpoint: not a regular file", NULL},
    };
    run_cases("costly inputs", c, sizeof c / sizeof c[0]);
    assert_false(exists("x.h5") || exists("x.h5.part"));
    /* the tube of 1.9e6 vertices: refused from its spec, before the mesh is made (it took 11-17 s) */
    double t0 = now();
    int rc = sh(err, sizeof err, "sed 's|edge: 0.006}|edge: 5.53e-5}|' " TUBE " > big.yaml && %s check big.yaml", DEM);
    double took = now() - t0;
    if (rc != 65 || !strstr(err, "big.yaml:23: membranes[0].mesh.edge: edges of 5.53e-05 m make 1899392 vertices") ||
        !strstr(err, "refused before the mesh is made") || took > 3)
        fail_msg("the 1.9e6-vertex tube: status %d after %.1f s: %s", rc, took, err);
    /* the same with time.dt: the bound is sure without the Rayleigh times */
    rc = sh(err, sizeof err, "sed 's|edge: 0.006}|edge: 5.53e-5}|; s|time: {dt_rayleigh: 0.2,|time: {dt: 1.0e-5,|' " TUBE
                             " > big2.yaml && %s check big2.yaml", DEM);
    if (rc != 65 || !strstr(err, "the scene's time.dt gives 1e-05 s: refused before the mesh is made"))
        fail_msg("the 1.9e6-vertex tube with time.dt: status %d: %s", rc, err);
}

/* Class 5: exit codes and messages as README.md's table and docs/scenes.md say. */
static void test_codes_and_messages(void **st)
{
    (void)st;
    char err[8192];
    assert_int_equal(sh(err, sizeof err, "mkdir -p outdir && printf 'v 0 0 0\\nv 0 0 0\\nv 0 1 0\\nf 1 2 3\\n' > same.obj"),
                     0);
    static const cli_case c[] = {
        /* a missing mesh file: 66 (was 65) */
        {"sed 's|mesh: {kind: tube.*|mesh: {kind: file, path: none.obj}|' " TUBE " > nm.yaml && %1$s check nm.yaml", 66,
         "nm.yaml:23: membranes[0].mesh.path: ./none.obj: cannot open the mesh file: No such file", NULL},
        /* -o naming a directory: 74, the output cannot be written (was 2) */
        {"%1$s run " TWO " -o outdir --quiet", 74, "outdir: cannot write it: is a directory", NULL},
        /* a nan translate, coincident corners, a tube too large to measure: blamed on what is wrong, not on "young,
         * thickness, density and vertex_radius must be > 0 (got nan m)" */
        {"printf 'v 0 0 0\\nv 1 0 0\\nv 0 1 0\\nf 1 2 3\\n' > tri.obj && sed 's|mesh: {kind: tube.*|mesh: {kind: file, "
         "path: tri.obj, translate: [0, nan, 0]}|; s|attach: .*||' " TUBE " > tr2.yaml && %1$s check tr2.yaml", 65,
         "tr2.yaml:23: membranes[0].mesh.translate: must be finite [m]", NULL},
        {"sed 's|mesh: {kind: tube.*|mesh: {kind: file, path: same.obj}|; s|attach: .*||' " TUBE " > co.yaml && %1$s "
         "check co.yaml", 65, "co.yaml:23: membranes[0].mesh: its shortest edge comes out 0 m: two corners of a "
                              "triangle coincide", NULL},
        {"sed 's|mesh: {kind: tube.*|mesh: {kind: tube, radius: 1.0e300, height: 1.0e300, edge: 1.0e299}|' " TUBE
         " > r300.yaml && %1$s check r300.yaml", 65, "r300.yaml:23: membranes[0].mesh: its shortest edge comes out inf m",
         NULL},
        /* YAML syntax errors: the key on the line where libyaml stopped, not a field "libyaml"; a truncated file's
         * error at its last line, not the one after; a bad indent at its own line's key */
        {"printf 'name: x\\neffects: [hertz\\n' > y1.yaml && %1$s check y1.yaml", 65,
         "y1.yaml:2: effects: YAML syntax error: did not find expected ',' or ']'", NULL},
        {"head -c 300 " TWO " > y2.yaml && %1$s check y2.yaml", 65, "y2.yaml:7: YAML syntax error: did not find expected",
         NULL},
        {"printf 'name: \"x\\n' > y3.yaml && %1$s check y3.yaml", 65, "y3.yaml:1: name: YAML syntax error", NULL},
        {"printf 'name: x\\nprecision: fp64\\n  effects: [hertz]\\n' > y4.yaml && %1$s check y4.yaml", 65,
         "y4.yaml:3: effects: YAML syntax error: mapping values are not allowed", NULL},
        /* a sphere in a wall: at the sphere's line, the wall named with its own */
        {"sed 's/hertz, damping/hertz, damping, walls/; s/^particles:/walls: [{type: plane, material: rubber, point: "
         "[0, 0, -0.005], normal: [0, 0, 1]}]\\nparticles:/' " TWO " > w.yaml && %1$s check w.yaml", 65,
         "w.yaml:12: particles[0].spheres[0]: particles[0].spheres[0] (radius 0.01 m", "overlaps wall walls[0] (line 8)"},
        /* plain numbers only: strtod reads hex */
        {"sed 's/dt: 1.0e-6 /dt: 0x10 /' " TWO " > h.yaml && %1$s check h.yaml", 65,
         "h.yaml:15: time.dt: '0x10' is not a number", NULL},
        {"sed 's/density: 2000/density: -0X7D0/' " TWO " > h2.yaml && %1$s check h2.yaml", 65,
         "h2.yaml:7: materials[0].density: '-0X7D0' is not a number", NULL},
        /* an empty file names the first key it lacks */
        {": > e.yaml && %1$s check e.yaml", 65, "e.yaml:1: effects: missing: the scene is empty", NULL},
    };
    run_cases("codes and messages", c, sizeof c / sizeof c[0]);
}

/* Class 5 too: a misspelt key, effect, material or wall name is refused with the nearest known one (an edit distance
 * over the mapping's keys in the schema, the scene's walls or materials); a word near none gets no guess. */
#define PP SRC "/examples/pour_press_small.yaml"
static void test_did_you_mean(void **st)
{
    (void)st;
    static const cli_case c[] = {
        {"sed 's/^precision: fp64/precison: fp64/' " PP " > k1.yaml && %1$s check k1.yaml", 65,
         "k1.yaml:4: precison: Unexpected key: precison (Invalid key) (did you mean 'precision'?)", NULL},
        /* the keys of the mapping the key is in: generate's, the time block's, a wall's (a swap of two letters) */
        {"sed 's/radius_min: 0.001,/radus_min: 0.001,/' " PP " > k2.yaml && %1$s check k2.yaml", 65,
         "particles[0].generate.radus_min: Unexpected key", "(did you mean 'radius_min'?)"},
        {"sed 's/settle: 0.3/setle: 0.3/' " PP " > k3.yaml && %1$s check k3.yaml", 65, "time.setle: Unexpected key",
         "(did you mean 'settle'?)"},
        {"sed 's/normal: \\[0, 0, -1\\]/nromal: [0, 0, -1]/' " PP " > k4.yaml && %1$s check k4.yaml", 65,
         "walls[2].nromal: Unexpected key", "(did you mean 'normal'?)"},
        {"sed 's/gravity, walls]/gravty, walls]/' " PP " > k5.yaml && %1$s check k5.yaml", 65,
         "unknown effect 'gravty'", "(did you mean 'gravity'?)"},
        {"sed 's/material: bead/material: baed/' " PP " > k6.yaml && %1$s check k6.yaml", 65,
         "particles[0].material: unknown material 'baed' (did you mean 'bead'?)", NULL},
        /* sample.piston names plane walls: 'dei' is near the die, a cylinder, and gets no guess; 'pistn' does */
        {"sed 's/piston: piston}/piston: pistn}/' " PP " > k7.yaml && %1$s check k7.yaml", 65,
         "sample.piston: no plane wall named 'pistn' (did you mean 'piston'?)", NULL},
        {"sed 's/piston: piston}/piston: dei}/' " PP " > k8.yaml && %1$s check k8.yaml", 65,
         "sample.piston: no plane wall named 'dei'\n", NULL},
        /* nothing near: no guess */
        {"sed 's/^precision: fp64/zzzzzz: fp64/' " PP " > k9.yaml && %1$s check k9.yaml", 65,
         "k9.yaml:4: zzzzzz: Unexpected key: zzzzzz (Invalid key)\n", NULL},
    };
    run_cases("did you mean", c, sizeof c / sizeof c[0]);
}

/* Class 6: the output's name is escaped in the XDMF sidecar (it was written raw: -o '<&"x>.h5' made invalid XML);
 * a name XML cannot hold at all (a control character, invalid UTF-8) is refused before the run. */
static void test_xdmf_escaping(void **st)
{
    (void)st;
    char err[8192];
    assert_int_equal(sh(err, sizeof err, "%s run " TWO " -o '<&\"x>.h5' --quiet --stop-after 10", DEM), 0);
    assert_int_equal(sh(err, sizeof err, "%s -c 'import sys, xml.etree.ElementTree as E; "
                                         "E.parse(sys.argv[1])' '<&\"x>.xmf'", test_python()),
                     0);
    assert_int_equal(sh(err, sizeof err, "grep -qF '&lt;&amp;&quot;x&gt;.h5:/frames/position' '<&\"x>.xmf'"), 0);
    static const cli_case c[] = {
        {"%1$s run " TWO " -o \"$(printf 'a\\001b.h5')\" --quiet", 2, "a\\x01b.h5: the output's name has a control "
                                                                      "character or is not UTF-8", NULL},
        {"%1$s run " TWO " -o \"$(printf 'a\\377b.h5')\" --quiet", 2, "is not UTF-8", NULL},
    };
    run_cases("XDMF names", c, sizeof c / sizeof c[0]);
}

static int setup(void **st) { (void)st; return test_tmpdir_make(tmp, sizeof tmp, "dem-test-bad-input"); }
static int teardown(void **st) { (void)st; return test_tmpdir_remove(tmp); }

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_memory_safety),      cmocka_unit_test(test_outputs_distinct),
        cmocka_unit_test(test_restored_state),     cmocka_unit_test(test_costly_inputs),
        cmocka_unit_test(test_codes_and_messages), cmocka_unit_test(test_xdmf_escaping),
        cmocka_unit_test(test_did_you_mean),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
