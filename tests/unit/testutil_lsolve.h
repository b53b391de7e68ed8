/* SPDX-License-Identifier: GPL-3.0-or-later
 * testutil_lsolve.h -- a test matrix shared by the unit tests of lsolve
 * and of the coarse level.
 */
#ifndef UMPPM_TESTUTIL_LSOLVE_H
#define UMPPM_TESTUTIL_LSOLVE_H

#include "testutil.h"
#include "umppm/lsolve.h"

/* 5-point Laplacian on an m x m grid with Dirichlet walls, scaled by s
 * (s = 1: SPD, s = -1: negative definite, as the PPE). Optional extra
 * first-order convection conv (nonsymmetric, still diagonally dominant). */
static inline lsolve_mat *tu_grid_laplacian(int m, double s, double conv)
{
    lsolve_trip t;
    ump_err err;
    lsolve_mat *A = NULL;
    assert_int_equal(lsolve_trip_init(&t, m * m, 5 * (size_t)m * m, &err), UMP_OK);
    for (int j = 0; j < m; j++)
        for (int i = 0; i < m; i++) {
            int r = j * m + i;
            assert_int_equal(lsolve_trip_add(&t, r, r, s * (4 + conv), &err), UMP_OK);
            if (i > 0)
                assert_int_equal(lsolve_trip_add(&t, r, r - 1, s * (-1 - conv), &err), UMP_OK);
            if (i < m - 1)
                assert_int_equal(lsolve_trip_add(&t, r, r + 1, -s, &err), UMP_OK);
            if (j > 0)
                assert_int_equal(lsolve_trip_add(&t, r, r - m, -s, &err), UMP_OK);
            if (j < m - 1)
                assert_int_equal(lsolve_trip_add(&t, r, r + m, -s, &err), UMP_OK);
        }
    if (lsolve_trip_to_mat(&t, &A, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    lsolve_trip_free(&t);
    return A;
}

#endif
