/* SPDX-License-Identifier: GPL-3.0-or-later
 * case.h -- an OpenFOAM case directory and its settings (module prefix case_).
 *
 * Reads system/controlDict, constant/transportProperties and
 * system/fvSolution into plain structs (defaults as OpenFOAM's), and finds
 * time directories. Numerics never read files: they get these structs.
 */
#ifndef UMPPM_CASE_H
#define UMPPM_CASE_H

#include "umppm/ump.h"

typedef enum { CASE_START_STARTTIME, CASE_START_LATESTTIME, CASE_START_FIRSTTIME } case_start_from;
typedef enum { CASE_STOP_ENDTIME, CASE_STOP_WRITENOW, CASE_STOP_NOWRITENOW, CASE_STOP_NEXTWRITE } case_stop_at;
typedef enum {
    CASE_WRITE_TIMESTEP, CASE_WRITE_RUNTIME, CASE_WRITE_ADJUSTABLERUNTIME,
    CASE_WRITE_CPUTIME, CASE_WRITE_CLOCKTIME
} case_write_control;

typedef struct case_control {
    char application[128];
    case_start_from start_from;
    double start_time;           /* startTime */
    case_stop_at stop_at;
    double end_time;
    double delta_t;
    case_write_control write_control;
    double write_interval;
    int purge_write;             /* keep only the last N time directories; 0 = all */
    int write_binary;            /* writeFormat */
    int write_precision;         /* default 6 */
    int write_compression;       /* on/off (yes/no, compressed/uncompressed) */
    int time_format_fixed;       /* timeFormat: 0 general, 1 fixed, 2 scientific */
    int time_precision;          /* default 6 */
    int adjust_time_step;        /* adjustTimeStep */
    double max_co;               /* maxCo, default 1 */
    double max_delta_t;          /* maxDeltaT, default "great" */
    int run_time_modifiable;
} case_control;

typedef struct case_transport {
    double nu;                   /* kinematic viscosity [m^2/s] */
    int has_nu;
    /* Boussinesq constants of buoyantBoussinesqPimpleFoam (optional here;
     * case_require_boussinesq checks them for a buoyant case) */
    double beta;                 /* thermal expansion coefficient [1/K] */
    double TRef;                 /* reference temperature [K] */
    double Pr, Prt;              /* laminar and turbulent Prandtl numbers */
    int has_beta, has_TRef, has_Pr;
} case_transport;

/* Gravity of a buoyant case: constant/g (uniformDimensionedVectorField) and
 * the optional constant/hRef (uniformDimensionedScalarField, default 0). */
typedef struct case_buoyancy {
    int on;                      /* constant/g exists */
    double g[3];
    double h_ref;
    int has_h_ref;
} case_buoyancy;

typedef struct case_solution {
    char algo[8];                /* the dictionary read: PISO, PIMPLE or SIMPLE */
    long p_ref_cell;             /* PISO/PIMPLE/SIMPLE pRefCell, default 0 */
    double p_ref_value;          /* pRefValue, default 0 */
    int has_p_ref_cell, has_p_ref_value; /* given (required where p needs a reference) */
    int has_p_ref_point;
    double p_ref_point[3];       /* pRefPoint, if given instead of pRefCell */
} case_solution;

/* The UMPPM sub-dictionary of system/fvSolution (all optional):
 *   UMPPM { variant UMPPMstar; alpha 0.09; laplacian CPM; reFactor 0;
 *           writeQuality no; ppeSolver auto;
 *           predictorSolver { preconditioner Jacobi; tolerance 1e-12; maxIter 500; }
 *           cloudName umppmCloud; sortInterval 1; refill auto;
 *           refillParticles 4; refillWeights increment; mlsSupport 2; }
 * Its keys, types, defaults, allowed values and help are ONE table,
 * case_umppm_options(): the reader, case_umppm_defaults() and
 * case_umppm_help() (umppmFoam -help) all use it.
 * reFactor: r_e / particle spacing of MPS, PS, IPS (0: 2.1 MPS, 2 PS/IPS);
 * writeQuality: also write the particle fields uN and tau (Hwang, Ng &
 * Sheu 2016 [HNS16] Eqs. 13, 22).
 * variant: UMPPM (adaptive), UMPPMstar (also written "UMPPM*" in quotes), or
 * auto (app.c: UMPPM in a closed flow on mostly non-square quadrilaterals). */
typedef struct case_umppm {
    int variant_star;            /* 1: UMPPM*, 0: UMPPM, -1: auto (the default) */
    double alpha;                /* default 0.09, in (0, 1) */
    char laplacian[16];          /* auto (default), CPM, MPS, IPS, PS, CPM4 */
    double re_factor;            /* default 0: the model's own */
    int write_quality;           /* default 0 */
    char ppe_solver[16];         /* auto (default), UMFPACK, KLU, CHOLMOD */
    char pred_pc[16];            /* Jacobi (default), ILU0, none */
    double pred_tol;             /* default 1e-12 */
    long pred_maxit;             /* default 500 */
    char cloud_name[64];         /* default umppmCloud */
    long sort_interval;          /* sortInterval: re-sort the particles by cell
                                    every N steps, 0 never; default 1 */
    int buoyancy_balanced;       /* buoyancy: 1 balanced (default), 0 source */
    int refill_carried;          /* refill: 1 carried, 0 centroid, -1 auto (default:
                                    carried with UMPPM*, centroid with UMPPM) */
    long refill_k;               /* refillParticles: default 4, 1..16 */
    int refill_increment;        /* refillWeights: 1 increment (default), 0 distance */
    double mls_support;          /* mlsSupport: 2 (default) or 1..4 cell extents; 0: Eq. 35's scales */
    double face_support;         /* faceSupport: -1 auto (default), 0 or 1..4 cell extents */
    double p_theta;              /* pressureTheta: 0 .. 0.5; -1: auto (default) */
    int anisotropic;             /* anisotropicCells: -1 auto (default), 0 or 1 */
    int q_transpose;             /* interpolationError: 1 transpose, 0 gradient,
                                    -1 auto (default) */
    int positive_rows;           /* positiveRows: default 1 */
    int bounded_fits;            /* boundedFits: default 1 */
    double max_velocity;         /* maxVelocity: divergence bound on |U| of
                                    cells and particles; 0 (default): 100 x
                                    the case's speed scale (app.c) */
} case_umppm;

/* Type of an option of the UMPPM dictionary, and of the case_umppm field
 * it is stored in. */
typedef enum case_opt_type {
    CASE_OPT_CHOICE, /* one word of choices[]: char[size], or int (choice_values[i]) */
    CASE_OPT_SCALAR, /* a number: double */
    CASE_OPT_LABEL,  /* an integer: long */
    CASE_OPT_BOOL,   /* a switch (yes/no, on/off, true/false, 1/0): int 0/1 */
    CASE_OPT_WORD    /* any one word or "string": char[size] (longer is refused) */
} case_opt_type;

/* Allowed numbers of a scalar or label option: [lo, hi] with each end
 * closed, open or absent, and optionally the single value 0 and the word
 * auto besides. */
typedef struct case_opt_range {
    int has_lo, has_hi;          /* 0: no bound on that side */
    int lo_open, hi_open;        /* 1: the bound itself is excluded */
    double lo, hi;
    int or_zero;                 /* 0 is allowed besides the range */
    int or_auto;                 /* the word auto is allowed (scalar:
                                    stored as -1, the caller decides) */
} case_opt_range;

typedef struct case_option {
    const char *key;             /* "alpha"; in a sub-dictionary with its path,
                                    "predictorSolver.tolerance" */
    case_opt_type type;
    const char *default_text;    /* as written in fvSolution: "0.09", "UMPPMstar", "no" */
    double default_value;        /* scalar, label, bool (0/1); choice with
                                    choice_values: its int value; else 0 */
    const char *const *choices;  /* CASE_OPT_CHOICE: NULL-terminated words, else NULL */
    const int *choice_values;    /* NULL: the word itself is stored */
    case_opt_range range;        /* CASE_OPT_SCALAR / CASE_OPT_LABEL */
    const char *help;            /* one line */
    size_t offset, size;         /* the field in case_umppm */
} case_option;

/* A table of options: the sub-dictionary of system/fvSolution it reads
 * ("UMPPM", "meshless") and its entries. */
typedef struct case_opt_table {
    const char *dict;
    const case_option *opt;
    size_t n;
} case_opt_table;

/* The options table (static storage); *n gets its length. */
const case_option *case_umppm_options(size_t *n);
/* What o allows, as in messages and -help: "UMPPM UMPPMstar UMPPM*",
 * "(0, 1)", "0 or [1, 4]", "> 0", ">= 1", "yes/no", "word". Returns buf. */
const char *case_option_allowed(const case_option *o, char *buf, size_t len);
/* Every field of u set to its default from the table. */
void case_umppm_defaults(case_umppm *u);
/* The table as text for umppmFoam -help, under the heading "UMPPM dictionary
 * (system/fvSolution)": key, default, allowed, then the help line. Writes at
 * most len bytes (NUL included) into buf as snprintf, returns the full
 * length (call with NULL, 0 to size the buffer). */
size_t case_umppm_help(char *buf, size_t len);

/* Read the UMPPM sub-dictionary of <case>/system/fvSolution (absent: all
 * defaults). Each key is read with its type and checked against its allowed
 * values; an error names file, line, key, value and what is allowed:
 *   system/fvSolution:12: UMPPM variant 'foo' is not one of: auto UMPPM UMPPMstar UMPPM*
 *   system/fvSolution:13: UMPPM alpha 1.5 is out of range: allowed (0, 1)
 * Keys not in the table are refused, as is a non-dictionary UMPPM or
 * predictorSolver:
 *   system/fvSolution:14: UMPPM: unknown key 'alpah'; known keys: variant alpha ...
 *   system/fvSolution:2: UMPPM must be a dictionary { ... }, found label 3 */
ump_status case_read_umppm(const char *case_dir, case_umppm *u, ump_err *err);

/* Read <case>/system/controlDict. Missing required keys (deltaT, endTime,
 * startTime unless latestTime/firstTime, writeInterval) are errors naming
 * file and line; unknown enumeration words are errors listing the valid ones;
 * startTime, endTime, deltaT, writeInterval, maxCo must be finite, deltaT,
 * writeInterval, maxDeltaT positive, endTime >= startTime (startFrom
 * startTime). endTime is read and checked only for stopAt endTime (as
 * Time::readDict; otherwise it may be absent, default 1e15). The same
 * function re-reads the file for runTimeModifiable. */
ump_status case_read_control(const char *case_dir, case_control *c, ump_err *err);
/* Read <case>/constant/transportProperties: nu (required), beta, TRef, Pr,
 * Prt (optional), each with or without dimensions; wrong dimensions or
 * values out of range are errors naming file and line. */
ump_status case_read_transport(const char *case_dir, case_transport *t, ump_err *err);
/* Error naming the first of beta, TRef, Pr missing from t. */
ump_status case_require_boussinesq(const char *case_dir, const case_transport *t, ump_err *err);
/* constant/g (absent: b->on = 0) and constant/hRef. */
ump_status case_read_buoyancy(const char *case_dir, case_buoyancy *b, ump_err *err);
/* Read <case>/system/fvSolution: pRefCell/pRefValue/pRefPoint from the PISO,
 * PIMPLE or SIMPLE sub-dictionary (first present). A missing file, or none
 * of the three dictionaries, is an error (icoFoam needs PISO). */
ump_status case_read_solution(const char *case_dir, case_solution *s, ump_err *err);

/* ---- meshlessFoam: the meshless sub-dictionary of system/fvSolution ------
 * All keys optional, one table (case_meshless_options) as for UMPPM:
 *   meshless { method MPS; spacing 0; reNumberDensity 3.1; reLaplacian 3.1;
 *              beta 0.98; lambda 0; sourceTerm mixed; gamma 0.1;
 *              collisionDistance 0.5; restitution 0.2; maxCo 0.2;
 *              pressureTolerance 1e-8; velocityTolerance 1e-10;
 *              maxIter 5000; cloudName meshlessCloud; maxVelocity 0;
 *              supportRadius 3; weightFunction spline; courantFPM 0.12;
 *              gravityStepFPM 0.24; surfaceRadius 3; surfaceBeta 0.8;
 *              surfaceShift 0.2; densitySourceFPM 0.02;
 *              laplacianStabilization 1; surfaceDampingFPM 0.1;
 *              wallDistance 0.25; mergeDistance 0.5; holeRadius 1.2;
 *              pairRepulsion 0.8; pairRepulsionCoeff 0.25;
 *              particleShifting 0; maxParticleLoss 0.2; maxParticleGain 0.2;
 *              manageInterval 1; }
 * (the last nineteen serve method FPM; reNumberDensity .. restitution and
 * maxCo serve MPS) */
typedef struct case_meshless {
    char method[16];             /* MPS */
    double spacing;              /* l0 [m]; 0: from the mesh */
    double re_n, re_lap;         /* radii / l0 */
    double beta;                 /* free-surface threshold */
    double lambda;               /* [m^2]; 0: Eq. 7 */
    int source_mixed;            /* sourceTerm: 0 density, 1 mixed */
    double gamma;
    double collision;            /* / l0; 0: off */
    double restitution;
    double max_co;               /* Courant number on l0 */
    double p_tol, u_tol;
    long maxit;
    char cloud_name[64];
    double max_velocity;         /* divergence bound; 0: from g and the domain */
    /* method FPM (fpm.h) */
    double support;              /* h0 / l0 */
    int weight;                  /* 5: spline (Eq. 5), 4: exponential (Eq. 4) */
    double fpm_co, fpm_cg;       /* coefficients of Eqs. 26, 27 */
    double re_s, beta_s;         /* free-surface number density: radius / l0, threshold */
    double shift_s;              /* free surface: centroid offset / l0 */
    double gamma_fpm;            /* FPM: weight of the density deviation in the PPE source */
    double stab_fpm;             /* FPM: weight of the stabilising term of the PPE Laplacian */
    double surf_damp_fpm;        /* FPM: free-surface velocity damping / (l0 sqrt(|g| l0)) */
    double max_loss;             /* FPM: stop when this fraction of the liquid's particles is merged away */
    double max_gain;             /* FPM: ... or when insertion has added this fraction */
    double d_wall, d_min, r_hole;/* particle management / l0 (fpm_manage) */
    double shift_a;              /* particle shifting coefficient; 0: off */
    double d_rep, c_rep;         /* FPM close-pair repulsion radius / l0 (0: off), coefficient */
    long manage_interval;        /* steps between particle managements */
} case_meshless;

const case_option *case_meshless_options(size_t *n);
void case_meshless_defaults(case_meshless *u);
size_t case_meshless_help(char *buf, size_t len);
/* Read the meshless sub-dictionary of <case>/system/fvSolution (absent:
 * defaults), with the messages of case_read_umppm. */
ump_status case_read_meshless(const char *case_dir, case_meshless *u, ump_err *err);

/* meshlessFoam's moving container: constant/dynamicMeshDict with the whole
 * mesh in solidBody motion, as OpenFOAM v1912 reads it (sloshingTank2D):
 *   dynamicFvMesh dynamicMotionSolverFvMesh; motionSolver solidBody;
 *   solidBodyMotionFunction oscillatingLinearMotion;
 *   oscillatingLinearMotionCoeffs { amplitude (0.05 0 0); omega 4.18879; }
 * (the motion entries may also sit in solidBodyCoeffs { }). Displacement
 * amplitude sin(omega t) (Lu et al. 2019, Eq. 28). Or wall patches moved by
 * the point displacement (a wave maker, as OpenFOAM's waveMakerPiston):
 *   dynamicFvMesh dynamicMotionSolverFvMesh;
 *   motionSolver displacementLaplacian;   (or solver ...; deform = 1)
 * Absent, or dynamicFvMesh staticFvMesh: on = deform = 0. Anything else --
 * another motion function or solver, a cellZone/cellSet (part of the
 * mesh), topology changes -- is refused by name. */
typedef struct case_motion {
    int on;                /* the whole container sways */
    int deform;            /* motionSolver displacementLaplacian: wall
                              patches move as 0/pointDisplacement says (mlapp.c) */
    double amplitude[3];   /* [m] */
    double omega;          /* [rad/s] */
} case_motion;
ump_status case_read_motion(const char *case_dir, case_motion *mo, ump_err *err);

/* interFoam's constant/transportProperties: phases (liquid gas); each
 * phase { transportModel Newtonian; nu; rho; }; sigma (a value, or v1912's
 * sigma { type constant; sigma ...; }, or another surfaceTensionModel by
 * name). name[0] is the liquid (its alpha.<name> is the volume fraction). */
typedef struct case_phases {
    char name[2][64];
    double nu[2], rho[2];
    double sigma;           /* constant sigma, where has_sigma */
    int has_sigma;
    char sigma_model[64];   /* a surfaceTensionModel other than constant, or "" */
} case_phases;
ump_status case_read_phases(const char *case_dir, case_phases *ph, ump_err *err);

/* runTimeModifiable's log: ", key old -> new" for every setting of c that
 * differs from o ("" if none); delta_t_fixed: adjustTimeStep has set the
 * step, so a new deltaT is not used. */
void case_control_changes(const case_control *o, const case_control *c, int delta_t_fixed, char *buf,
                          size_t len);
/* stopAt's word (endTime, writeNow, noWriteNow, nextWrite). */
const char *case_stop_at_name(int stop_at);

/* deltaT of <case>/<tname>/uniform/time (as OpenFOAM's Time writes it),
 * *has = 0 where the file or the entry is absent. */
ump_status case_read_time_delta_t(const char *case_dir, const char *tname, double *delta_t, int *has,
                                  ump_err *err);

/* 1 if name can become one path component (a cloud or function-object
 * directory): non-empty, no '/', no "..". */
int case_name_is_safe(const char *name);
/* endTime before the start time t0 (directory tname) is an error (stopAt
 * endTime only). */
ump_status case_check_start(const char *case_dir, const case_control *c, const char *tname, double t0,
                            ump_err *err);

/* What tells one version of a file from another without reading it: its
 * device and inode (an editor that writes a new file and renames it over
 * the old one), size, and modification and status-change times to the
 * nanosecond the filesystem keeps. runTimeModifiable compares these, as
 * OpenFOAM's fileModificationChecking timeStamp compares the mtime. */
typedef struct case_stamp {
    unsigned long long dev, ino;
    long long size;
    long long mtime_sec, ctime_sec;
    long mtime_nsec, ctime_nsec;
} case_stamp;
/* The stamp of path: 0, or -1 (errno set, *s zeroed) when stat fails. */
int case_file_stamp(const char *path, case_stamp *s);
/* 1 when a and b are the same version. */
int case_stamp_equal(const case_stamp *a, const case_stamp *b);

/* Time directories of a case: names whose text reads fully as a number
 * (plus "0"), sorted by value. *names is an array of *n malloc'd strings;
 * free with case_free_times. */
ump_status case_list_times(const char *case_dir, char ***names, double **values,
                           int *n, ump_err *err);
void case_free_times(char **names, double *values, int n);

/* The start time directory per controlDict startFrom (startTime: the
 * directory whose value equals startTime within 1e-12 relative, error if
 * none; latestTime; firstTime). */
ump_status case_start_dir(const char *case_dir, const case_control *c,
                          char *name, size_t len, double *value, ump_err *err);

#endif
