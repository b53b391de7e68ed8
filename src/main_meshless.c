/* SPDX-License-Identifier: GPL-3.0-or-later
 * main_meshless.c -- the meshlessFoam application: OpenFOAM-style command
 * line, banner and log; the only place of this application that prints
 * errors and exits.
 *
 *   meshlessFoam [-case DIR] [-reseed] [-noFunctionObjects] [-help] [-version]
 *
 * -help also lists the keys of the meshless dictionary of system/fvSolution
 * (case_meshless_help: the reader's own table).
 */
#include "umppm/case.h"
#include "umppm/mlapp.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define MESHLESS_VERSION "0.1"

static void usage(FILE *fp)
{
    fprintf(fp,
            "\nUsage: meshlessFoam [OPTIONS]\n"
            "options:\n"
            "  -case <dir>       Specify case directory to use (instead of the cwd)\n"
            "  -reseed           A restart time without its particle cloud: seed new particles\n"
            "                    from its alpha and U (else an error)\n"
            "  -noFunctionObjects  Do not execute function objects (meshlessFoam runs none)\n"
            "  -version          Print the version and exit\n"
            "  -help             Print this usage and the meshless options, then exit\n"
            "\nFree-surface flow on particles alone (method MPS: fully implicit MPS;\n"
            "method FPM: the finite particle method), run in an\n"
            "interFoam (laminar) case directory as it is: the wall patches of\n"
            "constant/polyMesh are the container, 0/alpha.<liquid> the initial liquid.\n\n");
}

static void help(FILE *fp)
{
    usage(fp);
    size_t n = case_meshless_help(NULL, 0);
    char *text = malloc(n + 1);
    if (text) {
        case_meshless_help(text, n + 1);
        fputs(text, fp);
        fputs("\n", fp);
    }
    free(text);
}

static void banner(int argc, char **argv, const char *case_dir)
{
    char host[256] = "unknown", cwd[PATH_MAX], when[64], clock[64];
    gethostname(host, sizeof host);
    time_t now = time(NULL);
    struct tm tmv;
    localtime_r(&now, &tmv);
    strftime(when, sizeof when, "%b %d %Y", &tmv);
    strftime(clock, sizeof clock, "%H:%M:%S", &tmv);
    const char *abs = realpath(case_dir, cwd) ? cwd : case_dir;
    printf("/*---------------------------------------------------------------------------*\\\n"
           "| meshlessFoam: free-surface flow on particles (implicit MPS, finite particle)|\n"
           "| Version:   %-65s|\n"
           "| Reads and writes OpenFOAM (v1912) case directories                          |\n"
           "\\*---------------------------------------------------------------------------*/\n",
           MESHLESS_VERSION);
    printf("Build  : meshlessFoam-%s (C11)\n", MESHLESS_VERSION);
    printf("Exec   :");
    for (int i = 0; i < argc; i++)
        printf(" %s", argv[i]);
    printf("\nDate   : %s\nTime   : %s\nHost   : %s\nPID    : %ld\nCase   : %s\nnProcs : 1\n", when, clock, host,
           (long)getpid(), abs);
    printf("\n// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n");
}

static int run(int argc, char **argv)
{
    const char *case_dir = ".";
    mlapp_options opt = {0, 0};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (a[0] == '-' && a[1] == '-')
            a++;
        if (strcmp(a, "-case") == 0) {
            if (i + 1 >= argc || argv[i + 1][0] == '\0') {
                fprintf(stderr, "--> meshlessFoam FATAL ERROR: option -case needs a directory\n");
                usage(stderr);
                return 1;
            }
            case_dir = argv[++i];
        } else if (strcmp(a, "-reseed") == 0) {
            opt.reseed = 1;
        } else if (strcmp(a, "-noFunctionObjects") == 0) {
            opt.no_function_objects = 1;
        } else if (strcmp(a, "-help") == 0 || strcmp(a, "-h") == 0) {
            help(stdout);
            return 0;
        } else if (strcmp(a, "-version") == 0) {
            printf("meshlessFoam %s (reads OpenFOAM v1912 cases)\n", MESHLESS_VERSION);
            return 0;
        } else if (strcmp(a, "-parallel") == 0) {
            fprintf(stderr, "--> meshlessFoam FATAL ERROR: option -parallel is not implemented: meshlessFoam "
                    "runs one process on the undecomposed case, with threads (set OMP_NUM_THREADS)\n");
            return 1;
        } else {
            fprintf(stderr, "--> meshlessFoam FATAL ERROR: unknown option '%s'\n", argv[i]);
            usage(stderr);
            return 1;
        }
    }
    banner(argc, argv, case_dir);
    ump_err err;
    if (mlapp_run(case_dir, &opt, &err) != UMP_OK) {
        fflush(stdout);
        fprintf(stderr, "--> meshlessFoam FATAL ERROR: %s\n", err.msg);
        return 1;
    }
    printf("End\n\n");
    return 0;
}

int main(int argc, char **argv)
{
    ump_solver = "meshlessFoam";
    int rc = run(argc, argv);
    errno = 0;
    if ((fflush(stdout) != 0 || ferror(stdout)) && rc == 0) {
        fprintf(stderr, "--> meshlessFoam FATAL ERROR: standard output: cannot write the log (%s)\n",
                errno ? strerror(errno) : "write error");
        rc = 1;
    }
    return rc;
}
