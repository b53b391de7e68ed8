/* SPDX-License-Identifier: GPL-3.0-or-later
 * features.h -- OpenFOAM case features umppmFoam does not implement
 * (module prefix feat_).
 *
 * An OpenFOAM case can ask for much more than umppmFoam solves: source
 * terms (fvOptions, fvConstraints), viscoelastic laminar models, non-
 * Newtonian viscosity, porosity, MRF zones, steady or Crank-Nicolson time
 * schemes, moving meshes, finite-area regions, several phases. Running such
 * a case as if it were icoFoam's gives a wrong answer without a word, so
 * each one is refused by name, before the mesh is read (both by a run and
 * by -checkMesh), with the file, the entry and what to do instead, e.g.
 *
 *   <case>/constant/fvOptions:18: fvOptions are not implemented by
 *   umppmFoam (entry 'momentumSource', type vectorSemiImplicitSource);
 *   remove the file to run without it, or use pimpleFoam
 *
 * Empty fvOptions/fvConstraints/porosityProperties/MRFProperties files
 * (no entries), MRF zones with `active false`, `dynamicFvMesh
 * staticFvMesh`, `transportModel Newtonian`, `laminarModel Stokes` and the
 * ddt schemes Euler and backward are accepted.
 */
#ifndef UMPPM_FEATURES_H
#define UMPPM_FEATURES_H

#include "umppm/ump.h"

#include <stddef.h>

/* Refuse the first unsupported feature of the case at case_dir; tname is
 * the start time directory (its alpha.* fields mean a multiphase case).
 * UMP_ERR_UNSUPPORTED with the message above; UMP_ERR_PARSE/IO when one of
 * the files read is broken. Reads (when present) constant/transportProperties,
 * constant/dynamicMeshDict, constant/turbulenceProperties,
 * constant/momentumTransport, {constant,system}/{fvOptions,fvConstraints},
 * constant/porosityProperties, constant/MRFProperties, system/fvSchemes;
 * looks for system/faSchemes, system/faSolution, constant/faMesh. */
ump_status feat_check_case(const char *case_dir, const char *tname, ump_err *err);

/* The ddt scheme of U in system/fvSchemes (ddt(U), else default) into
 * buf: "Euler" or "backward"; "Euler (no system/fvSchemes)" when the file
 * or its ddtSchemes is absent. Anything else is refused as by
 * feat_check_case. */
/* The same checks for meshlessFoam, whose cases are interFoam's: the
 * phases and alpha fields are its input, so only moving meshes,
 * finite-area regions, turbulence or viscoelastic models and source terms
 * (fvOptions, fvConstraints, porosity, MRF) are refused, naming
 * meshlessFoam and interFoam. */
ump_status feat_check_meshless(const char *case_dir, ump_err *err);
ump_status feat_ddt_scheme(const char *case_dir, char *buf, size_t len, ump_err *err);

#endif
