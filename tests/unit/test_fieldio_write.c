/* SPDX-License-Identifier: GPL-3.0-or-later
 * test_fieldio_write.c -- field.c and the writing half of fieldio.h.
 *
 * Expected texts are OpenFOAM v1912's layout as icoFoam writes it (checked
 * byte for byte against icoFoam output of a case with every supported
 * boundary type, ascii, binary and gzip); the banner may differ, so files
 * are compared from the "FoamFile" line on and the banner's shape is
 * checked separately.
 */
#include "testutil.h"

#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include "umppm/field.h"
#include "umppm/fieldio.h"

/* ---- helpers ---------------------------------------------------------- */

static char *slurp(const char *path, size_t *len)
{
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return NULL;
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap + 1);
    size_t k;
    while ((k = fread(buf + n, 1, cap - n, fp)) > 0) {
        n += k;
        if (n == cap) {
            cap *= 2;
            buf = realloc(buf, cap + 1);
        }
    }
    fclose(fp);
    buf[n] = '\0';
    if (len)
        *len = n;
    return buf;
}

static char *gunzip_file(const char *path, size_t *len)
{
    gzFile gz = gzopen(path, "rb");
    if (!gz)
        return NULL;
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap + 1);
    int k;
    while ((k = gzread(gz, buf + n, (unsigned)(cap - n))) > 0) {
        n += (size_t)k;
        if (n == cap) {
            cap *= 2;
            buf = realloc(buf, cap + 1);
        }
    }
    gzclose(gz);
    buf[n] = '\0';
    if (len)
        *len = n;
    return buf;
}

/* tu_write for directories held in 4096-byte buffers (fio_timedir). */
static void put_file(const char *dir, const char *name, const char *text)
{
    size_t n = strlen(dir) + strlen(name) + 2;
    char *path = malloc(n);
    snprintf(path, n, "%s/%s", dir, name);
    FILE *fp = fopen(path, "wb");
    if (!fp)
        fail_msg("cannot write %s", path);
    fputs(text, fp);
    fclose(fp);
    free(path);
}

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* The file from its "FoamFile" line on, after checking the banner shape:
 * 7 lines of 79 characters, the first and last OpenFOAM's frame. */
static const char *after_banner(const char *text)
{
    const char *p = text;
    assert_memory_equal(p, "/*--------------------------------*- C++ -*---", 45);
    for (int line = 0; line < 7; line++) {
        const char *nl = strchr(p, '\n');
        assert_non_null(nl);
        assert_int_equal(nl - p, 79);
        if (line == 6)
            assert_memory_equal(p, "\\*-----", 7);
        p = nl + 1;
    }
    return p;
}

static void assert_body(const char *path, const char *expected)
{
    char *text = slurp(path, NULL);
    if (!text)
        fail_msg("cannot read %s", path);
    const char *body = after_banner(text);
    if (strcmp(body, expected) != 0) {
        fprintf(stderr, "---- got (%s)\n%s---- expected\n%s----\n", path, body, expected);
        fail_msg("%s differs", path);
    }
    free(text);
}

/* A 2-patch-or-more mesh description: only names and sizes are used. */
typedef struct fake_mesh {
    pmesh pm;
    pmesh_patch patch[8];
} fake_mesh;

static void fake_init(fake_mesh *m, int n, const char *const *names, const ump_idx *sizes)
{
    memset(m, 0, sizeof *m);
    m->pm.npatches = n;
    m->pm.patch = m->patch;
    for (int i = 0; i < n; i++) {
        m->patch[i].name = (char *)names[i];
        m->patch[i].n = sizes[i];
    }
}

static void set_extra(fld_patch *p, const char *key, const char *text)
{
    p->extra = realloc(p->extra, (size_t)(p->nextra + 1) * sizeof *p->extra);
    p->extra[p->nextra].key = strdup(key);
    p->extra[p->nextra].text = strdup(text);
    p->nextra++;
}

#define DIVIDER_DOT \
    "// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n"
#define FOOTER \
    "\n\n// ************************************************************************* //\n"

/* ---- field.c ---------------------------------------------------------- */

static void test_bc_names(void **state)
{
    (void)state;
    static const char *const words[] = {
        "calculated", "fixedValue", "noSlip", "movingWallVelocity", "zeroGradient",
        "empty", "cyclic", "symmetryPlane", "symmetry", "fixedFluxPressure", "inletOutlet", "slip",
        "uniformFixedValue", "flowRateInletVelocity", "outletInlet", "totalPressure",
        "pressureInletOutletVelocity"};
    assert_int_equal(sizeof words / sizeof words[0], FLD_BC_NTYPES);
    for (int t = 0; t < FLD_BC_NTYPES; t++) {
        assert_string_equal(fld_bc_name((fld_bc_type)t), words[t]);
        assert_int_equal(fld_bc_parse(words[t]), t);
    }
    assert_int_equal(fld_bc_parse("partialSlip"), -1);
    assert_int_equal(fld_bc_parse("FixedValue"), -1);
    assert_int_equal(fld_bc_parse(""), -1);
    assert_int_equal(fld_bc_parse(NULL), -1);
    assert_int_equal(fld_bc_is_fixed(FLD_BC_FIXEDVALUE), 1);
    assert_int_equal(fld_bc_is_fixed(FLD_BC_NOSLIP), 1);
    assert_int_equal(fld_bc_is_fixed(FLD_BC_MOVINGWALLVELOCITY), 1);
    assert_int_equal(fld_bc_is_fixed(FLD_BC_ZEROGRADIENT), 0);
    assert_int_equal(fld_bc_is_fixed(FLD_BC_CALCULATED), 0);
    assert_int_equal(fld_bc_is_fixed(FLD_BC_INLETOUTLET), 0);
    assert_int_equal(fld_bc_is_fixed(FLD_BC_FIXEDFLUXPRESSURE), 0);
    assert_int_equal(fld_bc_is_fixed(FLD_BC_EMPTY), 0);
    assert_int_equal(fld_bc_is_fixed(FLD_BC_UNIFORMFIXEDVALUE), 1);
    assert_int_equal(fld_bc_is_fixed(FLD_BC_FLOWRATEINLETVELOCITY), 1);
    assert_int_equal(fld_bc_is_fixed(FLD_BC_TOTALPRESSURE), 1);
    assert_int_equal(fld_bc_is_fixed(FLD_BC_SLIP), 0);
    assert_int_equal(fld_bc_is_fixed(FLD_BC_OUTLETINLET), 0);
    assert_int_equal(fld_bc_is_fixed(FLD_BC_PRESSUREINLETOUTLETVELOCITY), 0);
}

static void test_create_copy_free(void **state)
{
    (void)state;
    const ump_idx sizes[3] = {2, 0, 5};
    fld_field *f = NULL, *g = NULL;
    ump_err err;
    assert_int_equal(fld_create("U", 3, 4, 3, sizes, &f, &err), UMP_OK);
    assert_string_equal(f->name, "U");
    assert_int_equal(f->ncomp, 3);
    assert_int_equal(f->ncells, 4);
    assert_int_equal(f->npatches, 3);
    for (int i = 0; i < 12; i++)
        assert_true(f->internal[i] == 0.0);
    for (int p = 0; p < 3; p++) {
        assert_int_equal(f->patch[p].type, FLD_BC_CALCULATED);
        assert_int_equal(f->patch[p].n, sizes[p]);
        assert_non_null(f->patch[p].value);
        assert_null(f->patch[p].aux);
        assert_int_equal(f->patch[p].nextra, 0);
    }
    f->dims[1] = 1;
    f->dims[2] = -1;
    f->internal[5] = 7.5;
    f->patch[2].type = FLD_BC_INLETOUTLET;
    f->patch[2].aux = calloc(15, sizeof(double));
    f->patch[2].aux[14] = -3;
    f->patch[2].value[1] = 2;
    f->patch[2].value_given = 1;
    set_extra(&f->patch[2], "phi", "phiAlt");

    assert_int_equal(fld_copy(f, &g, &err), UMP_OK);
    assert_ptr_not_equal(g, f);
    assert_string_equal(g->name, "U");
    assert_true(g->dims[1] == 1 && g->dims[2] == -1);
    assert_true(g->internal[5] == 7.5);
    assert_ptr_not_equal(g->internal, f->internal);
    assert_int_equal(g->patch[2].type, FLD_BC_INLETOUTLET);
    assert_int_equal(g->patch[2].value_given, 1);
    assert_true(g->patch[2].value[1] == 2);
    assert_true(g->patch[2].aux[14] == -3);
    assert_ptr_not_equal(g->patch[2].aux, f->patch[2].aux);
    assert_int_equal(g->patch[2].nextra, 1);
    assert_string_equal(g->patch[2].extra[0].key, "phi");
    assert_string_equal(g->patch[2].extra[0].text, "phiAlt");
    assert_null(g->patch[0].aux);
    fld_free(&f);
    assert_null(f);
    assert_true(g->internal[5] == 7.5);
    fld_free(&g);
    fld_free(&g); /* NULL is fine */
    fld_free(NULL);
}

static void test_create_errors(void **state)
{
    (void)state;
    const ump_idx sizes[2] = {1, -1};
    fld_field *f = (fld_field *)1;
    ump_err err;
    assert_int_equal(fld_create("p", 2, 4, 0, NULL, &f, &err), UMP_ERR_INPUT);
    assert_null(f);
    assert_non_null(strstr(err.msg, "p"));
    assert_int_equal(fld_create("p", 1, -1, 0, NULL, &f, &err), UMP_ERR_INPUT);
    assert_int_equal(fld_create("p", 1, 4, 2, sizes, &f, &err), UMP_ERR_INPUT);
    assert_int_equal(fld_create("p", 1, 4, 1, NULL, &f, &err), UMP_ERR_INPUT);
    assert_int_equal(fld_create("", 1, 4, 0, NULL, &f, &err), UMP_ERR_INPUT);
    assert_int_equal(fld_copy(NULL, &f, &err), UMP_ERR_INPUT);
    /* allocation failures at every point, no leaks (checked under ASan) */
    const ump_idx ok_sizes[2] = {3, 4};
    for (long k = 0; k < 5; k++) {
        ump_alloc_fail_after(k);
        ump_status rc = fld_create("p", 1, 4, 2, ok_sizes, &f, &err);
        ump_alloc_fail_after(-1);
        if (rc == UMP_OK) {
            fld_free(&f);
            continue;
        }
        assert_int_equal(rc, UMP_ERR_NOMEM);
        assert_null(f);
    }
    assert_int_equal(fld_create("p", 1, 4, 2, ok_sizes, &f, &err), UMP_OK);
    fld_field *g = NULL;
    for (long k = 0; k < 6; k++) {
        ump_alloc_fail_after(k);
        ump_status rc = fld_copy(f, &g, &err);
        ump_alloc_fail_after(-1);
        if (rc == UMP_OK) {
            fld_free(&g);
            continue;
        }
        assert_int_equal(rc, UMP_ERR_NOMEM);
        assert_null(g);
    }
    fld_free(&f);
}

/* ---- headers ---------------------------------------------------------- */

static void test_header_footer(void **state)
{
    (void)state;
    char dir[64], path[128];
    tu_tmpdir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/h", dir);
    FILE *fp = fopen(path, "wb");
    fio_write_header(fp, "volVectorField", "0.1", "U", 0);
    fputs("x 1;\n", fp);
    fio_write_footer(fp);
    fio_write_header(fp, "dictionary", NULL, "time", 1);
    fclose(fp);
    char *text = slurp(path, NULL);
    const char *body = after_banner(text);
    const char *second = strstr(body, "/*---");
    assert_non_null(second);
    assert_memory_equal(body,
        "FoamFile\n{\n"
        "    version     2.0;\n"
        "    format      ascii;\n"
        "    class       volVectorField;\n"
        "    location    \"0.1\";\n"
        "    object      U;\n"
        "}\n" DIVIDER_DOT "\n"
        "x 1;\n" FOOTER, (size_t)(second - body));
    assert_string_equal(after_banner(second),
        "FoamFile\n{\n"
        "    version     2.0;\n"
        "    format      binary;\n"
        "    class       dictionary;\n"
        "    arch        \"LSB;label=32;scalar=64\";\n"
        "    object      time;\n"
        "}\n" DIVIDER_DOT "\n");
    free(text);
    tu_rmtree(dir);
}

/* ---- ascii fields ----------------------------------------------------- */

static void test_ascii_scalar_uniform(void **state)
{
    (void)state;
    static const char *const names[] = {"movingWall", "fixedWalls", "frontAndBack"};
    const ump_idx sizes[] = {2, 3, 8};
    fake_mesh m;
    fake_init(&m, 3, names, sizes);
    fld_field *f;
    ump_err err;
    char dir[64], path[128];
    tu_tmpdir(dir, sizeof dir);
    assert_int_equal(fld_create("p", 1, 4, 3, sizes, &f, &err), UMP_OK);
    f->dims[1] = 2;
    f->dims[2] = -2;
    for (int c = 0; c < 4; c++)
        f->internal[c] = 1.5;
    f->patch[0].type = FLD_BC_ZEROGRADIENT;
    f->patch[1].type = FLD_BC_FIXEDVALUE;
    f->patch[1].value[0] = f->patch[1].value[1] = f->patch[1].value[2] = -0.000245641;
    f->patch[2].type = FLD_BC_EMPTY;
    assert_int_equal(fio_write_field(dir, "0", &m.pm, f, NULL, &err), UMP_OK);
    snprintf(path, sizeof path, "%s/p", dir);
    assert_body(path,
        "FoamFile\n{\n"
        "    version     2.0;\n"
        "    format      ascii;\n"
        "    class       volScalarField;\n"
        "    location    \"0\";\n"
        "    object      p;\n"
        "}\n" DIVIDER_DOT "\n"
        "dimensions      [0 2 -2 0 0 0 0];\n"
        "\n\n"
        "internalField   uniform 1.5;\n"
        "\n"
        "boundaryField\n{\n"
        "    movingWall\n    {\n"
        "        type            zeroGradient;\n"
        "    }\n"
        "    fixedWalls\n    {\n"
        "        type            fixedValue;\n"
        "        value           uniform -0.000245641;\n"
        "    }\n"
        "    frontAndBack\n    {\n"
        "        type            empty;\n"
        "    }\n"
        "}\n" FOOTER);
    fld_free(&f);
    tu_rmtree(dir);
}

/* 12 cells (a long list), every boundary type, short and long patch lists,
 * an empty (0-face) non-empty-type patch, extras after type. */
static void test_ascii_vector_all_types(void **state)
{
    (void)state;
    static const char *const names[] = {
        "lid", "walls", "slip", "out", "inlet", "ghost", "cyc", "symP", "sym", "calc",
        "frontAndBack"};
    const ump_idx sizes[] = {3, 2, 2, 11, 2, 0, 1, 1, 1, 2, 4};
    enum { NP = 11 };
    fake_mesh m;
    memset(&m, 0, sizeof m);
    pmesh_patch pp[NP];
    memset(pp, 0, sizeof pp);
    m.pm.npatches = NP;
    m.pm.patch = pp;
    for (int i = 0; i < NP; i++) {
        pp[i].name = (char *)names[i];
        pp[i].n = sizes[i];
    }
    fld_field *f;
    ump_err err;
    char dir[64], path[128];
    tu_tmpdir(dir, sizeof dir);
    assert_int_equal(fld_create("U", 3, 12, NP, sizes, &f, &err), UMP_OK);
    f->dims[1] = 1;
    f->dims[2] = -1;
    for (int c = 0; c < 12; c++) {
        f->internal[3 * c] = c * 0.5;
        f->internal[3 * c + 1] = -c * 1e-5;
        f->internal[3 * c + 2] = 0;
    }
    /* lid: movingWallVelocity, 3 distinct values -> one line */
    f->patch[0].type = FLD_BC_MOVINGWALLVELOCITY;
    const double lid[9] = {1, 0, 0, 0.5, 0, 0, 0.25, 0, 0};
    memcpy(f->patch[0].value, lid, sizeof lid);
    f->patch[1].type = FLD_BC_NOSLIP;
    f->patch[2].type = FLD_BC_ZEROGRADIENT;
    /* out: inletOutlet, 11 faces -> one value per line; extra phi */
    f->patch[3].type = FLD_BC_INLETOUTLET;
    f->patch[3].aux = calloc(33, sizeof(double));
    for (int i = 0; i < 11; i++)
        f->patch[3].value[3 * i] = i == 10 ? 2.0 : 1.0;
    set_extra(&f->patch[3], "phi", "phiAbs");
    /* inlet: fixedValue, two equal values -> uniform */
    f->patch[4].type = FLD_BC_FIXEDVALUE;
    f->patch[4].value[0] = f->patch[4].value[3] = 1e-05;
    /* ghost: fixedValue with no faces */
    f->patch[5].type = FLD_BC_FIXEDVALUE;
    f->patch[6].type = FLD_BC_CYCLIC;
    f->patch[7].type = FLD_BC_SYMMETRYPLANE;
    f->patch[8].type = FLD_BC_SYMMETRY;
    /* calc: calculated, two different values */
    f->patch[9].value[0] = 1;
    f->patch[9].value[4] = -2;
    f->patch[10].type = FLD_BC_EMPTY;
    assert_int_equal(fio_write_field(dir, "0.1", &m.pm, f, NULL, &err), UMP_OK);
    snprintf(path, sizeof path, "%s/U", dir);
    assert_body(path,
        "FoamFile\n{\n"
        "    version     2.0;\n"
        "    format      ascii;\n"
        "    class       volVectorField;\n"
        "    location    \"0.1\";\n"
        "    object      U;\n"
        "}\n" DIVIDER_DOT "\n"
        "dimensions      [0 1 -1 0 0 0 0];\n"
        "\n\n"
        "internalField   nonuniform List<vector> \n"
        "12\n(\n"
        "(0 0 0)\n(0.5 -1e-05 0)\n(1 -2e-05 0)\n(1.5 -3e-05 0)\n(2 -4e-05 0)\n"
        "(2.5 -5e-05 0)\n(3 -6e-05 0)\n(3.5 -7e-05 0)\n(4 -8e-05 0)\n(4.5 -9e-05 0)\n"
        "(5 -0.0001 0)\n(5.5 -0.00011 0)\n"
        ")\n;\n"
        "\n"
        "boundaryField\n{\n"
        "    lid\n    {\n"
        "        type            movingWallVelocity;\n"
        "        value           nonuniform List<vector> 3((1 0 0) (0.5 0 0) (0.25 0 0));\n"
        "    }\n"
        "    walls\n    {\n"
        "        type            noSlip;\n"
        "    }\n"
        "    slip\n    {\n"
        "        type            zeroGradient;\n"
        "    }\n"
        "    out\n    {\n"
        "        type            inletOutlet;\n"
        "        phi             phiAbs;\n"
        "        inletValue      uniform (0 0 0);\n"
        "        value           nonuniform List<vector> \n"
        "11\n(\n"
        "(1 0 0)\n(1 0 0)\n(1 0 0)\n(1 0 0)\n(1 0 0)\n(1 0 0)\n(1 0 0)\n(1 0 0)\n(1 0 0)\n"
        "(1 0 0)\n(2 0 0)\n"
        ")\n;\n"
        "    }\n"
        "    inlet\n    {\n"
        "        type            fixedValue;\n"
        "        value           uniform (1e-05 0 0);\n"
        "    }\n"
        "    ghost\n    {\n"
        "        type            fixedValue;\n"
        "        value           nonuniform 0();\n"
        "    }\n"
        "    cyc\n    {\n"
        "        type            cyclic;\n"
        "    }\n"
        "    symP\n    {\n"
        "        type            symmetryPlane;\n"
        "    }\n"
        "    sym\n    {\n"
        "        type            symmetry;\n"
        "    }\n"
        "    calc\n    {\n"
        "        type            calculated;\n"
        "        value           nonuniform List<vector> 2((1 0 0) (0 -2 0));\n"
        "    }\n"
        "    frontAndBack\n    {\n"
        "        type            empty;\n"
        "    }\n"
        "}\n" FOOTER);
    fld_free(&f);
    tu_rmtree(dir);
}

/* fixedFluxPressure (gradient then value, extra rho after type), a 10-entry
 * list (still one line), an 11-entry scalar list, precision 10, long keys. */
static void test_ascii_scalar_lists(void **state)
{
    (void)state;
    static const char *const names[] = {"wall", "top"};
    const ump_idx sizes[] = {10, 2};
    fake_mesh m;
    fake_init(&m, 2, names, sizes);
    fld_field *f;
    ump_err err;
    char dir[64], path[128];
    tu_tmpdir(dir, sizeof dir);
    assert_int_equal(fld_create("p_rgh", 1, 11, 2, sizes, &f, &err), UMP_OK);
    f->dims[0] = 1;
    f->dims[1] = -1;
    f->dims[2] = -2;
    f->dims[3] = 0.5;
    for (int c = 0; c < 11; c++)
        f->internal[c] = 1.0 / 3.0 + c;
    f->patch[0].type = FLD_BC_FIXEDFLUXPRESSURE;
    f->patch[0].aux = calloc(10, sizeof(double));
    f->patch[0].aux[9] = 1e-20;
    for (int i = 0; i < 10; i++)
        f->patch[0].value[i] = i;
    set_extra(&f->patch[0], "rho", "rhok");
    set_extra(&f->patch[0], "aVeryLongKeyword", "( 1 2 )");
    f->patch[1].type = FLD_BC_CALCULATED;
    fio_format fmt = {0, 10, 0};
    assert_int_equal(fio_write_field(dir, NULL, &m.pm, f, &fmt, &err), UMP_OK);
    snprintf(path, sizeof path, "%s/p_rgh", dir);
    assert_body(path,
        "FoamFile\n{\n"
        "    version     2.0;\n"
        "    format      ascii;\n"
        "    class       volScalarField;\n"
        "    object      p_rgh;\n"
        "}\n" DIVIDER_DOT "\n"
        "dimensions      [1 -1 -2 0.5 0 0 0];\n"
        "\n\n"
        "internalField   nonuniform List<scalar> \n"
        "11\n(\n"
        "0.3333333333\n1.333333333\n2.333333333\n3.333333333\n4.333333333\n"
        "5.333333333\n6.333333333\n7.333333333\n8.333333333\n9.333333333\n"
        "10.33333333\n"
        ")\n;\n"
        "\n"
        "boundaryField\n{\n"
        "    wall\n    {\n"
        "        type            fixedFluxPressure;\n"
        "        rho             rhok;\n"
        "        aVeryLongKeyword ( 1 2 );\n"
        "        gradient        nonuniform List<scalar> 10(0 0 0 0 0 0 0 0 0 1e-20);\n"
        "        value           nonuniform List<scalar> 10(0 1 2 3 4 5 6 7 8 9);\n"
        "    }\n"
        "    top\n    {\n"
        "        type            calculated;\n"
        "        value           uniform 0;\n"
        "    }\n"
        "}\n" FOOTER);
    fld_free(&f);
    tu_rmtree(dir);
}

/* ---- binary and compression ------------------------------------------- */

static void put_le(unsigned char *p, double v)
{
    uint64_t bits;
    memcpy(&bits, &v, 8);
    for (int k = 0; k < 8; k++)
        p[k] = (unsigned char)(bits >> (8 * k));
}

static void test_binary_bytes(void **state)
{
    (void)state;
    static const char *const names[] = {"lid", "ghost", "walls", "frontAndBack"};
    const ump_idx sizes[] = {2, 0, 2, 4};
    fake_mesh m;
    fake_init(&m, 4, names, sizes);
    fld_field *f;
    ump_err err;
    char dir[64], path[128];
    tu_tmpdir(dir, sizeof dir);
    assert_int_equal(fld_create("U", 3, 2, 4, sizes, &f, &err), UMP_OK);
    f->dims[1] = 1;
    f->dims[2] = -1;
    const double iv[6] = {0.000249136, -0.000245641, 0, 0.1, 0.2, 0.3};
    memcpy(f->internal, iv, sizeof iv);
    f->patch[0].type = FLD_BC_FIXEDVALUE;
    const double lv[6] = {1, 0, 0, 1, 0, 0};
    memcpy(f->patch[0].value, lv, sizeof lv);
    f->patch[1].type = FLD_BC_FIXEDVALUE;
    f->patch[2].type = FLD_BC_CALCULATED;
    f->patch[2].value[0] = 1.0 / 3.0;
    f->patch[3].type = FLD_BC_EMPTY;
    fio_format fmt = {1, 6, 1}; /* compression is ignored for binary */
    assert_int_equal(fio_write_field(dir, "0.1", &m.pm, f, &fmt, &err), UMP_OK);
    snprintf(path, sizeof path, "%s/U.gz", dir);
    assert_false(exists(path));
    snprintf(path, sizeof path, "%s/U", dir);
    size_t len;
    char *text = slurp(path, &len);
    assert_non_null(text);
    const char *body = after_banner(text);

    /* expected: text, 6 raw doubles, text, 6 raw doubles, text */
    unsigned char exp[2048];
    size_t n = 0;
#define ADD(s) do { memcpy(exp + n, s, strlen(s)); n += strlen(s); } while (0)
    ADD("FoamFile\n{\n"
        "    version     2.0;\n"
        "    format      binary;\n"
        "    class       volVectorField;\n"
        "    arch        \"LSB;label=32;scalar=64\";\n"
        "    location    \"0.1\";\n"
        "    object      U;\n"
        "}\n" DIVIDER_DOT "\n"
        "dimensions      [0 1 -1 0 0 0 0];\n"
        "\n\n"
        "internalField   nonuniform List<vector> \n2\n(");
    for (int i = 0; i < 6; i++, n += 8)
        put_le(exp + n, iv[i]);
    ADD(");\n"
        "\n"
        "boundaryField\n{\n"
        "    lid\n    {\n"
        "        type            fixedValue;\n"
        "        value           uniform (1 0 0);\n"
        "    }\n"
        "    ghost\n    {\n"
        "        type            fixedValue;\n"
        "        value           nonuniform 0;\n"
        "    }\n"
        "    walls\n    {\n"
        "        type            calculated;\n"
        "        value           nonuniform List<vector> \n2\n(");
    const double wv[6] = {1.0 / 3.0, 0, 0, 0, 0, 0};
    for (int i = 0; i < 6; i++, n += 8)
        put_le(exp + n, wv[i]);
    ADD(");\n"
        "    }\n"
        "    frontAndBack\n    {\n"
        "        type            empty;\n"
        "    }\n"
        "}\n" FOOTER);
#undef ADD
    assert_int_equal(len - (size_t)(body - text), n);
    assert_memory_equal(body, exp, n);
    free(text);
    fld_free(&f);
    tu_rmtree(dir);
}

static void test_gzip_round_trip(void **state)
{
    (void)state;
    static const char *const names[] = {"w"};
    const ump_idx sizes[] = {12};
    fake_mesh m;
    fake_init(&m, 1, names, sizes);
    fld_field *f;
    ump_err err;
    char dir[64], gzdir[80], path[160];
    tu_tmpdir(dir, sizeof dir);
    snprintf(gzdir, sizeof gzdir, "%s/gz", dir);
    assert_int_equal(fio_mkdir_p(gzdir, &err), UMP_OK);
    assert_int_equal(fld_create("T", 1, 30, 1, sizes, &f, &err), UMP_OK);
    for (int c = 0; c < 30; c++)
        f->internal[c] = 300 + c * 0.125;
    for (int i = 0; i < 12; i++)
        f->patch[0].value[i] = i;
    /* a stale plain file must go when the compressed one is written */
    tu_write(gzdir, "T", "stale");
    fio_format plain = {0, 6, 0}, gz = {0, 6, 1};
    assert_int_equal(fio_write_field(dir, "0.5", &m.pm, f, &plain, &err), UMP_OK);
    assert_int_equal(fio_write_field(gzdir, "0.5", &m.pm, f, &gz, &err), UMP_OK);
    snprintf(path, sizeof path, "%s/T", gzdir);
    assert_false(exists(path));
    snprintf(path, sizeof path, "%s/T.gz", gzdir);
    size_t zlen, plen;
    char *raw = slurp(path, &zlen);
    assert_true(zlen > 2 && (unsigned char)raw[0] == 0x1f && (unsigned char)raw[1] == 0x8b);
    free(raw);
    char *unz = gunzip_file(path, &zlen);
    snprintf(path, sizeof path, "%s/T", dir);
    char *ref = slurp(path, &plen);
    assert_int_equal(zlen, plen);
    assert_memory_equal(unz, ref, plen);
    assert_non_null(strstr(ref, "internalField   nonuniform List<scalar> \n30\n(\n300\n300.125\n"));
    free(unz);
    free(ref);
    /* writing plain again removes the .gz */
    assert_int_equal(fio_write_field(gzdir, "0.5", &m.pm, f, &plain, &err), UMP_OK);
    snprintf(path, sizeof path, "%s/T.gz", gzdir);
    assert_false(exists(path));
    fld_free(&f);
    tu_rmtree(dir);
}

static void test_write_errors(void **state)
{
    (void)state;
    static const char *const names[] = {"a", "b"};
    const ump_idx sizes[] = {2, 3};
    fake_mesh m;
    fake_init(&m, 2, names, sizes);
    fld_field *f;
    ump_err err;
    char dir[64], path[128];
    tu_tmpdir(dir, sizeof dir);
    assert_int_equal(fld_create("p", 1, 3, 2, sizes, &f, &err), UMP_OK);
    /* patch count mismatch */
    m.pm.npatches = 1;
    assert_int_equal(fio_write_field(dir, "0", &m.pm, f, NULL, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "patches"));
    m.pm.npatches = 2;
    /* patch size mismatch names the patch */
    m.patch[1].n = 4;
    assert_int_equal(fio_write_field(dir, "0", &m.pm, f, NULL, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "patch b"));
    m.patch[1].n = 3;
    /* inletOutlet without inletValue */
    f->patch[1].type = FLD_BC_INLETOUTLET;
    assert_int_equal(fio_write_field(dir, "0", &m.pm, f, NULL, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "inletValue"));
    f->patch[1].type = FLD_BC_ZEROGRADIENT;
    snprintf(path, sizeof path, "%s/p", dir);
    assert_false(exists(path));
    /* missing directory */
    snprintf(path, sizeof path, "%s/no/such", dir);
    assert_int_equal(fio_write_field(path, "0", &m.pm, f, NULL, &err), UMP_ERR_IO);
    assert_non_null(strstr(err.msg, path));
    assert_int_equal(fio_write_field(dir, "0", &m.pm, f, NULL, &err), UMP_OK);
    fld_free(&f);
    tu_rmtree(dir);
}

/* ---- uniform/time ----------------------------------------------------- */

static void test_uniform_time(void **state)
{
    (void)state;
    char dir[64], path[160];
    ump_err err;
    tu_tmpdir(dir, sizeof dir);
    /* icoFoam's cavity at index 20: 20 additions of 0.005 */
    double t = 0;
    for (int i = 0; i < 20; i++)
        t += 0.005;
    assert_int_equal(fio_write_uniform_time(dir, "0.1", t, "0.1", 20, 0.005, 0.005, 6, 0, &err),
                     UMP_OK);
    snprintf(path, sizeof path, "%s/uniform/time", dir);
    assert_body(path,
        "FoamFile\n{\n"
        "    version     2.0;\n"
        "    format      ascii;\n"
        "    class       dictionary;\n"
        "    location    \"0.1/uniform\";\n"
        "    object      time;\n"
        "}\n" DIVIDER_DOT "\n"
        "value           0.100000000000000019;\n"
        "\n"
        "name            \"0.1\";\n"
        "\n"
        "index           20;\n"
        "\n"
        "deltaT          0.005;\n"
        "\n"
        "deltaT0         0.005;\n" FOOTER);
    /* pimpleFoam, timeFormat fixed, writePrecision 10: deltaT uses the
     * write precision, value 18 decimals */
    assert_int_equal(fio_write_uniform_time(dir, "0.003704", 3 * 0.00123456789, "0.003704", 3,
                                            0.00123456789, 0.00123456789, 10, 1, &err),
                     UMP_OK);
    char *text = slurp(path, NULL);
    assert_non_null(strstr(text, "    location    \"0.003704/uniform\";\n"));
    assert_non_null(strstr(text, "\nvalue           0.003703703670000000;\n\nname            \"0.003704\";\n"));
    assert_non_null(strstr(text, "\ndeltaT          0.00123456789;\n\ndeltaT0         0.00123456789;\n"));
    free(text);
    /* default precision and scientific */
    assert_int_equal(fio_write_uniform_time(dir, "1e-05", 1e-05, "1e-05", 1, 1.0 / 3.0, 1e-05,
                                            0, 2, &err), UMP_OK);
    text = slurp(path, NULL);
    assert_non_null(strstr(text, "\nvalue           1.000000000000000082e-05;\n"));
    assert_non_null(strstr(text, "\ndeltaT          0.333333;\n\ndeltaT0         1e-05;\n"));
    free(text);
    tu_rmtree(dir);
}

/* ---- directories ------------------------------------------------------ */

static void test_mkdir_p(void **state)
{
    (void)state;
    char dir[64], path[160];
    ump_err err;
    tu_tmpdir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/a/b//c/", dir);
    assert_int_equal(fio_mkdir_p(path, &err), UMP_OK);
    assert_int_equal(fio_mkdir_p(path, &err), UMP_OK);
    snprintf(path, sizeof path, "%s/a/b/c", dir);
    assert_true(exists(path));
    tu_write(dir, "file", "x");
    snprintf(path, sizeof path, "%s/file/sub", dir);
    assert_int_equal(fio_mkdir_p(path, &err), UMP_ERR_IO);
    assert_non_null(strstr(err.msg, "file"));
    tu_rmtree(dir);
}

static int count_entries(const char *dir)
{
    char cmd[256];
    snprintf(cmd, sizeof cmd, "ls -A '%s' | wc -l", dir);
    FILE *p = popen(cmd, "r");
    int n = -1;
    if (!p || fscanf(p, "%d", &n) != 1)
        n = -1;
    if (p)
        pclose(p);
    return n;
}

static void test_timedir_atomic(void **state)
{
    (void)state;
    char cas[64], path[4200];
    ump_err err;
    fio_timedir td;
    tu_tmpdir(cas, sizeof cas);

    /* new directory: hidden while being written, visible after commit */
    assert_int_equal(fio_timedir_begin(cas, "0.1", &td, &err), UMP_OK);
    assert_int_equal(td.open, 1);
    snprintf(path, sizeof path, "%s/0.1", cas);
    assert_string_equal(td.final_dir, path);
    snprintf(path, sizeof path, "%s/.0.1.tmp.%ld", cas, (long)getpid());
    assert_string_equal(td.tmp_dir, path);
    put_file(td.tmp_dir, "U", "first");
    snprintf(path, sizeof path, "%s/0.1", cas);
    assert_false(exists(path));
    assert_int_equal(fio_timedir_commit(&td, &err), UMP_OK);
    assert_int_equal(td.open, 0);
    snprintf(path, sizeof path, "%s/0.1/U", cas);
    char *text = slurp(path, NULL);
    assert_string_equal(text, "first");
    free(text);
    assert_int_equal(count_entries(cas), 1);

    /* an aborted rewrite leaves the previous directory intact */
    assert_int_equal(fio_timedir_begin(cas, "0.1", &td, &err), UMP_OK);
    put_file(td.tmp_dir, "U", "second");
    fio_timedir_abort(&td);
    fio_timedir_abort(&td); /* twice is fine */
    assert_false(exists(td.tmp_dir));
    text = slurp(path, NULL);
    assert_string_equal(text, "first");
    free(text);
    assert_int_equal(count_entries(cas), 1);

    /* a failed field write inside the time directory, then abort */
    assert_int_equal(fio_timedir_begin(cas, "0.1", &td, &err), UMP_OK);
    {
        static const char *const names[] = {"a"};
        const ump_idx sizes[] = {1};
        fake_mesh m;
        fake_init(&m, 1, names, sizes);
        m.patch[0].n = 2; /* mismatch: the write must fail */
        fld_field *f;
        assert_int_equal(fld_create("U", 3, 1, 1, sizes, &f, &err), UMP_OK);
        assert_int_not_equal(fio_write_field(td.tmp_dir, "0.1", &m.pm, f, NULL, &err), UMP_OK);
        fld_free(&f);
    }
    fio_timedir_abort(&td);
    text = slurp(path, NULL);
    assert_string_equal(text, "first");
    free(text);

    /* commit over an existing directory: the files written replace
     * theirs, the others' files are kept (OpenFOAM's solvers write into
     * the existing directory) */
    assert_int_equal(fio_timedir_begin(cas, "0.1", &td, &err), UMP_OK);
    put_file(td.tmp_dir, "p", "new p");
    assert_int_equal(fio_timedir_commit(&td, &err), UMP_OK);
    text = slurp(path, NULL); /* U: not written, kept */
    assert_string_equal(text, "first");
    free(text);
    snprintf(path, sizeof path, "%s/0.1/p", cas);
    text = slurp(path, NULL);
    assert_string_equal(text, "new p");
    free(text);
    assert_int_equal(fio_timedir_begin(cas, "0.1", &td, &err), UMP_OK);
    put_file(td.tmp_dir, "p", "newer p");
    assert_int_equal(fio_timedir_commit(&td, &err), UMP_OK);
    text = slurp(path, NULL);
    assert_string_equal(text, "newer p");
    free(text);
    assert_int_equal(count_entries(cas), 1); /* no hidden leftovers */

    /* a plain file in the way is an error, before anything is written,
     * and is kept */
    tu_write(cas, "0.2", "not a directory");
    assert_int_equal(fio_timedir_check(cas, "0.2", &err), UMP_ERR_IO);
    assert_non_null(strstr(err.msg, "a file named 0.2 is in the way of time directory 0.2"));
    assert_int_equal(fio_timedir_check(cas, "0.1", &err), UMP_OK);
    assert_int_equal(fio_timedir_check(cas, "0.3", &err), UMP_OK);
    assert_int_equal(fio_timedir_begin(cas, "0.2", &td, &err), UMP_ERR_IO);
    assert_int_equal(td.open, 0);
    snprintf(path, sizeof path, "%s/0.2", cas);
    text = slurp(path, NULL);
    assert_string_equal(text, "not a directory");
    free(text);
    assert_int_equal(count_entries(cas), 2);
    /* ... also when it appears after begin (commit refuses, abort cleans) */
    assert_int_equal(unlink(path), 0);
    assert_int_equal(fio_timedir_begin(cas, "0.2", &td, &err), UMP_OK);
    put_file(td.tmp_dir, "U", "u");
    tu_write(cas, "0.2", "late file");
    assert_int_equal(fio_timedir_commit(&td, &err), UMP_ERR_IO);
    fio_timedir_abort(&td);
    text = slurp(path, NULL);
    assert_string_equal(text, "late file");
    free(text);
    assert_int_equal(unlink(path), 0);
    /* commit twice is an error */
    assert_int_equal(fio_timedir_begin(cas, "0.2", &td, &err), UMP_OK);
    put_file(td.tmp_dir, "U", "u");
    assert_int_equal(fio_timedir_commit(&td, &err), UMP_OK);
    assert_int_equal(fio_timedir_commit(&td, &err), UMP_ERR_INPUT);
    snprintf(path, sizeof path, "%s/0.2/U", cas);
    assert_true(exists(path));
    assert_int_equal(count_entries(cas), 2);

    /* purgeWrite's removal leaves nothing, hidden or not */
    assert_int_equal(fio_remove_timedir(cas, "0.2", &err), UMP_OK);
    assert_int_equal(count_entries(cas), 1);
    assert_int_equal(fio_remove_timedir(cas, "0.2", &err), UMP_OK); /* gone: fine */

    /* bad names and missing case */
    assert_int_equal(fio_timedir_begin(cas, "a/b", &td, &err), UMP_ERR_INPUT);
    assert_int_equal(fio_timedir_begin(cas, "..", &td, &err), UMP_ERR_INPUT);
    assert_int_equal(fio_timedir_begin(cas, "", &td, &err), UMP_ERR_INPUT);
    snprintf(path, sizeof path, "%s/missing", cas);
    assert_int_equal(fio_timedir_begin(path, "0.1", &td, &err), UMP_ERR_IO);
    assert_int_equal(td.open, 0);
    fio_timedir_abort(&td);
    tu_rmtree(cas);
}

/* A commit whose final rename fails puts the previous version back (the
 * temporary directory is removed behind its back to make the rename fail;
 * works as root too). */
static void test_timedir_commit_failure(void **state)
{
    (void)state;
    char cas[64], path[4200];
    ump_err err;
    fio_timedir td;
    tu_tmpdir(cas, sizeof cas);
    assert_int_equal(fio_timedir_begin(cas, "1", &td, &err), UMP_OK);
    put_file(td.tmp_dir, "U", "old");
    assert_int_equal(fio_timedir_commit(&td, &err), UMP_OK);
    assert_int_equal(fio_timedir_begin(cas, "1", &td, &err), UMP_OK);
    put_file(td.tmp_dir, "U", "new");
    snprintf(path, sizeof path, "%s/U", td.tmp_dir);
    assert_int_equal(unlink(path), 0);
    assert_int_equal(rmdir(td.tmp_dir), 0);
    assert_int_equal(fio_timedir_commit(&td, &err), UMP_ERR_IO);
    assert_non_null(strstr(err.msg, td.final_dir));
    snprintf(path, sizeof path, "%s/1/U", cas);
    char *text = slurp(path, NULL);
    assert_non_null(text);
    assert_string_equal(text, "old");
    free(text);
    assert_int_equal(td.open, 1);
    fio_timedir_abort(&td);
    assert_int_equal(count_entries(cas), 1);

    /* not as root: a read-only case directory makes the first rename fail */
    if (geteuid() != 0) {
        assert_int_equal(fio_timedir_begin(cas, "1", &td, &err), UMP_OK);
        put_file(td.tmp_dir, "U", "new");
        chmod(cas, 0555);
        assert_int_equal(fio_timedir_commit(&td, &err), UMP_ERR_IO);
        chmod(cas, 0755);
        text = slurp(path, NULL);
        assert_string_equal(text, "old");
        free(text);
        fio_timedir_abort(&td);
        assert_int_equal(count_entries(cas), 1);
    }
    tu_rmtree(cas);
}

/* What fio_recover saw, for test_recover. */
typedef struct seen {
    int n;
    fio_recovery what[8];
    char hidden[8][64];
} seen;

static void note(void *ctx, fio_recovery what, const char *hidden, const char *tname, long pid)
{
    seen *s = ctx;
    (void)tname;
    (void)pid;
    if (s->n < 8) {
        s->what[s->n] = what;
        snprintf(s->hidden[s->n], sizeof s->hidden[s->n], "%s", hidden);
        s->n++;
    }
}

static fio_recovery seen_what(const seen *s, const char *hidden)
{
    for (int i = 0; i < s->n; i++)
        if (strcmp(s->hidden[i], hidden) == 0)
            return s->what[i];
    fail_msg("fio_recover did not report %s", hidden);
    return FIO_LEFT_RUNNING;
}

/* Start-up recovery: .old without its time renamed back, .old with its
 * time, .tmp and .del removed, a live process's left alone, other hidden
 * names untouched. */
static void test_recover(void **state)
{
    (void)state;
    char cas[64], path[4200], name[128];
    ump_err err;
    tu_tmpdir(cas, sizeof cas);
    const char *dirs[] = {".0.1.old.999999", ".0.2.old.999998", "0.2", ".0.3.tmp.999997",
                          ".1e-05.del.999996", ".git", ".0.4.tmp.abc"};
    for (size_t i = 0; i < sizeof dirs / sizeof dirs[0]; i++) {
        snprintf(path, sizeof path, "%s/%s", cas, dirs[i]);
        assert_int_equal(mkdir(path, 0777), 0);
        put_file(path, "U", dirs[i]);
    }
    snprintf(name, sizeof name, ".0.5.tmp.%ld", (long)getppid()); /* a running process */
    snprintf(path, sizeof path, "%s/%s", cas, name);
    assert_int_equal(mkdir(path, 0777), 0);
    tu_write(cas, ".0.6.tmp.999995", "a file, not the writer's"); /* not a directory: kept */
    snprintf(path, sizeof path, "%s/.0.7.old.999994", cas); /* its time is a file: kept */
    assert_int_equal(mkdir(path, 0777), 0);
    tu_write(cas, "0.7", "in the way");
    seen s = {0};
    assert_int_equal(fio_recover(cas, note, &s, &err), UMP_OK);
    assert_int_equal(s.n, 6);
    assert_int_equal(seen_what(&s, ".0.7.old.999994"), FIO_LEFT_BLOCKED);
    assert_int_equal(seen_what(&s, ".0.1.old.999999"), FIO_RECOVERED);
    assert_int_equal(seen_what(&s, ".0.2.old.999998"), FIO_REMOVED_OLD);
    assert_int_equal(seen_what(&s, ".0.3.tmp.999997"), FIO_REMOVED_TMP);
    assert_int_equal(seen_what(&s, ".1e-05.del.999996"), FIO_REMOVED_DEL);
    assert_int_equal(seen_what(&s, name), FIO_LEFT_RUNNING);
    snprintf(path, sizeof path, "%s/0.1/U", cas);
    char *text = slurp(path, NULL);
    assert_string_equal(text, ".0.1.old.999999");
    free(text);
    snprintf(path, sizeof path, "%s/0.2/U", cas);
    text = slurp(path, NULL);
    assert_string_equal(text, "0.2");
    free(text);
    /* 0.1 0.2 .git .0.4.tmp.abc .0.5.tmp.<ppid> .0.6.tmp.999995 0.7 .0.7.old.999994 */
    assert_int_equal(count_entries(cas), 8);
    s.n = 0;
    assert_int_equal(fio_recover(cas, note, &s, &err), UMP_OK);
    assert_int_equal(s.n, 2); /* the live one and the blocked one again */
    snprintf(path, sizeof path, "%s/missing", cas);
    assert_int_equal(fio_recover(path, NULL, NULL, &err), UMP_ERR_IO);
    tu_rmtree(cas);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bc_names),
        cmocka_unit_test(test_create_copy_free),
        cmocka_unit_test(test_create_errors),
        cmocka_unit_test(test_header_footer),
        cmocka_unit_test(test_ascii_scalar_uniform),
        cmocka_unit_test(test_ascii_vector_all_types),
        cmocka_unit_test(test_ascii_scalar_lists),
        cmocka_unit_test(test_binary_bytes),
        cmocka_unit_test(test_gzip_round_trip),
        cmocka_unit_test(test_write_errors),
        cmocka_unit_test(test_uniform_time),
        cmocka_unit_test(test_mkdir_p),
        cmocka_unit_test(test_timedir_atomic),
        cmocka_unit_test(test_timedir_commit_failure),
        cmocka_unit_test(test_recover),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
