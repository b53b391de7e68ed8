/* SPDX-License-Identifier: GPL-3.0-or-later
 * fieldio_write.c -- the writing half of fieldio.h: volScalarField and
 * volVectorField files, <time>/uniform/time, and time directories that
 * appear atomically.
 *
 * The layout is OpenFOAM v1912's, byte for byte after the banner (checked
 * against icoFoam and pimpleFoam output): keywords padded to column 17,
 * `uniform X` when a non-empty field has all elements equal, ascii lists of
 * up to 10 elements on one line and longer ones one element per line,
 * binary lists as "\nN\n(" + little-endian doubles + ")", empty lists
 * "0()" (ascii) or "0" (binary) without a List<> prefix.
 */
/* renameat2 (glibc >= 2.28) needs _GNU_SOURCE */
#define _GNU_SOURCE
#include "umppm/fieldio.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/types.h>
#include <unistd.h>
#include <zlib.h>

#define DIVIDER_STAR \
    "// ************************************************************************* //"
#define DIVIDER_DOT \
    "// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //"

/* OpenFOAM's Ostream::writeKeyword pads keywords to this width. */
#define KEY_WIDTH 16
/* OpenFOAM's shortListLen: ascii lists this long or shorter stay on one line. */
#define SHORT_LIST 10

/* Output to a plain FILE or a gzip stream through one small buffer, so the
 * same formatting code serves both and errors are collected once. */
typedef struct sink {
    FILE *fp;
    gzFile gz;
    int failed;
    size_t len;
    char buf[16384];
} sink;

static void sink_flush(sink *s)
{
    if (s->len && !s->failed) {
        if (s->gz) {
            if (gzwrite(s->gz, s->buf, (unsigned)s->len) != (int)s->len)
                s->failed = 1;
        } else if (fwrite(s->buf, 1, s->len, s->fp) != s->len) {
            s->failed = 1;
        }
    }
    s->len = 0;
}

static void sink_put(sink *s, const void *p, size_t n)
{
    const char *c = p;
    while (n) {
        if (s->len == sizeof s->buf)
            sink_flush(s);
        size_t k = sizeof s->buf - s->len;
        if (k > n)
            k = n;
        memcpy(s->buf + s->len, c, k);
        s->len += k;
        c += k;
        n -= k;
    }
}

static void sink_puts(sink *s, const char *str)
{
    sink_put(s, str, strlen(str));
}

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static void sink_printf(sink *s, const char *fmt, ...)
{
    char small[256];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(small, sizeof small, fmt, ap);
    va_end(ap);
    if (n < 0) {
        s->failed = 1;
        return;
    }
    if ((size_t)n < sizeof small) {
        sink_put(s, small, (size_t)n);
        return;
    }
    /* long names: format again into a buffer of the right size */
    char *big = malloc((size_t)n + 1);
    if (!big) {
        s->failed = 1;
        return;
    }
    va_start(ap, fmt);
    vsnprintf(big, (size_t)n + 1, fmt, ap);
    va_end(ap);
    sink_put(s, big, (size_t)n);
    free(big);
}

/* A number as C++ ostream writes it in its default (general) float format. */
static void put_num(sink *s, double v, int prec)
{
    sink_printf(s, "%.*g", prec, v);
}

/* One element: a scalar, or "(x y z)". OpenFOAM writes both ascii and
 * binary single values as text, without inner padding. */
static void put_elem(sink *s, const double *v, int ncomp, int prec)
{
    if (ncomp == 1) {
        put_num(s, v[0], prec);
        return;
    }
    sink_puts(s, "(");
    for (int k = 0; k < ncomp; k++) {
        if (k)
            sink_puts(s, " ");
        put_num(s, v[k], prec);
    }
    sink_puts(s, ")");
}

/* The key, then spaces to column KEY_WIDTH (at least one), after indent. */
static void put_key(sink *s, int indent, const char *key)
{
    static const char spaces[] = "                                ";
    sink_put(s, spaces, (size_t)indent);
    sink_puts(s, key);
    size_t len = strlen(key);
    size_t pad = len < KEY_WIDTH ? KEY_WIDTH - len : 1;
    sink_put(s, spaces, pad);
}

static void put_raw_le(sink *s, const double *v, size_t n)
{
    unsigned char b[8];
    for (size_t i = 0; i < n; i++) {
        uint64_t bits;
        memcpy(&bits, &v[i], sizeof bits);
        /* written byte by byte so big-endian hosts still produce LSB data */
        for (int k = 0; k < 8; k++)
            b[k] = (unsigned char)(bits >> (8 * k));
        sink_put(s, b, sizeof b);
    }
}

/* OpenFOAM's Field::writeEntry: "uniform X" when non-empty and all elements
 * equal, else "nonuniform" + the list; then ";\n". */
static void put_field_value(sink *s, const double *v, ump_idx n, int ncomp,
                            int binary, int prec)
{
    int uniform = n > 0;
    for (ump_idx i = 1; uniform && i < n; i++)
        for (int k = 0; k < ncomp; k++)
            if (!(v[(size_t)i * ncomp + k] == v[k])) {
                uniform = 0;
                break;
            }
    if (uniform) {
        sink_puts(s, "uniform ");
        put_elem(s, v, ncomp, prec);
    } else if (n == 0) {
        /* List::writeEntry drops the List<T> prefix of empty lists */
        sink_puts(s, binary ? "nonuniform 0" : "nonuniform 0()");
    } else {
        sink_puts(s, ncomp == 1 ? "nonuniform List<scalar> " : "nonuniform List<vector> ");
        if (binary) {
            sink_printf(s, "\n%ld\n(", (long)n);
            put_raw_le(s, v, (size_t)n * (size_t)ncomp);
            sink_puts(s, ")");
        } else if (n <= SHORT_LIST) {
            sink_printf(s, "%ld(", (long)n);
            for (ump_idx i = 0; i < n; i++) {
                if (i)
                    sink_puts(s, " ");
                put_elem(s, v + (size_t)i * ncomp, ncomp, prec);
            }
            sink_puts(s, ")");
        } else {
            sink_printf(s, "\n%ld\n(\n", (long)n);
            for (ump_idx i = 0; i < n; i++) {
                put_elem(s, v + (size_t)i * ncomp, ncomp, prec);
                sink_puts(s, "\n");
            }
            sink_puts(s, ")\n");
        }
    }
    sink_puts(s, ";\n");
}

static void put_header(sink *s, const char *cls, const char *location,
                       const char *object, int binary)
{
    sink_puts(s,
        "/*--------------------------------*- C++ -*----------------------------------*\\\n"
        "| =========                 |                                                 |\n"
        "| \\\\      /  F ield         | umppmFoam: OpenFOAM v1912 case file format      |\n"
        "|  \\\\    /   O peration     | Written by umppmFoam, not by OpenFOAM           |\n"
        "|   \\\\  /    A nd           |                                                 |\n"
        "|    \\\\/     M anipulation  |                                                 |\n"
        "\\*---------------------------------------------------------------------------*/\n"
        "FoamFile\n{\n"
        "    version     2.0;\n");
    sink_puts(s, binary ? "    format      binary;\n" : "    format      ascii;\n");
    sink_printf(s, "    class       %s;\n", cls);
    if (binary)
        sink_puts(s, "    arch        \"LSB;label=32;scalar=64\";\n");
    if (location)
        sink_printf(s, "    location    \"%s\";\n", location);
    sink_printf(s, "    object      %s;\n", object);
    sink_puts(s, "}\n" DIVIDER_DOT "\n\n");
}

static void put_footer(sink *s)
{
    sink_puts(s, "\n\n" DIVIDER_STAR "\n");
}

void fio_write_header(FILE *fp, const char *cls, const char *location,
                      const char *object, int binary)
{
    sink s = {.fp = fp}; /* 16 KiB on the stack: nothing to fail; a write error stays in ferror(fp) */
    put_header(&s, cls, location, object, binary);
    sink_flush(&s);
}

void fio_write_footer(FILE *fp)
{
    fputs("\n\n" DIVIDER_STAR "\n", fp);
}

/* ---- directories ------------------------------------------------------ */

ump_status fio_mkdir_p(const char *path, ump_err *err)
{
    UMP_CHECK(path && *path, err, UMP_ERR_INPUT, "fio_mkdir_p: empty path");
    char *p = ump_strdup(path);
    if (!p)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", path);
    size_t len = strlen(p);
    while (len > 1 && p[len - 1] == '/')
        p[--len] = '\0';
    /* create each prefix in turn; an existing directory is fine */
    for (char *c = p + 1;; c++) {
        int last = (*c == '\0');
        if (*c == '/' || last) {
            char keep = *c;
            *c = '\0';
            if (mkdir(p, 0777) != 0) {
                int e = errno;
                struct stat st;
                if (e != EEXIST || stat(p, &st) != 0 || !S_ISDIR(st.st_mode)) {
                    ump_status rc = UMP_FAIL(err, UMP_ERR_IO, "%s: cannot create directory: %s",
                                             p, strerror(e == EEXIST ? ENOTDIR : e));
                    free(p);
                    return rc;
                }
            }
            *c = keep;
        }
        if (last)
            break;
    }
    free(p);
    return UMP_OK;
}

/* Remove a file or a directory tree without following symbolic links.
 * Returns 0 on success (or when path does not exist). */
static int rm_tree(const char *path)
{
    struct stat st;
    if (lstat(path, &st) != 0)
        return errno == ENOENT ? 0 : -1;
    if (!S_ISDIR(st.st_mode))
        return unlink(path);
    DIR *d = opendir(path);
    if (!d)
        return -1;
    int rc = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        size_t n = strlen(path) + strlen(e->d_name) + 2;
        char *child = malloc(n);
        if (!child) {
            rc = -1;
            break;
        }
        snprintf(child, n, "%s/%s", path, e->d_name);
        if (rm_tree(child) != 0)
            rc = -1;
        free(child);
    }
    closedir(d);
    if (rmdir(path) != 0)
        rc = -1;
    return rc;
}

ump_status fio_remove_dir(const char *path, ump_err *err)
{
    if (rm_tree(path) != 0)
        return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot remove (%s)", path, strerror(errno));
    return UMP_OK;
}

/* Swap two directories atomically: renameat2(RENAME_EXCHANGE), Linux >=
 * 3.15. -1 with errno EINVAL/ENOSYS/EOPNOTSUPP where the filesystem or the
 * kernel has no exchange. */
#ifndef RENAME_EXCHANGE
#define RENAME_EXCHANGE (1 << 1)
#endif
static int exchange(const char *a, const char *b)
{
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 28))
    return renameat2(AT_FDCWD, a, AT_FDCWD, b, RENAME_EXCHANGE);
#elif defined(SYS_renameat2)
    return (int)syscall(SYS_renameat2, AT_FDCWD, a, AT_FDCWD, b, RENAME_EXCHANGE);
#else
    (void)a;
    (void)b;
    errno = ENOSYS;
    return -1;
#endif
}

/* 1 when path exists, 0 when not; -1 (message in err) when it exists but is
 * not a directory: a time directory is never written over a file. */
static int dir_in_place(const char *path, const char *name, ump_err *err)
{
    struct stat st;
    if (lstat(path, &st) != 0)
        return 0;
    if (S_ISDIR(st.st_mode))
        return 1;
    UMP_FAIL(err, UMP_ERR_IO, "%s: a %s named %s is in the way of time directory %s, which this "
             "run writes; move or remove it (umppmFoam does not delete it)", path,
             S_ISLNK(st.st_mode) ? "symbolic link" : S_ISREG(st.st_mode) ? "file" : "non-directory",
             name, name);
    return -1;
}

ump_status fio_timedir_check(const char *case_dir, const char *name, ump_err *err)
{
    char path[4200];
    int n = snprintf(path, sizeof path, "%s/%s", case_dir, name);
    UMP_CHECK(n > 0 && (size_t)n < sizeof path, err, UMP_ERR_INPUT, "%s: path too long", case_dir);
    return dir_in_place(path, name, err) < 0 ? UMP_ERR_IO : UMP_OK;
}

ump_status fio_timedir_begin(const char *case_dir, const char *name,
                             fio_timedir *td, ump_err *err)
{
    UMP_CHECK(td, err, UMP_ERR_INPUT, "fio_timedir_begin: no timedir");
    memset(td, 0, sizeof *td);
    UMP_CHECK(case_dir && *case_dir, err, UMP_ERR_INPUT, "fio_timedir_begin: empty case path");
    UMP_CHECK(name && *name && !strchr(name, '/') && strcmp(name, ".") != 0
                  && strcmp(name, "..") != 0,
              err, UMP_ERR_INPUT, "%s: invalid time directory name '%s'", case_dir,
              name ? name : "");
    UMP_CHECK(strlen(name) < sizeof td->name, err, UMP_ERR_INPUT,
              "%s: time name '%s' too long", case_dir, name);
    long pid = (long)getpid();
    int n1 = snprintf(td->final_dir, sizeof td->final_dir, "%s/%s", case_dir, name);
    int n2 = snprintf(td->tmp_dir, sizeof td->tmp_dir, "%s/" FIO_HIDDEN_FMT, case_dir, name,
                      FIO_HIDDEN_TMP, pid);
    UMP_CHECK(n1 > 0 && n2 > 0 && (size_t)n1 < sizeof td->final_dir
                  && (size_t)n2 < sizeof td->tmp_dir,
              err, UMP_ERR_INPUT, "%s: path too long", case_dir);
    memcpy(td->name, name, strlen(name) + 1);

    struct stat st;
    if (stat(case_dir, &st) != 0 || !S_ISDIR(st.st_mode))
        return UMP_FAIL(err, UMP_ERR_IO, "%s: case directory not found", case_dir);
    /* a file where the time directory goes: refused before anything is written */
    if (dir_in_place(td->final_dir, name, err) < 0)
        return UMP_ERR_IO;
    /* a leftover of an earlier crashed run with the same pid */
    if (rm_tree(td->tmp_dir) != 0)
        return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot remove stale directory: %s",
                        td->tmp_dir, strerror(errno));
    if (mkdir(td->tmp_dir, 0777) != 0)
        return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot create directory: %s",
                        td->tmp_dir, strerror(errno));
    td->open = 1;
    return UMP_OK;
}

/* A copy of regular file src as dst (where a hard link cannot be made). */
static int copy_file(const char *src, const char *dst, mode_t mode)
{
    int in = open(src, O_RDONLY), out = in < 0 ? -1 : open(dst, O_WRONLY | O_CREAT | O_EXCL, mode & 0777);
    int rc = in < 0 || out < 0 ? -1 : 0;
    char buf[65536];
    for (ssize_t r; rc == 0 && (r = read(in, buf, sizeof buf)) != 0;) {
        if (r < 0 || write(out, buf, (size_t)r) != r)
            rc = -1;
    }
    if (in >= 0)
        close(in);
    if (out >= 0 && close(out) != 0)
        rc = -1;
    return rc;
}

/* Give the new version of a time directory (dst) what the version it
 * replaces (src) holds and the new one does not: files other tools wrote
 * there (postProcess's vorticity, a user's notes) survive the overwrite,
 * as OpenFOAM's solvers write into an existing time directory. Files are
 * hard-linked (copied where a link cannot be made), so src stays whole
 * until the swap. A directory in both is entered only where it is
 * uniform/ or lagrangian/ at the top (level 0), and a cloud directory
 * under lagrangian/ that the new version has is the new version's alone
 * (an old cloud field beside new positions would not match their count);
 * any other directory in both, and any file in both, is the new one's.
 * A file X is the new version's also where it has X.gz (or the reverse):
 * the plain name is read first. Not kept either: the fluxes and old-time
 * levels of the flow the new version replaces (phi, meshPhi, alphaPhi*,
 * Uf, ddt0(*), *_0) and its moved mesh (polyMesh/), which an OpenFOAM
 * solver continuing from this time, or ParaView, would read with the new
 * fields. Returns 0, or -1 with errno. */
static int flow_state(const char *file)
{
    char name[256];
    snprintf(name, sizeof name, "%s", file);
    size_t n = strlen(name);
    if (n > 3 && strcmp(name + n - 3, ".gz") == 0)
        name[n -= 3] = '\0';
    return strcmp(name, "phi") == 0 || strcmp(name, "meshPhi") == 0 || strncmp(name, "alphaPhi", 8) == 0 ||
           strcmp(name, "Uf") == 0 || strncmp(name, "ddt0(", 5) == 0 || (n > 2 && strcmp(name + n - 2, "_0") == 0);
}

/* Does dst hold name, or its other form (X and X.gz are one field: a stale
 * plain X would shadow a new X.gz)? */
static int new_has(const char *dst, const char *name)
{
    char t[4400];
    struct stat st;
    size_t n = strlen(name);
    if ((size_t)snprintf(t, sizeof t, "%s/%s", dst, name) < sizeof t && lstat(t, &st) == 0)
        return 1;
    if (n > 3 && strcmp(name + n - 3, ".gz") == 0)
        snprintf(t, sizeof t, "%s/%.*s", dst, (int)(n - 3), name);
    else
        snprintf(t, sizeof t, "%s/%s.gz", dst, name);
    return lstat(t, &st) == 0;
}

static int keep_others(const char *src, const char *dst, int level)
{
    DIR *d = opendir(src);
    if (!d)
        return -1;
    int rc = 0;
    for (struct dirent *e; rc == 0 && (e = readdir(d)) != NULL;) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        char s[4400], t[4400];
        if ((size_t)snprintf(s, sizeof s, "%s/%s", src, e->d_name) >= sizeof s ||
            (size_t)snprintf(t, sizeof t, "%s/%s", dst, e->d_name) >= sizeof t) {
            errno = ENAMETOOLONG;
            rc = -1;
            break;
        }
        struct stat ss, ts;
        if (lstat(s, &ss) != 0) {
            rc = -1;
            break;
        }
        if (lstat(t, &ts) == 0) {
            if (S_ISDIR(ss.st_mode) && S_ISDIR(ts.st_mode) && level == 0 &&
                (strcmp(e->d_name, "uniform") == 0 || strcmp(e->d_name, "lagrangian") == 0))
                rc = keep_others(s, t, strcmp(e->d_name, "uniform") == 0 ? 2 : 1);
            else if (S_ISDIR(ss.st_mode) && S_ISDIR(ts.st_mode) && level == 2)
                rc = keep_others(s, t, 2); /* uniform/functionObjects/... */
            continue;
        }
        if (errno != ENOENT) {
            rc = -1;
        } else if (!S_ISDIR(ss.st_mode) && new_has(dst, e->d_name)) {
            continue; /* X beside a new X.gz, or the reverse */
        } else if (level == 0 && !S_ISDIR(ss.st_mode) && flow_state(e->d_name)) {
            continue; /* the replaced flow's flux or old-time level */
        } else if (level == 0 && S_ISDIR(ss.st_mode) && strcmp(e->d_name, "polyMesh") == 0) {
            continue; /* the replaced run's moved mesh (a swaying container's) */
        } else if (S_ISDIR(ss.st_mode)) {
            rc = mkdir(t, 0777) != 0 ? -1 : keep_others(s, t, 3); /* (writable: filled here) */
        } else if (S_ISLNK(ss.st_mode)) {
            char l[4400];
            ssize_t n = readlink(s, l, sizeof l - 1);
            rc = n < 0 ? -1 : (l[n] = '\0', symlink(l, t));
        } else if (link(s, t) != 0) {
            rc = S_ISREG(ss.st_mode) ? copy_file(s, t, ss.st_mode) : 0; /* (sockets, fifos: not kept) */
        }
    }
    int keep = errno;
    closedir(d);
    errno = keep;
    return rc;
}

ump_status fio_timedir_commit(fio_timedir *td, ump_err *err)
{
    UMP_CHECK(td && td->open, err, UMP_ERR_INPUT, "fio_timedir_commit: no open time directory");
    int there = dir_in_place(td->final_dir, td->name, err);
    if (there < 0)
        return UMP_ERR_IO;
    if (!there) {
        if (rename(td->tmp_dir, td->final_dir) != 0)
            return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot rename into place: %s",
                            td->final_dir, strerror(errno));
        td->open = 0;
        return UMP_OK;
    }

    /* files of the old version that this one does not write are kept */
    if (keep_others(td->final_dir, td->tmp_dir, 0) != 0)
        return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot carry its other files into the new version (%s): the "
                        "previous version is left as it was", td->final_dir, strerror(errno));
    /* Overwrite. First choice: swap the new directory and the old one in one
     * atomic step, then delete the old one, now under the hidden temporary
     * name. A kill at any instant leaves <name> complete (old or new) and at
     * most a hidden .<name>.tmp.<pid>, which fio_recover removes. */
    if (exchange(td->tmp_dir, td->final_dir) == 0) {
        td->open = 0;
        (void)rm_tree(td->tmp_dir); /* the old version: losing it loses nothing */
        return UMP_OK;
    }
    int e = errno;
    if (e != EINVAL && e != ENOSYS && e != EOPNOTSUPP && e != ENOTSUP)
        return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot swap the new version into place: %s",
                        td->final_dir, strerror(e));

    /* No exchange on this filesystem: rename() cannot replace a non-empty
     * directory, so move the old one aside (hidden, .<name>.old.<pid>), move
     * the new one in, then delete the old one. A kill between the two
     * renames leaves no <name> but the hidden old copy, which fio_recover
     * renames back at the next start. */
    char old[4200];
    size_t case_len = strlen(td->final_dir) - strlen(td->name) - 1;
    int n = snprintf(old, sizeof old, "%.*s/" FIO_HIDDEN_FMT, (int)case_len, td->final_dir,
                     td->name, FIO_HIDDEN_OLD, (long)getpid());
    UMP_CHECK(n > 0 && (size_t)n < sizeof old, err, UMP_ERR_INPUT, "%s: path too long",
              td->final_dir);
    if (rm_tree(old) != 0)
        return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot remove stale directory: %s", old,
                        strerror(errno));
    if (rename(td->final_dir, old) != 0)
        return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot move the previous version aside: %s",
                        td->final_dir, strerror(errno));
    if (rename(td->tmp_dir, td->final_dir) != 0) {
        e = errno;
        /* put the previous version back; the new one stays in tmp_dir for
         * fio_timedir_abort() */
        (void)rename(old, td->final_dir);
        return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot rename into place: %s",
                        td->final_dir, strerror(e));
    }
    td->open = 0;
    /* the new directory is in place; a failure to delete the hidden old
     * copy loses nothing, so it is not reported */
    (void)rm_tree(old);
    return UMP_OK;
}

ump_status fio_remove_timedir(const char *case_dir, const char *name, ump_err *err)
{
    char path[4200], del[4200];
    int n1 = snprintf(path, sizeof path, "%s/%s", case_dir, name);
    int n2 = snprintf(del, sizeof del, "%s/" FIO_HIDDEN_FMT, case_dir, name, FIO_HIDDEN_DEL,
                      (long)getpid());
    UMP_CHECK(n1 > 0 && n2 > 0 && (size_t)n1 < sizeof path && (size_t)n2 < sizeof del, err,
              UMP_ERR_INPUT, "%s: path too long", case_dir);
    struct stat st;
    if (lstat(path, &st) != 0)
        return errno == ENOENT ? UMP_OK
                               : UMP_FAIL(err, UMP_ERR_IO, "%s: %s", path, strerror(errno));
    UMP_CHECK(S_ISDIR(st.st_mode), err, UMP_ERR_IO, "%s: not a directory (not removed)", path);
    if (rm_tree(del) != 0 || rename(path, del) != 0)
        return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot remove (%s)", path, strerror(errno));
    return fio_remove_dir(del, err);
}

void fio_timedir_abort(fio_timedir *td)
{
    if (!td || !td->open)
        return;
    (void)rm_tree(td->tmp_dir);
    td->open = 0;
}

/* ---- files ------------------------------------------------------------ */

/* Open path for writing, plain or gzip. */
static int sink_open(sink *s, const char *path, int gz)
{
    memset(s, 0, offsetof(sink, buf));
    if (gz) {
        s->gz = gzopen(path, "wb");
        return s->gz ? 0 : -1;
    }
    s->fp = fopen(path, "wb");
    return s->fp ? 0 : -1;
}

/* Flush and close; returns 0 when every byte was written. */
static int sink_close(sink *s)
{
    sink_flush(s);
    int bad = s->failed;
    if (s->gz) {
        if (gzclose(s->gz) != Z_OK)
            bad = 1;
    } else if (s->fp) {
        if (ferror(s->fp))
            bad = 1;
        if (fclose(s->fp) != 0)
            bad = 1;
    }
    s->gz = NULL;
    s->fp = NULL;
    return bad ? -1 : 0;
}

/* Does the boundary type write a `value` entry (v1912)? */
static int bc_writes_value(fld_bc_type t)
{
    switch (t) {
    case FLD_BC_CALCULATED:
    case FLD_BC_FIXEDVALUE:
    case FLD_BC_MOVINGWALLVELOCITY:
    case FLD_BC_FIXEDFLUXPRESSURE:
    case FLD_BC_INLETOUTLET:
    case FLD_BC_UNIFORMFIXEDVALUE:
    case FLD_BC_FLOWRATEINLETVELOCITY:
    case FLD_BC_OUTLETINLET:
    case FLD_BC_TOTALPRESSURE:
    case FLD_BC_PRESSUREINLETOUTLETVELOCITY:
        return 1;
    default:
        return 0; /* slip writes its type only, as v1912 */
    }
}

/* Is the second value list optional (written only when present)? */
static int bc_aux_optional(fld_bc_type t)
{
    return t == FLD_BC_PRESSUREINLETOUTLETVELOCITY;
}

static ump_status check_field(const char *path, const pmesh *pm, const fld_field *f,
                              ump_err *err)
{
    UMP_CHECK(f->ncomp == 1 || f->ncomp == 3, err, UMP_ERR_INPUT,
              "%s: field has %d components (expected 1 or 3)", path, f->ncomp);
    UMP_CHECK(f->ncells >= 0 && (f->ncells == 0 || f->internal), err, UMP_ERR_INPUT,
              "%s: field has no internal values", path);
    UMP_CHECK(f->npatches == pm->npatches, err, UMP_ERR_INPUT,
              "%s: field has %d patches, mesh has %d", path, f->npatches, pm->npatches);
    for (int i = 0; i < f->npatches; i++) {
        const fld_patch *p = &f->patch[i];
        const char *pn = pm->patch[i].name ? pm->patch[i].name : "";
        UMP_CHECK(*pn, err, UMP_ERR_INPUT, "%s: mesh patch %d has no name", path, i);
        UMP_CHECK((int)p->type >= 0 && p->type < FLD_BC_NTYPES, err, UMP_ERR_INPUT,
                  "%s: patch %s has an invalid boundary type %d", path, pn, (int)p->type);
        UMP_CHECK(p->n == pm->patch[i].n, err, UMP_ERR_INPUT,
                  "%s: patch %s has %ld values, mesh patch has %ld faces", path, pn,
                  (long)p->n, (long)pm->patch[i].n);
        UMP_CHECK(p->n == 0 || !bc_writes_value(p->type) || p->value, err, UMP_ERR_INPUT,
                  "%s: patch %s (%s) has no values", path, pn, fld_bc_name(p->type));
        UMP_CHECK(p->n == 0 || !fld_bc_aux_key(p->type) || bc_aux_optional(p->type) || p->aux, err, UMP_ERR_INPUT,
                  "%s: patch %s (%s) has no %s", path, pn, fld_bc_name(p->type),
                  fld_bc_aux_key(p->type) ? fld_bc_aux_key(p->type) : "");
        for (int k = 0; k < p->nextra; k++)
            UMP_CHECK(p->extra && p->extra[k].key && *p->extra[k].key && p->extra[k].text,
                      err, UMP_ERR_INPUT, "%s: patch %s has an incomplete extra entry",
                      path, pn);
    }
    return UMP_OK;
}

static void put_field(sink *s, const pmesh *pm, const fld_field *f, const char *location,
                      int binary, int prec)
{
    static const double none[3] = {0, 0, 0};
    put_header(s, f->ncomp == 1 ? "volScalarField" : "volVectorField", location, f->name,
               binary);
    put_key(s, 0, "dimensions");
    sink_puts(s, "[");
    for (int k = 0; k < 7; k++) {
        if (k)
            sink_puts(s, " ");
        put_num(s, f->dims[k], prec);
    }
    sink_puts(s, "];\n\n\n");
    put_key(s, 0, "internalField");
    put_field_value(s, f->internal ? f->internal : none, f->ncells, f->ncomp, binary, prec);
    sink_puts(s, "\nboundaryField\n{\n");
    for (int i = 0; i < f->npatches; i++) {
        const fld_patch *p = &f->patch[i];
        sink_printf(s, "    %s\n    {\n", pm->patch[i].name);
        put_key(s, 8, "type");
        sink_printf(s, "%s;\n", fld_bc_name(p->type));
        /* OpenFOAM writes a type's own optional keywords (phi of
         * inletOutlet...) right after type, before its value lists */
        for (int k = 0; k < p->nextra; k++) {
            put_key(s, 8, p->extra[k].key);
            /* a sub-dictionary ("{ k v; }", e.g. uniformValueCoeffs) takes no ';' */
            sink_printf(s, p->extra[k].text[0] == '{' ? "%s\n" : "%s;\n", p->extra[k].text);
        }
        const char *aux = fld_bc_aux_key(p->type);
        if (aux && (p->aux || !bc_aux_optional(p->type))) {
            put_key(s, 8, aux);
            put_field_value(s, p->aux ? p->aux : none, p->n, f->ncomp, binary, prec);
        }
        if (bc_writes_value(p->type)) {
            put_key(s, 8, "value");
            put_field_value(s, p->value ? p->value : none, p->n, f->ncomp, binary, prec);
        }
        sink_puts(s, "    }\n");
    }
    sink_puts(s, "}\n");
    put_footer(s);
}

/* <dir>/<name> (.gz when compressing) in OpenFOAM's way, its contents from
 * put(s, ctx): written, closed (removed again if that fails), then the other
 * variant removed as OpenFOAM does, so readers cannot pick up a stale file
 * (IFstream tries the plain name first). check, if not NULL, runs first
 * with the path (for its messages). */
typedef struct field_job {
    const pmesh *pm;
    const fld_field *f;     /* fio_write_field */
    const double *phi;      /* fio_write_phi */
    const char *location;
    int binary, prec;
} field_job;

static ump_status write_file(const char *dir, const char *name, const fio_format *fmt,
                             void (*put)(sink *, const field_job *), const field_job *job,
                             ump_status (*check)(const char *, const field_job *, ump_err *), ump_err *err)
{
    /* v1912 disables compression for binary output */
    int gz = fmt->compress && !fmt->binary;
    char path[4200], other[4200];
    int n1 = snprintf(path, sizeof path, "%s/%s%s", dir, name, gz ? ".gz" : "");
    int n2 = snprintf(other, sizeof other, "%s/%s%s", dir, name, gz ? "" : ".gz");
    UMP_CHECK(n1 > 0 && n2 > 0 && (size_t)n1 < sizeof path && (size_t)n2 < sizeof other,
              err, UMP_ERR_INPUT, "%s: path too long", dir);
    if (check)
        UMP_CALL(check(path, job, err));
    sink *s = malloc(sizeof *s);
    if (!s)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", path);
    if (sink_open(s, path, gz) != 0) {
        int e = errno;
        free(s);
        return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot open for writing: %s", path, strerror(e));
    }
    put(s, job);
    errno = 0;
    if (sink_close(s) != 0) {
        int e = errno;
        free(s);
        remove(path);
        return UMP_FAIL(err, UMP_ERR_IO, "%s: write failed: %s", path, e ? strerror(e) : "short write");
    }
    free(s);
    if (remove(other) != 0 && errno != ENOENT)
        return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot remove stale file: %s", other, strerror(errno));
    return UMP_OK;
}

static ump_status check_job(const char *path, const field_job *j, ump_err *err)
{
    return check_field(path, j->pm, j->f, err);
}

static void put_field_job(sink *s, const field_job *j)
{
    put_field(s, j->pm, j->f, j->location, j->binary, j->prec);
}

ump_status fio_write_field(const char *dir, const char *location, const pmesh *pm,
                           const fld_field *f, const fio_format *fmt, ump_err *err)
{
    static const fio_format def = {0, 6, 0};
    UMP_CHECK(dir && *dir && f && pm, err, UMP_ERR_INPUT, "fio_write_field: missing argument");
    UMP_CHECK(f->name && *f->name && !strchr(f->name, '/'), err, UMP_ERR_INPUT,
              "%s: invalid field name '%s'", dir, f->name ? f->name : "");
    if (!fmt)
        fmt = &def;
    field_job j = {pm, f, NULL, location, fmt->binary, fmt->precision > 0 ? fmt->precision : 6};
    return write_file(dir, f->name, fmt, put_field_job, &j, check_job, err);
}

static void put_phi(sink *s, const field_job *j)
{
    const pmesh *pm = j->pm;
    const double *phi = j->phi;
    put_header(s, "surfaceScalarField", j->location, "phi", j->binary);
    put_key(s, 0, "dimensions");
    sink_puts(s, "[0 3 -1 0 0 0 0];\n");
    put_key(s, 0, "oriented");
    sink_puts(s, "oriented;\n\n\n");
    put_key(s, 0, "internalField");
    put_field_value(s, phi, pm->ninternal, 1, j->binary, j->prec);
    sink_puts(s, "\nboundaryField\n{\n");
    for (int i = 0; i < pm->npatches; i++) {
        const pmesh_patch *pp = &pm->patch[i];
        int empty = pp->kind == PMESH_EMPTY;
        sink_printf(s, "    %s\n    {\n", pp->name);
        put_key(s, 8, "type");
        /* constraint patches carry their own type, as OpenFOAM's phi (a
         * "calculated" symmetryPlane patch is refused when read back) */
        sink_puts(s, empty                                 ? "empty;\n"
                     : pp->kind == PMESH_CYCLIC         ? "cyclic;\n"
                     : pp->kind == PMESH_SYMMETRYPLANE  ? "symmetryPlane;\n"
                     : pp->kind == PMESH_SYMMETRY       ? "symmetry;\n"
                                                        : "calculated;\n");
        put_key(s, 8, "value");
        put_field_value(s, phi + (empty ? 0 : pp->start), empty ? 0 : pp->n, 1, j->binary, j->prec);
        sink_puts(s, "    }\n");
    }
    sink_puts(s, "}\n");
    put_footer(s);
}

ump_status fio_write_phi(const char *dir, const char *location, const pmesh *pm, const double *phi,
                         const fio_format *fmt, ump_err *err)
{
    static const fio_format def = {0, 6, 0};
    UMP_CHECK(dir && *dir && pm && phi, err, UMP_ERR_INPUT, "fio_write_phi: missing argument");
    if (!fmt)
        fmt = &def;
    field_job j = {pm, NULL, phi, location, fmt->binary, fmt->precision > 0 ? fmt->precision : 6};
    return write_file(dir, "phi", fmt, put_phi, &j, NULL, err);
}

ump_status fio_write_text(const char *dir, const char *name, const char *text, size_t len, ump_err *err)
{
    char path[4200];
    int n = snprintf(path, sizeof path, "%s/%s", dir, name);
    UMP_CHECK(n > 0 && (size_t)n < sizeof path, err, UMP_ERR_INPUT, "%s: path too long", dir);
    FILE *fp = fopen(path, "wb");
    if (!fp)
        return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot open for writing: %s", path, strerror(errno));
    int bad = fwrite(text, 1, len, fp) != len;
    bad |= fclose(fp) != 0;
    UMP_CHECK(!bad, err, UMP_ERR_IO, "%s: write failed", path);
    return UMP_OK;
}

/* <dir>/uniform/<object> opened for writing (uniform/ made), its header
 * written (location "<location>/uniform"); path gets the file's path. */
static ump_status uniform_open(const char *dir, const char *location, const char *object, sink **out,
                               char path[4400], ump_err *err)
{
    char udir[4200], loc[4200];
    int n1 = snprintf(udir, sizeof udir, "%s/uniform", dir);
    int n2 = snprintf(path, 4400, "%s/uniform/%s", dir, object);
    int n3 = snprintf(loc, sizeof loc, "%s/uniform", location ? location : "");
    UMP_CHECK(n1 > 0 && n2 > 0 && n3 > 0 && (size_t)n1 < sizeof udir && n2 < 4400 && (size_t)n3 < sizeof loc,
              err, UMP_ERR_INPUT, "%s: path too long", dir);
    UMP_CALL(fio_mkdir_p(udir, err));
    sink *s = malloc(sizeof *s);
    if (!s)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", path);
    if (sink_open(s, path, 0) != 0) {
        int e = errno;
        free(s);
        return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot open for writing: %s", path, strerror(e));
    }
    put_header(s, "dictionary", location ? loc : NULL, object, 0);
    *out = s;
    return UMP_OK;
}

/* The footer, then close; a failed write leaves no partial file. */
static ump_status uniform_close(sink *s, const char *path, ump_err *err)
{
    put_footer(s);
    errno = 0;
    int bad = sink_close(s);
    int e = errno;
    free(s);
    if (bad) {
        remove(path);
        return UMP_FAIL(err, UMP_ERR_IO, "%s: write failed: %s", path, e ? strerror(e) : "short write");
    }
    return UMP_OK;
}

ump_status fio_write_uniform_dict(const char *dir, const char *location, const char *object, const char *body,
                                  ump_err *err)
{
    char path[4400];
    sink *s;
    UMP_CALL(uniform_open(dir, location, object, &s, path, err));
    sink_puts(s, body);
    return uniform_close(s, path, err);
}

ump_status fio_write_uniform_time(const char *dir, const char *location,
                                  double value, const char *name, long index,
                                  double deltaT, double deltaT0,
                                  int write_precision, int time_format,
                                  ump_err *err)
{
    UMP_CHECK(dir && *dir && name, err, UMP_ERR_INPUT,
              "fio_write_uniform_time: missing argument");
    int prec = write_precision > 0 ? write_precision : 6;
    char path[4400];
    sink *s;
    UMP_CALL(uniform_open(dir, location, "time", &s, path, err));
    /* Time::writeTimeDict: the value is a time name with 18 digits in the
     * case's timeFormat; deltaT and deltaT0 use the stream precision */
    put_key(s, 0, "value");
    if (time_format == 1)
        sink_printf(s, "%.18f;\n\n", value);
    else if (time_format == 2)
        sink_printf(s, "%.18e;\n\n", value);
    else
        sink_printf(s, "%.18g;\n\n", value);
    put_key(s, 0, "name");
    sink_printf(s, "\"%s\";\n\n", name);
    put_key(s, 0, "index");
    sink_printf(s, "%ld;\n\n", index);
    put_key(s, 0, "deltaT");
    sink_printf(s, "%.*g;\n\n", prec, deltaT);
    put_key(s, 0, "deltaT0");
    sink_printf(s, "%.*g;\n", prec, deltaT0);
    return uniform_close(s, path, err);
}
