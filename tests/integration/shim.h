/* SPDX-License-Identifier: GPL-3.0-or-later
 * shim.h -- what the LD_PRELOAD shims of the integration tests share
 * (killshim.c, editshim.c): one lock, and the next definition of a function
 * a shim hides, looked up on first use.
 *
 * One lock, because umppmFoam writes the fields and the cloud of a time from
 * two threads. Include once, in the shim's only source file, after defining
 * _GNU_SOURCE (RTLD_NEXT).
 */
#ifndef UMPPM_TEST_SHIM_H
#define UMPPM_TEST_SHIM_H

#include <dlfcn.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static pthread_mutex_t shim_lock = PTHREAD_MUTEX_INITIALIZER;

/* Write msg to stderr (async-signal-safe) and abort: the test fails loudly. */
static void shim_die(const char *msg)
{
    ssize_t w = write(2, msg, strlen(msg));
    (void)w;
    abort();
}

/* The next definition of name after this library. */
static void *shim_next(const char *name)
{
    void *p = dlsym(RTLD_NEXT, name);
    if (!p)
        shim_die("shim: dlsym failed\n");
    return p;
}

/* Declares real_<name> of function-pointer type `type` and sets it on first
 * use, under shim_lock (the pointer goes through memcpy: ISO C has no
 * object-to-function pointer conversion). */
#define SHIM_NEXT(type, name) \
    static type real_##name; \
    pthread_mutex_lock(&shim_lock); \
    if (!real_##name) { \
        void *p_ = shim_next(#name); \
        memcpy(&real_##name, &p_, sizeof p_); \
    } \
    pthread_mutex_unlock(&shim_lock);

#endif
